#pragma once
// The spiral globe's projections (seed 001, "Focal point and projections"): where a vertex of
// the abstract spiral (a unit direction and a radius, spiral_mesh.hpp) lands once the mesh is
// centred on the focal point, the point under the camera. GL-free, in float: this is the CPU
// twin of shaders/spiral/spiral_projection.glsl, function for function and name for name, so
// that tests can compare what the GPU computes with it.
//
// The spiral's plane is the azimuthal plane of the focal point on the sphere of ellipsoid
// normals: a vertex with direction (s, c) = (sin azimuth, cos azimuth) and radius r (radians
// of arc) stands for the normal p = cos r f + sin r (s e + c n), f being the focal point's
// normal and e, n its east and north; so density is the same at the poles as anywhere, and
// the seed's "hemisphere rotated to the focal point" is exact rather than a lat/lon offset.
//
// Precision: everything is formed as an offset from the focal point with small quantities
// multiplied together (sin r and 1 - cos r by their series below a quarter radian, never
// differences of Earth-sized numbers), so a vertex metres from the focal point is placed to a
// fraction of a millimetre in float; the renderer adds (focal point - eye), formed in double on
// the CPU, to get eye-relative positions (Tellus's rule for globe renderers).
//
// Projections (the seed's modes; all share the spiral, heights and shading):
//   globe       the WGS84 ellipsoid, heights along the normal (the seed's globe, exact)
//   flat        equirectangular: east = N cos(lat0) dlon, north = M dlat, up = height, on the
//               plane tangent at the focal point (M, N the focal point's radii of curvature)
//   hyperbolic  the focus + context disc: ground distance d drawn at R tanh(d / R) from the
//               focal point on the tangent plane (R the Gaussian radius): near the focal point
//               as the globe, the whole hemisphere inside a disc of radius R
//   dome        the globe turned inside out round the viewer (for a dome display): the surface
//               rises towards the horizon as far as the globe's falls away
#include <optional>
#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace tellus {

enum class SpiralProjection : int { Globe = 0, Flat = 1, Hyperbolic = 2, Dome = 3 };

std::string_view spiralProjectionName(SpiralProjection projection);
// "globe", "flat", "hyperbolic" or "dome"; nullopt otherwise.
std::optional<SpiralProjection> parseSpiralProjection(std::string_view name);

// The focal point as the vertex shader receives it (uniforms, float).
struct SpiralFocus {
  double latRad = 0.0, lonRad = 0.0;  // geodetic, for the CPU side
  glm::vec3 east{0.0f}, north{0.0f}, up{0.0f};  // the focal point's frame, unit ECEF
  float sinLat = 0.0f, cosLat = 1.0f;
  float primeVerticalM = 0.0f;  // N: the radius of curvature east-west, metres
  float meridianM = 0.0f;       // M: the radius of curvature north-south, metres
};
SpiralFocus makeSpiralFocus(double latRad, double lonRad);

// The seed's radius correction: the radius r in [minRadius, maxRadius] moved to
// sqrt((r - min) / (max - min)) * (max - min) + min, which enlarges the central triangles and
// shrinks the outer ones (more even on screen); radii below minRadius (the fan's edge) go to
// minRadius. Without `correct`, r.
float spiralCorrectedRadius(float radius, float minRadius, float maxRadius, bool correct);

// sin r and 1 - cos r for r in [0, pi], accurate relative to their size near 0 (series below a
// quarter radian; GPUs' sin and cos are only accurate to about 1e-6 absolute).
float spiralSinRadius(float radius);
float spiralOneMinusCosRadius(float radius);

// The vertex's latitude and longitude minus the focal point's (radians): (dlat, dlon), dlon in
// (-pi, pi]. Where the height textures are sampled.
glm::vec2 spiralLatLonOffset(glm::vec2 direction, float radius, const SpiralFocus& focus);

// The unit normal p of the vertex (its geodetic up).
glm::vec3 spiralNormal(glm::vec2 direction, float radius, const SpiralFocus& focus);

// The vertex on the WGS84 ellipsoid at `heightM` above it, minus the focal point on the
// ellipsoid (height 0): ECEF metres.
glm::vec3 spiralGlobeOffset(glm::vec2 direction, float radius, float heightM,
                            const SpiralFocus& focus);

// The same for any projection; `latLonOffset` is spiralLatLonOffset's (the flat projection's
// coordinates).
glm::vec3 spiralProjectedOffset(SpiralProjection projection, glm::vec2 direction, float radius,
                                glm::vec2 latLonOffset, float heightM, const SpiralFocus& focus);

}  // namespace tellus
