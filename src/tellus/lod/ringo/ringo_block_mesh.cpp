#include "tellus/lod/ringo/ringo_block_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <glm/geometric.hpp>

#include "tellus/core/geodesy.hpp"
#include "tellus/lod/globe/globe_mesh.hpp"

namespace tellus {
namespace {

std::uint32_t packComponent(double v) {
  const auto q = std::int32_t(std::lrint(std::clamp(v, -1.0, 1.0) * 511.0));  // to nearest
  return std::uint32_t(q) & 0x3ffu;
}

std::uint32_t packNormal(const glm::dvec3& n) {
  return packComponent(n.x) | (packComponent(n.y) << 10) | (packComponent(n.z) << 20);
}

float unpackComponent(std::uint32_t bits) {
  std::int32_t v = std::int32_t(bits & 0x3ffu);
  if (v >= 512) v -= 1024;
  return std::max(-1.0f, float(v) / 511.0f);
}

}  // namespace

glm::vec3 unpackRingoNormal(std::uint32_t packed) {
  return {unpackComponent(packed), unpackComponent(packed >> 10), unpackComponent(packed >> 20)};
}

RingoBlockMesh buildRingoBlockMesh(const RingoBlock& block, int cells,
                                   std::span<const float> heights, const Geoid* geoid,
                                   const RingoMorphSource* morphFrom) {
  RingoBlockMesh mesh;
  mesh.cells = cells;
  const int side = cells + 1;
  const GeoBounds box = GlobalTiling::bounds(block.key);
  const double step = (box.eastDeg - box.westDeg) / cells;
  // Absolute ECEF of every sample, in double: the latitude's terms once a row, the
  // longitude's once a column (the same bits as geodeticToEcef, a third of its time).
  // The geoid likewise (Geoid::undulationsM: undulationM's values).
  const std::size_t count = std::size_t(side) * std::size_t(side);
  std::vector<double> latDeg(static_cast<std::size_t>(side)), lonDeg(latDeg.size());
  std::vector<double> cosLon(latDeg.size()), sinLon(latDeg.size());
  for (int k = 0; k < side; ++k) {
    latDeg[std::size_t(k)] = box.northDeg - k * step;
    lonDeg[std::size_t(k)] = box.westDeg + k * step;
    cosLon[std::size_t(k)] = std::cos(lonDeg[std::size_t(k)] * wgs84::kDegree);
    sinLon[std::size_t(k)] = std::sin(lonDeg[std::size_t(k)] * wgs84::kDegree);
  }
  std::vector<double> undulation(geoid ? count : 0);
  if (geoid) geoid->undulationsM(latDeg, lonDeg, undulation);
  std::vector<glm::dvec3> ecef(count);
  for (int j = 0; j < side; ++j) {
    const wgs84::LatitudeTerms latitude =
        wgs84::LatitudeTerms::of(latDeg[std::size_t(j)] * wgs84::kDegree);
    for (int i = 0; i < side; ++i) {
      const std::size_t k = std::size_t(j) * std::size_t(side) + std::size_t(i);
      const double ellipsoidal = geoid ? heights[k] + undulation[k] : double(heights[k]);
      ecef[k] = wgs84::geodeticToEcef(latitude, cosLon[std::size_t(i)], sinLon[std::size_t(i)],
                                      ellipsoidal);
    }
  }
  // The morph deltas: one function of a vertex's latitude and longitude (the same bits in every
  // block that holds the vertex), so shared vertices stay shared while they morph.
  if (morphFrom && !morphFrom->empty()) {
    std::vector<double> from(count);
    morphFrom->heightsOnLattice(latDeg, lonDeg, from);
    mesh.morphDeltasM.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      mesh.morphDeltasM[k] = std::isfinite(from[k]) ? float(from[k] - double(heights[k])) : 0.0f;
    }
  }
  const auto deltaAt = [&](int i, int j) {
    return mesh.morphDeltasM.empty()
               ? 0.0f
               : mesh.morphDeltasM[std::size_t(j) * std::size_t(side) + std::size_t(i)];
  };
  const auto at = [&](int i, int j) -> const glm::dvec3& {
    return ecef[std::size_t(std::clamp(j, 0, cells)) * std::size_t(side) +
                std::size_t(std::clamp(i, 0, cells))];
  };
  mesh.vertices.resize(ecef.size());
  mesh.bounds = {glm::dvec3(std::numeric_limits<double>::max()),
                 glm::dvec3(std::numeric_limits<double>::lowest())};
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      RingoVertex& v = mesh.vertices[std::size_t(j) * std::size_t(side) + std::size_t(i)];
      const glm::dvec3& p = at(i, j);
      globe::splitEcef(p, v.whole, v.fraction);
      v.heightM = heights[std::size_t(j) * std::size_t(side) + std::size_t(i)];
      // Odd vertices of the north and south rows and of the west and east columns collapse
      // onto their neighbour towards the edge's start; the others stay.
      v.collapsedWhole = v.whole;
      v.collapsedFraction = v.fraction;
      v.morphDeltaM = v.collapsedMorphDeltaM = deltaAt(i, j);
      if ((j == 0 || j == cells) && i % 2 == 1) {
        v.edges = j == 0 ? kRingoNorth : kRingoSouth;
        globe::splitEcef(at(i - 1, j), v.collapsedWhole, v.collapsedFraction);
        v.collapsedMorphDeltaM = deltaAt(i - 1, j);
      } else if ((i == 0 || i == cells) && j % 2 == 1) {
        v.edges = i == 0 ? kRingoWest : kRingoEast;
        globe::splitEcef(at(i, j - 1), v.collapsedWhole, v.collapsedFraction);
        v.collapsedMorphDeltaM = deltaAt(i, j - 1);
      }
      // The normal from the neighbouring samples (one-sided at the block's border), oriented
      // away from the Earth's centre.
      const glm::dvec3 east = at(i + 1, j) - at(i - 1, j);
      const glm::dvec3 south = at(i, j + 1) - at(i, j - 1);
      glm::dvec3 n = glm::cross(south, east);
      const double length = glm::length(n);
      n = length > 0.0 ? n / length : glm::normalize(p);  // a pole's row: all one point
      if (glm::dot(n, p) < 0.0) n = -n;
      v.normal = packNormal(n);
      mesh.bounds.min = glm::min(mesh.bounds.min, p);
      mesh.bounds.max = glm::max(mesh.bounds.max, p);
      if (v.morphDeltaM != 0.0f) {  // where the morph starts from
        const glm::dvec3 from = ringoVertexEcef(v, 0, 1.0f);
        mesh.bounds.min = glm::min(mesh.bounds.min, from);
        mesh.bounds.max = glm::max(mesh.bounds.max, from);
      }
    }
  }
  return mesh;
}

