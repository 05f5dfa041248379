#pragma once
// The renderers' --<family>-* options on the command line, made from their schemas
// (render/registry/renderer_option.hpp) in one loop: render, bench and view take the same ones.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus::cli {

// Adds every family's options to `app`; each given value is set in `settings` (which must
// outlive the parse).
void addRendererOptions(CLI::App* app, RendererSettings& settings);

}  // namespace tellus::cli
