#include "tellus/export/tiles3d_export.hpp"

#include <algorithm>
#include <atomic>
#include <limits>
#include <mutex>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/export/glb_writer.hpp"
#include "tellus/export/implicit_subtree.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/export/quantized_mesh_tile_builder.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

// Levels a subtree spans (fewer when the whole pyramid is shallower).
constexpr int kSubtreeLevels = 7;

// The implicit tile (level, local x, y) of hemisphere `h`: the scheme's tile (level, h * 2^level + x, y).
fs::path contentPath(int hemisphere, int level, int x, int y) {
  return fs::path(std::to_string(hemisphere)) / "tiles" / std::to_string(level) / std::to_string(x) /
         fmt::format("{}.glb", y);
}
fs::path subtreePath(int hemisphere, int level, int x, int y) {
  return fs::path(std::to_string(hemisphere)) / "subtrees" / std::to_string(level) / std::to_string(x) /
         fmt::format("{}.subtree", y);
}

// How far a tile's skirts hang below its edges, in units of its level's geometric error: as
// Cesium's own terrain (CesiumTerrainProvider: 5 x the level's error). The gap between two
// neighbours' edges is at most the sum of their errors (each edge is within 0.9 of its level's
// error of the same data), so 5 covers neighbours up to two levels apart, as a client's
// screen-space selection puts them.
constexpr double kSkirtDepthInErrors = 5.0;

// The mesh with skirts: along each edge, a strip hanging `depthM` straight down (towards the
// ellipsoid) from the edge's vertices, facing out of the tile, with the edge's normals.
// Where a neighbour of another level meets this tile, the drawn edges differ by up to their
// errors; the skirts close that gap (3D Tiles has no notion of neighbours to stitch).
GeographicTileMesh withSkirts(const GeographicTileMesh& mesh, double depthM) {
  GeographicTileMesh out = mesh;
  constexpr int q = kQuantizedMeshMaxCoordinate;
  glm::dvec3 centroid(0.0);
  for (const glm::dvec3& p : mesh.ecef) centroid += p / double(mesh.ecef.size());
  // Each edge: its vertices, ordered along it.
  const auto edge = [&](auto onEdge, auto along) {
    std::vector<std::uint32_t> vertices;
    for (std::uint32_t k = 0; k < mesh.u.size(); ++k) {
      if (onEdge(k)) vertices.push_back(k);
    }
    std::sort(vertices.begin(), vertices.end(), [&](std::uint32_t a, std::uint32_t b) { return along(a) < along(b); });
    return vertices;
  };
  const auto u = [&](std::uint32_t k) { return mesh.u[k]; };
  const auto v = [&](std::uint32_t k) { return mesh.v[k]; };
  const std::vector<std::uint32_t> edges[4] = {
      edge([&](std::uint32_t k) { return mesh.u[k] == 0; }, v), edge([&](std::uint32_t k) { return mesh.u[k] == q; }, v),
      edge([&](std::uint32_t k) { return mesh.v[k] == 0; }, u), edge([&](std::uint32_t k) { return mesh.v[k] == q; }, u)};
  for (const std::vector<std::uint32_t>& vertices : edges) {
    const auto first = std::uint32_t(out.ecef.size());
    for (const std::uint32_t k : vertices) {
      const double lon = mesh.westDeg + mesh.extentDeg * mesh.u[k] / q;
      const double lat = std::clamp(mesh.southDeg + mesh.extentDeg * mesh.v[k] / q, -90.0, 90.0);
      const float height = float(double(mesh.heightM[k]) - depthM);
      out.u.push_back(mesh.u[k]);
      out.v.push_back(mesh.v[k]);
      out.heightM.push_back(height);
      out.ecef.push_back(wgs84::geodeticToEcef({lat * wgs84::kDegree, lon * wgs84::kDegree, double(height)}));
      out.normals.push_back(mesh.normals[k]);
    }
    for (std::size_t i = 0; i + 1 < vertices.size(); ++i) {
      const std::uint32_t a = vertices[i], b = vertices[i + 1];
      const std::uint32_t a2 = first + std::uint32_t(i), b2 = a2 + 1;
      // Facing out of the tile: away from its centroid.
      const glm::dvec3 facing = glm::cross(out.ecef[b] - out.ecef[a], out.ecef[b2] - out.ecef[a]);
      const bool outward = glm::dot(facing, 0.5 * (out.ecef[a] + out.ecef[b]) - centroid) > 0.0;
      const std::uint32_t quad[2][3] = {{a, b, b2}, {a, b2, a2}};
      for (const auto& triangle : quad) {
        if (outward) {
          out.indices.insert(out.indices.end(), {triangle[0], triangle[1], triangle[2]});
        } else {
          out.indices.insert(out.indices.end(), {triangle[0], triangle[2], triangle[1]});
        }
      }
    }
  }
  return out;
}

