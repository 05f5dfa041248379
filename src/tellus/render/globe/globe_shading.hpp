#pragma once
// What every globe renderer shares to look alike: the sun placed in the sky of the point under
// the eye, the fill shader's lighting, haze and shading-mode uniforms (globe/globe.frag), and
// the atmosphere behind the globe (globe/sky.*). Needs a current GL 4.5 context.
#include <glm/vec3.hpp>

#include "tellus/core/result.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

// The unit ECEF direction to the sun that the settings' azimuth and elevation give in the sky
// of the point under the eye.
glm::vec3 globeSunEcef(const ViewSetup& view, const RenderSettings& settings);

// Sets globe.frag's uniforms: sun, atmosphere, eye, shading mode (not the drape's).
void setGlobeFillUniforms(const gl::Program& fill, const ViewSetup& view,
                          const RenderSettings& settings, const glm::vec3& sunEcef);

class GlobeSky {
 public:
  static Result<GlobeSky> create();
  // Draws the atmosphere and space behind everything (no depth test or write).
  void draw(const ViewSetup& view, const glm::vec3& sunEcef) const;

 private:
  gl::Program program_;
  gl::VertexArray vertices_;  // none: the triangle comes from gl_VertexID
};

}  // namespace tellus
