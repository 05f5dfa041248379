#include "tellus/lod/spiral/spiral_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace tellus {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kMaxVertices = std::size_t(1) << 24;

}  // namespace

Result<SpiralMesh> buildSpiralMesh(const SpiralParams& p) {
  if (!(p.spinToDouble > 0.0) || !(p.baseRadius > 0.0) || !(p.outerRadius > p.baseRadius) ||
      !std::isfinite(p.spinToDouble) || !std::isfinite(p.outerRadius)) {
    return makeError("spiral: need spintodouble > 0 and 0 < baseradius < outer radius, got {}, "
                     "{}, {}", p.spinToDouble, p.baseRadius, p.outerRadius);
  }
  const double perRevolution = 360.0 / p.spinStepDeg;
  const long whole = std::lround(perRevolution);
  if (!(p.spinStepDeg > 0.0) || whole < 3 || std::abs(perRevolution - double(whole)) > 1e-9) {
    return makeError("spiral: spinstep {} degrees does not divide 360 into 3 or more equal steps "
                     "(successive revolutions would not meet: cracks)", p.spinStepDeg);
  }
  const int n = int(whole);
  // Vertices until one reaches the outer radius, plus a revolution so that its step has an
  // outer vertex.
  const double revolutions = p.spinToDouble * std::log2(p.outerRadius / p.baseRadius);
  const double count = std::ceil(revolutions * n) + 1.0 + n;
  if (count > double(kMaxVertices)) {
    return makeError("spiral: {} vertices (more than {}): raise spintodouble's rate or the "
                     "spin step", count, kMaxVertices);
  }
  SpiralMesh mesh;
  mesh.perRevolution = n;
  mesh.vertices.resize(std::size_t(count));
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    // The direction repeats exactly each revolution: spin taken modulo one turn.
    const double turn = double(k % std::size_t(n)) / n;
    const double revolutionsSoFar = double(k) / n;
    mesh.vertices[k] = {float(std::sin(2.0 * kPi * turn)), float(std::cos(2.0 * kPi * turn)),
                        float(p.baseRadius * std::exp2(revolutionsSoFar / p.spinToDouble))};
  }
  const std::size_t last = mesh.vertices.size() - std::size_t(n);  // inner vertices 0 .. last - 1
  mesh.strip.reserve(2 * last);
  for (std::size_t k = 0; k < last; ++k) {
    mesh.strip.push_back(std::uint32_t(k));
    mesh.strip.push_back(std::uint32_t(k + std::size_t(n)));
  }
  return mesh;
}

SpiralRange spiralRange(const SpiralMesh& mesh, double minRadius, double maxRadius) {
  const int n = mesh.perRevolution;
  const int innerCount = int(mesh.strip.size() / 2);  // inner vertices 0 .. innerCount - 1
  // Radii increase with k: the first inner vertex whose outer partner reaches minRadius...
  const auto radiusAt = [&](int k) { return mesh.radiusOf(k); };
  int first = 0;
  while (first < innerCount - 1 && radiusAt(first + n) < minRadius) ++first;
  // ...to the first inner vertex at or beyond maxRadius.
  int end = first + 1;
  while (end < innerCount - 1 && radiusAt(end) < maxRadius) ++end;
  // At least a revolution, so that the fan's edge is all strip (clamped into the mesh).
  end = std::min(std::max(end, first + n), innerCount - 1);
  first = std::min(first, std::max(0, end - n));
  return {first, end - first};
}

std::vector<std::uint32_t> spiralFan(const SpiralMesh& mesh, const SpiralRange& range,
                                     std::uint32_t centre) {
  const auto n = std::uint32_t(mesh.perRevolution);
  const auto first = std::uint32_t(range.first);
  std::vector<std::uint32_t> triangles;
  triangles.reserve(3 * (std::size_t(n) + 1));
  for (std::uint32_t j = 0; j + 1 < n; ++j) {
    triangles.insert(triangles.end(), {centre, first + j, first + j + 1});
  }
  // The last sector (centre, first + n - 1, first + n) contains vertex `first` on its edge
  // from the centre to first + n: split there.
  triangles.insert(triangles.end(), {centre, first + n - 1, first});
  triangles.insert(triangles.end(), {first, first + n - 1, first + n});
  return triangles;
}

}  // namespace tellus