// A tile's mesh as a glb: positions relative to its centre, the centre as the node's
// translation, both in glTF's y-up axes (x, z, -y).
Result<std::string> tileGlb(const GeographicTileMesh& mesh, int level, int x, int y, bool quantize) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::dvec3& p : mesh.ecef) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::dvec3 centre = 0.5 * (lo + hi);
  GlbMesh glb;
  glb.name = fmt::format("{}/{}/{}", level, x, y);
  glb.generator = "Tellus " TELLUS_VERSION;
  glb.positions.reserve(3 * mesh.ecef.size());
  glb.normals.reserve(3 * mesh.ecef.size());
  for (std::size_t k = 0; k < mesh.ecef.size(); ++k) {
    const glm::dvec3 p = mesh.ecef[k] - centre;
    const glm::dvec3& n = mesh.normals[k];
    for (const double value : {p.x, p.z, -p.y}) glb.positions.push_back(float(value));
    for (const double value : {n.x, n.z, -n.y}) glb.normals.push_back(float(value));
    glb.texcoords.push_back(float(mesh.u[k]) / float(kQuantizedMeshMaxCoordinate));
    glb.texcoords.push_back(1.0f - float(mesh.v[k]) / float(kQuantizedMeshMaxCoordinate));
  }
  glb.indices = mesh.indices;
  glb.quantize = quantize;
  glb.translation = std::array<double, 3>{centre.x, centre.z, -centre.y};
  glb.extras = {{"tile", fmt::format("level {}, x {}, y {} of the geographic scheme (x from 180 W, y from the "
                                     "south pole)", level, x, y)}};
  return encodeGlb(glb);
}

// The availability of the subtree rooted at (level, x, y) of hemisphere h.
QuadtreeSubtreeAvailability subtreeAvailability(const GeographicPyramid& pyramid, int levels, int hemisphere,
                                                int level, int x, int y) {
  QuadtreeSubtreeAvailability a = emptySubtreeAvailability(levels);
  const auto available = [&](int l, int lx, int ly) {
    return l <= pyramid.maxLevel && pyramid.ranges[std::size_t(l)].contains((hemisphere << l) + lx, ly);
  };
  for (int depth = 0; depth <= levels; ++depth) {
    const int side = 1 << depth;
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        if (!available(level + depth, (x << depth) + i, (y << depth) + j)) continue;
        if (depth < levels) {
          a.tiles[subtreeTileBit(depth, std::uint32_t(i), std::uint32_t(j))] = true;
        } else {
          a.children[std::size_t(quadtreeMortonIndex(std::uint32_t(i), std::uint32_t(j)))] = true;
        }
      }
    }
  }
  return a;
}

nlohmann::json regionJson(double west, double south, double east, double north, double minH, double maxH) {
  return {{"region", {west, south, east, north, minH, maxH}}};
}

