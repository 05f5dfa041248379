#pragma once
// What the renderers whose vertex shaders place vertices in grid units share (meshes built on
// the CPU, from patterns or warped grids): a fill and a wire program over common/height_texture_surface.frag,
// the height texture that shades them (ShadingHeightTexture), the per-frame uniforms (camera in
// grid units, metres per unit, texture stride and spacing, shading mode) and the wireframe
// overlay. Needs a current GL 4.5 context.
#include <array>
#include <functional>
#include <string_view>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/render/drawing/height_texture.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

class GridMeshShading {
 public:
  // `vertexShader` must declare uClipFromRelative, uCameraGrid, uGridScale and write the
  // outputs height_texture_surface.frag reads; `who` names the renderer in log lines.
  static Result<GridMeshShading> create(const HeightGrid& grid, const char* vertexShader, std::string_view who);

  // Sets the shared uniforms on both programs, the shading on the fill program, and binds the
  // height texture to unit 0; then draws with the fill program and, with settings.wireframe,
  // the wire program over it: `drawWith(program)` issues the renderer's draw calls.
  void draw(const ViewSetup& view, const RenderSettings& settings,
            const std::function<void(const gl::Program&)>& drawWith) const;

  // Both programs, for the renderer's own uniforms.
  std::array<const gl::Program*, 2> programs() const { return {&fill_, &wire_}; }
  const gl::Texture& heights() const { return heights_.texture; }
  int mapStride() const { return heights_.stride; }

 private:
  gl::Program fill_, wire_;
  ShadingHeightTexture heights_;
  double spacingXM_ = 1.0, spacingYM_ = 1.0;
};

}  // namespace tellus
