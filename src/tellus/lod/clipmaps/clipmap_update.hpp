#pragma once
// A toroidal update of one clipmap height texture, built off the render thread: for every level,
// the texels its window gains moving from `from` to `to` (the whole window when the texture holds
// nothing yet), as rectangles cut where the texture wraps, each with its texels (z_f, z_c) ready
// to upload row by row, made with a LevelFilter from the stored levels (clipmap_prefilter.hpp).
// GL-free; the sampler is called from the building thread only.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/lod/clipmaps/clipmap_heights.hpp"
#include "tellus/lod/clipmaps/clipmap_layout.hpp"
#include "tellus/lod/clipmaps/clipmap_prefilter.hpp"

namespace tellus::clipmaps {

struct TexelRect {
  int level = 0;
  glm::ivec2 texel{0};  // first texel in the level's layer
  glm::ivec2 size{0};   // texels
  std::vector<glm::vec2> texels;  // size.x * size.y, row by row: (own height, coarser surface)
};

struct ClipmapUpdate {
  std::vector<glm::ivec2> origins;  // the windows the texture holds once the rects are uploaded
  glm::dvec2 viewer{0.0};           // the viewer they were placed for (full-resolution col, row)
  std::vector<TexelRect> rects;
  std::uint64_t samples = 0;        // texels in all rects
};

// The update that brings a texture holding `from` (null: nothing yet) to the windows
// placeLevels(shape, viewer) places. Its texels equal texelHeights(filteredSampler(stored,
// filter), ...) bit for bit; each rectangle reads the stored samples it needs once.
ClipmapUpdate buildClipmapUpdate(const ClipmapShape& shape, const std::vector<glm::ivec2>* from,
                                 glm::dvec2 viewer, const LevelSampler& stored, const LevelFilter& filter);

}  // namespace tellus::clipmaps
