#include "tellus/export/quantized_mesh_tile_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include <glm/geometric.hpp>

#include "tellus/core/geodesy.hpp"
#include "tellus/export/greedy_tin.hpp"
#include "tellus/export/terrain_mesh.hpp"

namespace tellus {

double quantizedMeshTileExtentDeg(int level) { return std::ldexp(180.0, -level); }

namespace {

constexpr int kQ = kQuantizedMeshMaxCoordinate;

// A tile's frame: its boundaries and how a quantized coordinate maps to degrees.
struct TileFrame {
  int level = 0;
  double extentDeg = 0.0, westDeg = 0.0, southDeg = 0.0;
  // Exact boundaries (k * extent in binary) and the degrees of a quantized coordinate.
  double lonOf(int u) const { return u == kQ ? westDeg + extentDeg : westDeg + extentDeg * u / kQ; }
  double latOf(int v) const {
    return std::clamp(v == kQ ? southDeg + extentDeg : southDeg + extentDeg * v / kQ, -90.0, 90.0);
  }
};

// A point a tile may keep: its quantized coordinates and ellipsoidal height.
struct TilePoint {
  int u = 0, v = 0;
  float heightM = 0.0f;
};

glm::dvec3 ecefOf(const TileFrame& frame, int u, int v, double heightM) {
  return wgs84::geodeticToEcef(
      {frame.latOf(v) * wgs84::kDegree, frame.lonOf(u) * wgs84::kDegree, heightM});
}

// What stands for the ground where the source has no data, and the geoid.
struct GroundModel {
  const LonLatSampler* background = nullptr;  // heights above the geoid; sea floors as 0
  const Geoid* geoid = nullptr;
};

// The ground's height where the source has none, above the geoid: the background's (not below
// the sea surface), else 0.
void backgroundHeights(const GroundModel& ground, std::span<const double> lons, std::span<const double> lats,
                       std::span<float> out) {
  if (!ground.background) {
    std::fill(out.begin(), out.end(), 0.0f);
    return;
  }
  ground.background->sample(lons, lats, out);
  for (float& h : out) h = std::isfinite(h) ? std::max(h, 0.0f) : 0.0f;
}

// Heights at points: the source's (outside its data: the background's, else 0) made
// ellipsoidal.
void heightsAt(const LonLatSampler& source, const GroundModel& ground, std::span<const double> lons,
               std::span<const double> lats, std::span<float> out) {
  source.sample(lons, lats, out);
  std::vector<std::size_t> missing;
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (!std::isfinite(out[k])) missing.push_back(k);
  }
  if (!missing.empty()) {
    std::vector<double> missingLons(missing.size()), missingLats(missing.size());
    for (std::size_t i = 0; i < missing.size(); ++i) {
      missingLons[i] = lons[missing[i]];
      missingLats[i] = lats[missing[i]];
    }
    std::vector<float> filled(missing.size());
    backgroundHeights(ground, missingLons, missingLats, filled);
    for (std::size_t i = 0; i < missing.size(); ++i) out[missing[i]] = filled[i];
  }
  if (ground.geoid) {
    for (std::size_t k = 0; k < out.size(); ++k) {
      out[k] = float(ground.geoid->ellipsoidalHeightM(out[k], lats[k], lons[k]));
    }
  }
}

// One tile edge: `alongV` (a west or east edge: u fixed, v running) or not (south or north: v
// fixed). Samples at the source's spacing, then keeps the fewest that leave every sample
// within `boundM` of the chord between kept neighbours (in 3-D, at the same coordinate).
// Deterministic in its inputs: the two tiles sharing an edge keep the same points.
std::vector<TilePoint> simplifiedEdge(const LonLatSampler& source, const GroundModel& ground,
                                      const TileFrame& frame, bool alongV, int fixed,
                                      double boundM, const LonLatBox& dataBounds) {
  // How finely: the source's spacing where the edge meets the data, the lattice's elsewhere
  // (a property of the edge alone, so that both of its tiles decide alike).
  const double margin = 2.0 * source.spacingDeg();
  const double edgeWest = frame.lonOf(alongV ? fixed : 0), edgeEast = frame.lonOf(alongV ? fixed : kQ);
  const double edgeSouth = frame.latOf(alongV ? 0 : fixed), edgeNorth = frame.latOf(alongV ? kQ : fixed);
  const bool boundsGiven = dataBounds.eastDeg >= dataBounds.westDeg;
  const bool meetsData = !boundsGiven || (edgeEast >= dataBounds.westDeg - margin && edgeWest <= dataBounds.eastDeg + margin &&
                                          edgeNorth >= dataBounds.southDeg - margin && edgeSouth <= dataBounds.northDeg + margin);
  const double spacingDeg = meetsData ? std::max(source.spacingDeg(), 1e-9) : frame.extentDeg / 64.0;
  const int steps = int(std::clamp(std::ceil(frame.extentDeg / spacingDeg), 64.0, double(kQ)));
  std::vector<int> q(std::size_t(steps) + 1);
  for (int i = 0; i <= steps; ++i) q[std::size_t(i)] = int(std::lround(double(i) * kQ / steps));
  std::vector<double> lons(q.size()), lats(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    lons[i] = frame.lonOf(alongV ? fixed : q[i]);
    lats[i] = frame.latOf(alongV ? q[i] : fixed);
  }
  std::vector<float> heights(q.size());
  heightsAt(source, ground, lons, lats, heights);
  std::vector<glm::dvec3> ecef(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    ecef[i] = ecefOf(frame, alongV ? fixed : q[i], alongV ? q[i] : fixed, heights[i]);
  }
  std::vector<std::uint8_t> keep(q.size(), 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> segments{{0, q.size() - 1}};
  while (!segments.empty()) {
    const auto [a, b] = segments.back();
    segments.pop_back();
    double worst = boundM;
    std::size_t worstIndex = 0;
    for (std::size_t i = a + 1; i < b; ++i) {
      const double t = double(q[i] - q[a]) / double(q[b] - q[a]);
      const double miss = glm::length(ecef[i] - (ecef[a] + t * (ecef[b] - ecef[a])));
      if (miss > worst) {
        worst = miss;
        worstIndex = i;
      }
    }
    if (worstIndex == 0) continue;
    keep[worstIndex] = 1;
    segments.emplace_back(a, worstIndex);
    segments.emplace_back(worstIndex, b);
  }
  std::vector<TilePoint> kept;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (!keep[i]) continue;
    kept.push_back({alongV ? fixed : q[i], alongV ? q[i] : fixed, heights[i]});
  }
  return kept;
}

// The data's unit normal (ECEF) at each point: central differences `stepDeg` apart in the
// local east-north-up frame.
std::vector<glm::dvec3> dataNormals(const LonLatSampler& source, const GroundModel& ground,
                                    const TileFrame& frame, std::span<const TilePoint> points,
                                    double stepDeg) {
  const std::size_t n = points.size();
  std::vector<double> lons(4 * n), lats(4 * n);
  for (std::size_t k = 0; k < n; ++k) {
    const double lon = frame.lonOf(points[k].u), lat = frame.latOf(points[k].v);
    const double offsets[4][2] = {{-stepDeg, 0}, {stepDeg, 0}, {0, -stepDeg}, {0, stepDeg}};
    for (int j = 0; j < 4; ++j) {
      lons[4 * k + std::size_t(j)] = lon + offsets[j][0];
      lats[4 * k + std::size_t(j)] = std::clamp(lat + offsets[j][1], -90.0, 90.0);
    }
  }
  std::vector<float> heights(4 * n);
  heightsAt(source, ground, lons, lats, heights);
  std::vector<glm::dvec3> normals(n);
  const double stepRad = stepDeg * wgs84::kDegree;
  for (std::size_t k = 0; k < n; ++k) {
    const double latRad = frame.latOf(points[k].v) * wgs84::kDegree;
    const double lonRad = frame.lonOf(points[k].u) * wgs84::kDegree;
    const double dx = std::max(2.0 * wgs84::eastWestMetres(latRad, stepRad), 1e-3);
    const double dy = 2.0 * wgs84::northSouthMetres(latRad, stepRad);
    const double dhdx = (double(heights[4 * k + 1]) - double(heights[4 * k])) / dx;
    const double dhdy = (double(heights[4 * k + 3]) - double(heights[4 * k + 2])) / dy;
    const glm::dvec3 east(-std::sin(lonRad), std::cos(lonRad), 0.0);
    const glm::dvec3 north(-std::sin(latRad) * std::cos(lonRad), -std::sin(latRad) * std::sin(lonRad),
                           std::cos(latRad));
    const glm::dvec3 up(std::cos(latRad) * std::cos(lonRad), std::cos(latRad) * std::sin(lonRad),
                        std::sin(latRad));
    normals[k] = glm::normalize(-dhdx * east - dhdy * north + up);
  }
  return normals;
}

}  // namespace

