#pragma once
// The R32F height texture that shades meshes built on the CPU, from patterns or by warping a
// grid (grid_mesh_shading.hpp): the grid itself, or, beyond the GPU's texture limit, its finest
// pyramid level that fits (its samples `stride` grid samples apart, with that level's geometric
// error). Needs a current GL 4.5 context.
#include <string_view>

#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/texture.hpp"

namespace tellus {

struct ShadingHeightTexture {
  gl::Texture texture;  // row 0 north, linear filtering, clamped
  int stride = 1;       // grid samples per texture sample
  float errorM = 0.0f;  // the texture's own geometric error (0 for the grid itself), metres

  // `who` names the renderer in the log line a coarser level prompts.
  static ShadingHeightTexture create(const HeightGrid& grid, std::string_view who);
};

}  // namespace tellus
