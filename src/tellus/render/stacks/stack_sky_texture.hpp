#pragma once
// The column tops of a stack terrain (lod/stacks/stack_sky_heights.hpp) as a texture, so that
// stacks/stacks.frag drapes imagery only where the surface meets the sky (shaders/stacks/
// sky_heights.glsl). Made when a frame first draws with imagery, again after an edit. Needs a
// current GL 4.5 context.
#include "tellus/formats/stacks/material_stack.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"

namespace tellus {

class StackSkyTexture {
 public:
  static constexpr GLuint kUnit = 13;  // sky_heights.glsl: uStackSkyHeights

  // (Re)makes the texture from `finest` (level 0 of the terrain as drawn, edits included).
  void update(const StackTerrain& finest);
  bool empty() const { return texture_.id() == 0; }
  // Binds the texture and sets sky_heights.glsl's uniforms on `program`.
  void apply(const gl::Program& program) const;

 private:
  gl::Texture texture_;
  float worldToTexel_ = 1.0f;    // texels a world metre
  float texelOffset_ = 0.0f;     // texel coordinate of world 0
  float scaleM_ = 1.0f;          // metres of a normalised 1.0
  float spanM_ = 1.0f;           // world metres a texel spans
};

}  // namespace tellus