std::string tilesetJson(const TileStore& store, const GeographicPyramid& pyramid, int subtreeLevels,
                        double minH, double maxH) {
  const double pi = std::numbers::pi;
  nlohmann::json hemispheres = nlohmann::json::array();
  for (int h = 0; h < 2; ++h) {
    hemispheres.push_back({
        {"boundingVolume", regionJson(h == 0 ? -pi : 0.0, -pi / 2, h == 0 ? 0.0 : pi, pi / 2, minH, maxH)},
        {"geometricError", cesiumGeometricErrorM(0)},
        {"refine", "REPLACE"},
        {"content", {{"uri", fmt::format("{}/tiles/{{level}}/{{x}}/{{y}}.glb", h)}}},
        {"implicitTiling",
         {{"subdivisionScheme", "QUADTREE"},
          {"subtreeLevels", subtreeLevels},
          {"availableLevels", pyramid.maxLevel + 1},
          {"subtrees", {{"uri", fmt::format("{}/subtrees/{{level}}/{{x}}/{{y}}.subtree", h)}}}}}});
  }
  // An empty root misses the whole planet: its error is the Earth's diameter, so that clients
  // refine it from any distance.
  const double rootError = 2.0 * wgs84::kSemiMajorAxisM;
  const nlohmann::json tileset = {
      {"asset",
       {{"version", "1.1"},
        {"generator", "Tellus " TELLUS_VERSION},
        {"extras", {{"source", store.path().filename().string()},
                    {"heights", "metres above the WGS84 ellipsoid"},
                    {"tiling", "Cesium's geographic scheme: hemisphere H, level L, tile X, Y is the "
                               "quantized-mesh tile L, H * 2^L + X, Y"}}}}},
      {"geometricError", rootError},
      {"root",
       {{"boundingVolume", regionJson(-pi, -pi / 2, pi, pi / 2, minH, maxH)},
        {"geometricError", rootError},
        {"refine", "REPLACE"},
        {"children", hemispheres}}}};
  return tileset.dump(1);
}

}  // namespace

FolderOutputKind tiles3dFolderKind() {
  FolderOutputKind kind;
  kind.description = "a 3D Tiles tile set";
  kind.markerName = ".tellus-tileset";
  kind.markerContent = "{\"writer\": \"tellus " TELLUS_VERSION "\", \"format\": \"3d-tiles-1.1\"}\n";
  // tileset.json, H, H/tiles|subtrees, .../L, .../L/X, .../L/X/Y.glb|Y.subtree.
  kind.ownEntry = [](const fs::path& relative) {
    std::vector<std::string> parts;
    for (const fs::path& part : relative) parts.push_back(part.string());
    if (parts.size() == 1 && parts[0] == "tileset.json") return true;
    if (parts.empty() || parts.size() > 5 || (parts[0] != "0" && parts[0] != "1")) return false;
    if (parts.size() == 1) return true;
    if (parts[1] != "tiles" && parts[1] != "subtrees") return false;
    for (std::size_t k = 2; k < parts.size() && k < 4; ++k) {
      if (!isTileNumberName(parts[k])) return false;
    }
    if (parts.size() < 5) return true;
    const std::string suffix = parts[1] == "tiles" ? ".glb" : ".subtree";
    const std::string& last = parts[4];
    return last.size() > suffix.size() && last.ends_with(suffix) &&
           isTileNumberName(last.substr(0, last.size() - suffix.size()));
  };
  return kind;
}