Result<GeographicTileMesh> buildGeographicTileMesh(const LonLatSampler& source,
                                                   const QuantizedMeshTileAddress& address,
                                                   const QuantizedMeshTileOptions& options,
                                                   QuantizedMeshTileStats& stats) {
  const int level = address.level;
  if (level < 0 || level > 30 || address.x < 0 || address.y < 0 ||
      address.x >= (2 << level) || address.y >= (1 << level)) {
    return makeError("quantized-mesh tile {}/{}/{} is outside the geographic scheme", level,
                     address.x, address.y);
  }
  if (!(options.maxErrorM > 0.0) || !std::isfinite(options.maxErrorM) ||
      options.latticeSamples < 2 || options.latticeSamples > 4097 || options.maxTruthSamples < 1) {
    return makeError("quantized-mesh tile options out of range (bound {} m, lattice {})",
                     options.maxErrorM, options.latticeSamples);
  }
  TileFrame frame;
  frame.level = level;
  frame.extentDeg = quantizedMeshTileExtentDeg(level);
  frame.westDeg = -180.0 + address.x * frame.extentDeg;
  frame.southDeg = -90.0 + address.y * frame.extentDeg;
  const double boundM = options.maxErrorM;
  const GroundModel ground{options.background, options.geoid};

  // Points: the four corners, the simplified edges, then the interior's candidates.
  std::vector<TilePoint> points;
  {
    std::vector<double> lons, lats;
    for (const auto& [u, v] : {std::pair{0, 0}, {kQ, 0}, {kQ, kQ}, {0, kQ}}) {
      lons.push_back(frame.lonOf(u));
      lats.push_back(frame.latOf(v));
      points.push_back({u, v, 0.0f});
    }
    std::vector<float> heights(4);
    heightsAt(source, ground, lons, lats, heights);
    for (std::size_t k = 0; k < 4; ++k) points[k].heightM = heights[k];
  }
  const std::pair<bool, int> edges[4] = {{true, 0}, {true, kQ}, {false, 0}, {false, kQ}};  // W, E, S, N
  for (std::size_t side = 0; side < 4; ++side) {
    const auto [alongV, fixed] = edges[side];
    const double edgeBoundM = options.edgeErrorM[side] > 0.0 ? options.edgeErrorM[side] : boundM;
    for (const TilePoint& p : simplifiedEdge(source, ground, frame, alongV, fixed, edgeBoundM,
                                             options.dataBounds)) {
      const bool corner = (p.u == 0 || p.u == kQ) && (p.v == 0 || p.v == kQ);
      if (!corner) points.push_back(p);
    }
  }
  const auto borderCount = std::uint32_t(points.size());
  std::unordered_set<std::uint32_t> taken;
  const auto key = [](int u, int v) { return std::uint32_t(u) << 16 | std::uint32_t(v); };
  for (const TilePoint& p : points) taken.insert(key(p.u, p.v));

  // The source's samples inside the tile (every one, or every stride-th column and row when a
  // coarse tile holds more than maxTruthSamples).
  const LonLatBox box{frame.westDeg, frame.southDeg, frame.westDeg + frame.extentDeg,
                      std::min(90.0, frame.southDeg + frame.extentDeg)};
  const double inWindow = source.samplesInWindow(box);
  stats.truthStride = 1;
  while (inWindow / (double(stats.truthStride) * stats.truthStride) > double(options.maxTruthSamples)) {
    ++stats.truthStride;
  }
  std::vector<double> sampleLons, sampleLats;
  std::vector<float> sampleHeights;
  source.samplesInside(box, stats.truthStride, sampleLons, sampleLats, sampleHeights);
  for (std::size_t k = 0; k < sampleLons.size(); ++k) {
    const int u = int(std::lround((sampleLons[k] - frame.westDeg) / frame.extentDeg * kQ));
    const int v = int(std::lround((sampleLats[k] - frame.southDeg) / frame.extentDeg * kQ));
    if (u < 1 || u > kQ - 1 || v < 1 || v > kQ - 1 || !taken.insert(key(u, v)).second) continue;
    float h = sampleHeights[k];
    if (options.geoid) h = float(options.geoid->ellipsoidalHeightM(h, sampleLats[k], sampleLons[k]));
    points.push_back({u, v, h});
  }
  // Where the source has no data: the lattice's points, on the background (or the geoid, or
  // the ellipsoid).
  {
    const int n = options.latticeSamples;
    std::vector<double> lons, lats;
    std::vector<std::pair<int, int>> uv;
    for (int j = 1; j + 1 < n; ++j) {
      for (int i = 1; i + 1 < n; ++i) {
        const int u = int(std::lround(double(i) * kQ / (n - 1)));
        const int v = int(std::lround(double(j) * kQ / (n - 1)));
        uv.emplace_back(u, v);
        lons.push_back(frame.lonOf(u));
        lats.push_back(frame.latOf(v));
      }
    }
    std::vector<float> heights(lons.size()), ground0(lons.size());
    source.sample(lons, lats, heights);
    backgroundHeights(ground, lons, lats, ground0);
    for (std::size_t k = 0; k < uv.size(); ++k) {
      if (std::isfinite(heights[k]) || !taken.insert(key(uv[k].first, uv[k].second)).second) continue;
      const double h = ground.geoid ? ground.geoid->ellipsoidalHeightM(ground0[k], lats[k], lons[k]) : ground0[k];
      points.push_back({uv[k].first, uv[k].second, float(h)});
    }
  }
  stats.truthSamples = points.size();

  // The greedy insertion, in the tile's own ECEF frame (centred for precision), at the points'
  // drawn (quantized) positions.
  const glm::dvec3 origin = ecefOf(frame, kQ / 2, kQ / 2, 0.0);
  std::vector<std::int32_t> xs(points.size()), ys(points.size());
  std::vector<glm::dvec3> positions(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    xs[k] = points[k].u;
    ys[k] = points[k].v;
    positions[k] = ecefOf(frame, points[k].u, points[k].v, points[k].heightM) - origin;
  }
  const double midLatRad = std::clamp(frame.southDeg + 0.5 * frame.extentDeg, -89.0, 89.0) * wgs84::kDegree;
  ScatteredTinInput input;
  input.x = xs;
  input.y = ys;
  input.positions = positions;
  input.borderCount = borderCount;
  input.metresPerUnitX = wgs84::eastWestMetres(midLatRad, frame.extentDeg * wgs84::kDegree) / kQ;
  input.metresPerUnitY = wgs84::northSouthMetres(midLatRad, frame.extentDeg * wgs84::kDegree) / kQ;
  input.maxErrorM = boundM;
  GreedyTin tin = buildScatteredTin(input);
  stats.maxErrorM = tin.maxErrorM;

  TerrainMesh mesh;  // vertices as point indices, in first-use order
  mesh.samples = std::move(tin.vertices);
  mesh.indices = std::move(tin.triangles);
  orderForRendering(mesh);

  GeographicTileMesh out;
  out.westDeg = frame.westDeg;
  out.southDeg = frame.southDeg;
  out.extentDeg = frame.extentDeg;
  const std::size_t count = mesh.samples.size();
  std::vector<TilePoint> vertices(count);
  out.u.resize(count);
  out.v.resize(count);
  out.heightM.resize(count);
  out.ecef.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const TilePoint& p = vertices[k] = points[mesh.samples[k]];
    out.u[k] = std::uint16_t(p.u);
    out.v[k] = std::uint16_t(p.v);
    out.heightM[k] = p.heightM;
    out.ecef[k] = ecefOf(frame, p.u, p.v, p.heightM);
  }
  out.indices = std::move(mesh.indices);
  const double spacingDeg = std::max(source.spacingDeg(), frame.extentDeg / 256.0);
  out.normals = dataNormals(source, ground, frame, vertices, spacingDeg);
  stats.triangles = out.indices.size() / 3;
  return out;
}