std::uint32_t ringoCoarserEdges(int dx, int dy, const RingoLayout& layout) {
  const int half = layout.side() / 2;
  const int level = RingoLayout::levelAt(dx, dy);
  const auto coarser = [&](int nx, int ny) {
    return std::abs(nx) <= half && std::abs(ny) <= half && RingoLayout::levelAt(nx, ny) > level;
  };
  std::uint32_t edges = 0;
  if (coarser(dx, dy - 1)) edges |= kRingoNorth;
  if (coarser(dx + 1, dy)) edges |= kRingoEast;
  if (coarser(dx, dy + 1)) edges |= kRingoSouth;
  if (coarser(dx - 1, dy)) edges |= kRingoWest;
  return edges;
}

glm::dvec3 ringoVertexEcef(const RingoVertex& v, std::uint32_t coarserEdges,
                           float morphRemaining) {
  const bool collapse = (v.edges & coarserEdges) != 0;
  const glm::dvec3 ecef = collapse ? glm::dvec3(v.collapsedWhole) + glm::dvec3(v.collapsedFraction)
                                   : glm::dvec3(v.whole) + glm::dvec3(v.fraction);
  const double delta = double(collapse ? v.collapsedMorphDeltaM : v.morphDeltaM);
  if (delta == 0.0 || morphRemaining <= 0.0f) return ecef;
  // Along the ellipsoid normal there (ringo.vert: from the position's ECEF).
  constexpr double a2 = wgs84::kSemiMajorAxisM * wgs84::kSemiMajorAxisM;
  constexpr double b2 = wgs84::kSemiMinorAxisM * wgs84::kSemiMinorAxisM;
  const glm::dvec3 up = glm::normalize(glm::dvec3(ecef.x / a2, ecef.y / a2, ecef.z / b2));
  return ecef + up * (delta * double(morphRemaining));
}

}  // namespace tellus