Result<Tiles3dExportReport> exportTiles3d(const TileStore& store, const fs::path& folder,
                                          const Tiles3dExportOptions& options) {
  const FolderOutputKind kind = tiles3dFolderKind();
  if (Status writable = checkFolderOutput(folder, kind); !writable) return writable.error();
  Result<HeightGrid> finest = readStoreLevel(store, 0);
  if (!finest) return finest.error();
  Result<LonLatSampler> level0 = LonLatSampler::create(std::move(finest.value()));
  if (!level0) return makeError("'{}': {}", store.path().string(), level0.error().message);
  Result<GeographicPyramid> planned = planGeographicPyramid(level0.value(), store.path().string(), options.pyramid);
  if (!planned) return planned.error();
  const GeographicPyramid& pyramid = planned.value();
  const int subtreeLevels = std::min(kSubtreeLevels, pyramid.maxLevel + 1);
  // Subtrees: one at every available tile of levels 0, S, 2S...
  std::uint64_t subtreeCount = 0;
  for (int level = 0; level <= pyramid.maxLevel; level += subtreeLevels) {
    subtreeCount += pyramid.ranges[std::size_t(level)].count();
  }
  if (Status fits = checkFilesFit(folder, pyramid.tiles + subtreeCount,
                                  fmt::format("a 3D Tiles set of levels 0..{}", pyramid.maxLevel),
                                  fmt::format("give a smaller --max-level (the store's samples need no more "
                                              "than level {})", pyramid.naturalMaxLevel));
      !fits) {
    return fits.error();
  }
  Result<FolderOutput> output = FolderOutput::begin(folder, kind);
  if (!output) return output.error();
  const fs::path temporary = output->temporary();

  Tiles3dExportReport report;
  report.subtreeLevels = subtreeLevels;
  std::atomic<std::uint64_t> tilesDone{0};
  std::mutex heightsMutex;
  double minH = std::numeric_limits<double>::max(), maxH = -std::numeric_limits<double>::max();
  for (int level = 0; level <= pyramid.maxLevel; ++level) {
    QuantizedMeshTileOptions tileOptions;
    tileOptions.latticeSamples = std::max(options.pyramid.tileSamples, 65);
    tileOptions.geoid = options.geoid;
    tileOptions.background = options.background;
    tileOptions.dataBounds = pyramid.dataBox;
    const GeographicTileRange& range = pyramid.ranges[std::size_t(level)];
    const int columns = range.x1 - range.x0 + 1;
    std::vector<PyramidTileResult> results(range.count());
    std::error_code ec;
    for (int x = range.x0; x <= range.x1; ++x) {
      fs::create_directories(temporary / contentPath(x >> level, level, x - ((x >> level) << level), 0).parent_path(), ec);
      if (ec) return makeError("cannot create a folder in '{}': {}", temporary.string(), ec.message());
    }
    const Status built = forEachPyramidTile(
        pyramid, level,
        [&](int x, int y) -> Status {
          PyramidTileResult& result =
              results[std::size_t(y - range.y0) * std::size_t(columns) + std::size_t(x - range.x0)];
          QuantizedMeshTileOptions meshOptions = tileOptions;
          meshOptions.maxErrorM = pyramid.tileBoundM(level, x, y);
          meshOptions.edgeErrorM = pyramid.edgeBoundsM(level, x, y);
          Result<GeographicTileMesh> mesh = buildGeographicTileMesh(level0.value(), {level, x, y}, meshOptions, result.stats);
          if (!mesh) return mesh.error();
          const GeographicTileMesh skirted =
              withSkirts(mesh.value(), kSkirtDepthInErrors * cesiumGeometricErrorM(level));
          const auto [lowest, highest] = std::minmax_element(skirted.heightM.begin(), skirted.heightM.end());
          {
            // The drawn surface lies within the level's error of the data: below the lowest
            // vertex (a skirt's) by less than that.
            std::lock_guard lock(heightsMutex);
            minH = std::min(minH, double(*lowest) - cesiumGeometricErrorM(level));
            maxH = std::max(maxH, double(*highest));
          }
          Result<std::string> glb = tileGlb(skirted, level, x, y, options.quantize);
          if (!glb) return glb.error();
          result.bytes = glb->size();
          const int hemisphere = x >> level;
          const fs::path path = temporary / contentPath(hemisphere, level, x - (hemisphere << level), y);
          return writeBytesChecked(path, std::as_bytes(std::span(glb.value())), path);
        },
        [&] {
          const std::uint64_t done = ++tilesDone;
          if (options.progress) options.progress(done, pyramid.tiles);
        });
    if (!built) return built.error();
    report.levels.push_back(summarizeLevel(level, results));
    report.tiles += report.levels.back().tiles;
    report.bytes += report.levels.back().bytes;
  }
  // Subtrees.
  for (int level = 0; level <= pyramid.maxLevel; level += subtreeLevels) {
    const GeographicTileRange& range = pyramid.ranges[std::size_t(level)];
    for (int x = range.x0; x <= range.x1; ++x) {
      const int hemisphere = x >> level, localX = x - (hemisphere << level);
      for (int y = range.y0; y <= range.y1; ++y) {
        const std::string bytes =
            encodeSubtree(subtreeAvailability(pyramid, subtreeLevels, hemisphere, level, localX, y));
        const fs::path path = temporary / subtreePath(hemisphere, level, localX, y);
        std::error_code ec;
        fs::create_directories(path.parent_path(), ec);
        if (ec) return makeError("cannot create '{}': {}", path.parent_path().string(), ec.message());
        if (Status s = writeBytesChecked(path, std::as_bytes(std::span(bytes)), path); !s) return s.error();
        ++report.subtrees;
      }
    }
  }
  report.minHeightM = minH;
  report.maxHeightM = maxH;
  const std::string tileset = tilesetJson(store, pyramid, subtreeLevels, minH, maxH);
  const fs::path tilesetPath = temporary / "tileset.json";
  if (Status s = writeBytesChecked(tilesetPath, std::as_bytes(std::span(tileset)), tilesetPath); !s) {
    return s.error();
  }
  if (Status s = output->commit(); !s) return s.error();
  return report;
}

}  // namespace tellus