Result<QuantizedMeshTile> buildQuantizedMeshTile(const LonLatSampler& source,
                                                 const QuantizedMeshTileAddress& address,
                                                 const QuantizedMeshTileOptions& options,
                                                 QuantizedMeshTileStats& stats) {
  Result<GeographicTileMesh> built = buildGeographicTileMesh(source, address, options, stats);
  if (!built) return built.error();
  const GeographicTileMesh& mesh = built.value();
  TileFrame frame;
  frame.level = address.level;
  frame.extentDeg = mesh.extentDeg;
  frame.westDeg = mesh.westDeg;
  frame.southDeg = mesh.southDeg;

  QuantizedMeshTile tile;
  const std::size_t count = mesh.u.size();
  const auto [minIt, maxIt] = std::minmax_element(mesh.heightM.begin(), mesh.heightM.end());
  const float minH = *minIt, maxH = *maxIt;
  tile.u = mesh.u;
  tile.v = mesh.v;
  tile.height.resize(count);
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (std::size_t k = 0; k < count; ++k) {
    tile.height[k] = maxH > minH ? std::uint16_t(std::lround(double(mesh.heightM[k] - minH) /
                                                              double(maxH - minH) * kQ))
                                 : 0;
    if (mesh.u[k] == 0) tile.westEdge.push_back(std::uint32_t(k));
    if (mesh.v[k] == 0) tile.southEdge.push_back(std::uint32_t(k));
    if (mesh.u[k] == kQ) tile.eastEdge.push_back(std::uint32_t(k));
    if (mesh.v[k] == kQ) tile.northEdge.push_back(std::uint32_t(k));
    lo = glm::min(lo, mesh.ecef[k]);
    hi = glm::max(hi, mesh.ecef[k]);
  }
  tile.indices = mesh.indices;
  tile.octNormals.resize(count);
  for (std::size_t k = 0; k < count; ++k) tile.octNormals[k] = octEncodeNormal(mesh.normals[k]);
  const std::vector<glm::dvec3>& ecef = mesh.ecef;

  QuantizedMeshHeader& header = tile.header;
  header.minHeightM = minH;
  header.maxHeightM = maxH;
  header.boundingSphereCentreEcef = 0.5 * (lo + hi);
  header.centreEcef = header.boundingSphereCentreEcef;
  for (const glm::dvec3& p : ecef) {
    header.boundingSphereRadiusM =
        std::max(header.boundingSphereRadiusM, glm::length(p - header.boundingSphereCentreEcef));
  }
  if (!horizonOcclusionPoint(header.centreEcef, ecef, header.horizonOcclusionPoint)) {
    // No finite point hides exactly this tile (it spans too much of the globe): one far out
    // along its centre's direction, hidden only from the far side of the Earth.
    header.horizonOcclusionPoint = glm::normalize(header.centreEcef) * 1e6;
  }
  if (options.waterMask) {
    constexpr std::size_t side = kQuantizedMeshWaterMaskSide;
    tile.waterMask.resize(side * side);
    const double northDeg = std::min(90.0, frame.southDeg + frame.extentDeg);
    for (std::size_t j = 0; j < side; ++j) {
      const double lat = northDeg - (double(j) + 0.5) / side * frame.extentDeg;
      for (std::size_t i = 0; i < side; ++i) {
        const double lon = frame.westDeg + (double(i) + 0.5) / side * frame.extentDeg;
        tile.waterMask[j * side + i] = options.waterMask->at(lon, lat);
      }
    }
    if (std::all_of(tile.waterMask.begin(), tile.waterMask.end(),
                    [&](std::uint8_t v) { return v == tile.waterMask.front(); })) {
      tile.waterMask.resize(1);  // one value for the whole tile
    }
  }
  return tile;
}

}  // namespace tellus
