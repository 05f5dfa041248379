#pragma once
// The viewer panel's widgets for a renderer family's options, made from its schema
// (render/registry/renderer_option.hpp): sliders for numbers, check boxes for flags, combos for
// choices, the files as text. Call between ImGui::NewFrame() and ImGui::Render().
#include <any>

#include "tellus/render/registry/renderer_option.hpp"

namespace tellus {

// Draws a widget per panel option of `schema`, editing `options` (the family's Options).
// True when a change needs the renderer made again: a slider let go after a change, a box
// ticked, a choice made, of an option that is not `live` (live ones the viewer applies to the
// running renderer every frame).
bool drawOptionWidgets(const OptionSchema& schema, std::any& options);

}  // namespace tellus
