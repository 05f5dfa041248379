#pragma once
// The spiral globe's mesh (seed 001, "The Spiral"): one static exponential spiral around a focal
// point, generated once. GL-free; the CPU reference of what the spiral renderer draws.
//
// Vertex k sits at spin = k * spinStep (degrees) and radius baseRadius * 2^(spin / (360 *
// spinToDouble)): the radius doubles every spinToDouble revolutions, so the spiral is wound
// tighter near the focal point and, drawn over any range of radii [r, r * 2^m], shows about the
// same number of triangles (the seed's constant density across zoom levels). Vertices are stored
// as the seed's last version does: (sin spin, cos spin, radius), so a shader scales the unit
// direction by a (corrected) radius without trigonometry.
//
// One triangle strip alternates inner and outer vertices k, k + n (n = 360 / spinStep, the
// vertices a revolution): each step draws the seed's pair of triangles (spin, spin + step,
// spin + 360, spin + step + 360). The outer vertex of one revolution IS the inner vertex of the
// next (the same index), so successive revolutions meet exactly; the seed's rule that spinStep
// divide 360 is what makes n whole, and a step that does not is refused. A drawn range leaves
// a hole around the focal point, filled by a fan over the range's innermost revolution.
#include <cstdint>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

struct SpiralParams {
  double spinToDouble = 1.0;  // revolutions for the radius to double (> 0)
  double baseRadius = 1e-6;   // radius at spin 0 (> 0), in the projection's units
  double spinStepDeg = 10.0;  // spin between vertices: must divide 360 exactly
  double outerRadius = 1.0;   // vertices are generated until one reaches at least this
};

struct SpiralVertex {  // 12 bytes, as the vertex buffer holds it
  float dirX = 0.0f;   // sin(spin): east
  float dirY = 0.0f;   // cos(spin): north
  float radius = 0.0f;
};

struct SpiralMesh {
  int perRevolution = 0;                 // n: vertices (and strip steps) a revolution
  std::vector<SpiralVertex> vertices;    // k = 0, 1, ...: radius increasing with k
  std::vector<std::uint32_t> strip;      // k, k + n, k + 1, k + 1 + n, ... (one triangle strip)
  double radiusOf(int k) const { return double(vertices[std::size_t(k)].radius); }
  int steps() const { return int(strip.size() / 2) - 1; }  // strip steps (two triangles each)
};

// Errors: parameters out of range, a spin step that does not divide 360, or more than about 16
// million vertices.
Result<SpiralMesh> buildSpiralMesh(const SpiralParams& params);

// The part of the strip to draw for radii [minRadius, maxRadius]: strip steps first ..
// first + count - 1 (strip indices 2 * first .. 2 * (first + count) + 1), from the step whose
// outer vertex first reaches minRadius to the first step whose inner vertex reaches maxRadius
// (at least a revolution, clamped to the mesh). The hole inside step `first`'s revolution is the
// fan's.
struct SpiralRange {
  int first = 0;
  int count = 0;
};
SpiralRange spiralRange(const SpiralMesh& mesh, double minRadius, double maxRadius);

// The triangles (three vertex indices each, `centre` for the focal point) that fill the hole
// inside `range`: the innermost revolution's inner edge, vertices first .. first + n, joined to
// the centre. Vertex `first` lies on the segment from the centre to `first + n` (one spin
// apart by a whole revolution), so the last triangle is split there: every edge the fan shares
// with the strip is an edge of both (no T-junction for a displaced vertex to open).
std::vector<std::uint32_t> spiralFan(const SpiralMesh& mesh, const SpiralRange& range,
                                     std::uint32_t centre);

}  // namespace tellus
