#pragma once
// Terrain shading parameters and the CPU twin of shaders/common/shading.glsl:shadeTerrain().
// GL-free except applyShading(), which needs a current context.
#include <cstdint>

#include <glm/gtc/type_precision.hpp>
#include <glm/vec3.hpp>

#include "tellus/core/aabb.hpp"
#include "tellus/core/colour_ramp.hpp"

namespace tellus {

namespace gl {
class Program;
}

struct ShadingParams {
  ColourRamp ramp = ColourRamp::hypsometric();
  double sunAzimuthDeg = 315.0;   // compass direction the light comes from (315 = north-west)
  double sunElevationDeg = 30.0;  // above the horizon
  glm::vec3 sunColour{1.05f, 1.0f, 0.92f};
  glm::vec3 skyColour{0.30f, 0.36f, 0.45f};
  glm::vec3 hazeColour{0.55f, 0.66f, 0.80f};  // also the sky behind the terrain (linear)
  float hazeStartM = 0.0f;                    // distance from the camera where haze begins, metres
  float hazeDensity = 0.0f;                   // per metre beyond hazeStartM; see fitHazeToView()
  float slopeRock = 0.6f;

  glm::vec3 sunDirection() const;  // unit vector towards the sun, world frame

  // Aerial perspective fitted to one view of `bounds`: haze starts at the terrain's nearest
  // point and fades its farthest point (at farM) by about 30%.
  void fitHazeToView(const Aabb& bounds, const glm::dvec3& cameraPosition, double farM);
};

// Display-ready sRGB colour in [0, 1] of a terrain point; the shader's exact twin.
glm::vec3 shadeTerrain(const ShadingParams& params, float heightM, const glm::vec3& normal,
                       const glm::vec3& relativePosition);

// The sRGB background colour (the haze colour) as 8-bit values.
glm::u8vec3 skyColour8(const ShadingParams& params);

// Sets the uniforms of shading.glsl on `program`.
void applyShading(const gl::Program& program, const ShadingParams& params);

}  // namespace tellus
