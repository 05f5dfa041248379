#pragma once
// Camera in the world frame (see world_frame.hpp: x east, y north, z up, metres) and the
// matrices derived from it. Positions are double precision; matrices handed to the GPU are
// camera-relative (the view matrix is a pure rotation, the camera sits at the origin).
#include <string_view>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "tellus/core/aabb.hpp"
#include "tellus/core/result.hpp"

namespace tellus {

struct Camera {
  glm::dvec3 position{0.0};  // metres, world frame
  double yawDeg = 0.0;       // compass heading: 0 looks north, 90 east
  double pitchDeg = 0.0;     // above the horizon: negative looks down, -90 straight down
  double fovYDeg = 45.0;     // vertical field of view, degrees, in (0, 180)

  glm::dvec3 forward() const;  // unit view direction
  glm::dvec3 right() const;    // unit, horizontal, to the right of the view direction
  glm::dvec3 up() const;       // unit, completes the right-handed frame
};

// Near and far plane distances in metres.
struct ClipRange {
  double nearM = 1.0;
  double farM = 1000.0;
};

// The cameras Tellus accepts from users (--camera, keyframe files): coordinates within a
// million kilometres of the origin, finite yaw within +-1e6 degrees, pitch in [-90, 90], field
// of view in [0.01, 179] degrees. Anything else is an error that names the value, never a
// matrix of NaNs or a blank image.
inline constexpr double kMaxCameraCoordinateM = 1e9;
inline constexpr double kMaxCameraYawDeg = 1e6;
inline constexpr double kMinCameraFovDeg = 0.01, kMaxCameraFovDeg = 179.0;
Status checkCamera(const Camera& camera);

// Parses "x,y,z,yaw,pitch,fov" (metres and degrees). The error names the offending field.
Result<Camera> parseCamera(std::string_view text);

// Chooses near/far so that the whole box `bounds` lies inside the frustum's depth range:
// far reaches the farthest corner, near is half the distance to the box (at least 0.5 m).
// With the reversed-Z float depth buffer used by the renderers this keeps full precision.
ClipRange chooseClipRange(const Camera& camera, const Aabb& bounds);

// World-to-camera rotation (camera at the origin, looking down -z in eye space).
glm::dmat4 viewRotation(const Camera& camera);

// Reversed-Z perspective projection for glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE):
// depth 1 at the near plane, 0 at the far plane. aspect = width / height.
glm::dmat4 reversedZProjection(double fovYDeg, double aspect, const ClipRange& clip);

// Everything needed to project world points for one frame of size width x height pixels.
struct ViewSetup {
  Camera camera;
  ClipRange clip;
  int width = 0;
  int height = 0;
  glm::dmat4 view;        // viewRotation(camera)
  glm::dmat4 projection;  // reversedZProjection(...)
  // projection * view and its inverse, computed once by create() (per-pixel projections and
  // unprojections use them).
  glm::dmat4 viewProjection{1.0};
  glm::dmat4 inverseViewProjection{1.0};

  static ViewSetup create(const Camera& camera, const Aabb& bounds, int width, int height);

  // Matrix taking camera-relative world offsets (world - camera.position) to clip space.
  const glm::dmat4& relativeViewProjection() const { return viewProjection; }

  // Pixel coordinates (x right, y down, pixel centres at +0.5) and depth of a world point;
  // returns false when the point is behind the camera.
  bool projectToPixel(const glm::dvec3& world, glm::dvec2& pixel, double* depth = nullptr) const;

  // Inverse of projectToPixel: the world point at `pixel` (x right, y down) with reversed-Z
  // depth `depth` in (0, 1] (1 at the near plane) as read back from the depth buffer.
  glm::dvec3 unprojectPixel(const glm::dvec2& pixel, double depth) const;
};

// A camera that frames the whole box obliquely from above: looks north, pitched down
// `pitchDeg`, pulled back until every corner lies inside the central 90% of the image.
Camera overviewCamera(const Aabb& bounds, double aspect, double fovYDeg = 40.0,
                      double pitchDeg = -45.0, double yawDeg = 0.0);

}  // namespace tellus
