#include "tellus/export/gltf_export.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <sstream>

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include <glm/geometric.hpp>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/colour_ramp.hpp"
#include "tellus/core/enu_frame.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/dem/lonlat_image_warp.hpp"
#include "tellus/export/glb_writer.hpp"
#include "tellus/export/greedy_tin.hpp"
#include "tellus/export/terrain_mesh.hpp"

namespace tellus {
namespace fs = std::filesystem;

Result<HeightGrid> readStoreWindow(const TileStore& store, int level, int col0, int row0,
                                   int width, int height) {
  const PyramidLayout& layout = store.layout();
  if (level < 0 || level >= layout.levelCount() || width < 1 || height < 1 || col0 < 0 ||
      row0 < 0 || col0 + width > layout.dataWidthAt(level) ||
      row0 + height > layout.dataHeightAt(level)) {
    return makeError("window {}x{} at ({}, {}) is outside level {} of '{}'", width, height, col0,
                     row0, level, store.path().string());
  }
  const StoreMetadata& m = store.metadata();
  const int stride = PyramidLayout::stride(level);
  HeightGrid grid(width, height);
  grid.spacingXM = m.spacingXM * stride;
  grid.spacingYM = m.spacingYM * stride;
  grid.georef = m.georef;
  if (grid.georef.hasGeoTransform) {
    // Sample c of level L is sample c * stride of level 0 (sample centres kept in place), and
    // the window starts at (col0, row0).
    std::array<double, 6>& gt = grid.georef.geoTransform;
    const double shift = 0.5 - 0.5 * stride;
    gt[0] += shift * (gt[1] + gt[2]);
    gt[3] += shift * (gt[4] + gt[5]);
    for (int i : {1, 2, 4, 5}) gt[std::size_t(i)] *= stride;
    gt[0] += col0 * gt[1] + row0 * gt[2];
    gt[3] += col0 * gt[4] + row0 * gt[5];
  }
  const int n = layout.tileSize();
  std::vector<float> tile(layout.tileShape().sampleCount());
  const int tx0 = col0 / n, tx1 = std::min((col0 + width - 1) / n, layout.tilesX(level) - 1);
  const int ty0 = row0 / n, ty1 = std::min((row0 + height - 1) / n, layout.tilesY(level) - 1);
  for (int ty = ty0; ty <= ty1; ++ty) {
    for (int tx = tx0; tx <= tx1; ++tx) {
      if (Status s = store.readTileMetres({level, tx, ty}, tile); !s) return s.error();
      for (int j = 0; j <= n; ++j) {
        const int row = ty * n + j - row0;
        if (row < 0 || row >= height) continue;
        for (int i = 0; i <= n; ++i) {
          const int col = tx * n + i - col0;
          if (col < 0 || col >= width) continue;
          grid.at(col, row) = tile[std::size_t(j) * std::size_t(n + 1) + std::size_t(i)];
        }
      }
    }
  }
  return grid;
}


Result<GltfExportReport> exportGltf(const TileStore& store, const fs::path& output,
                                    const GltfExportOptions& options) {
  if (!std::isfinite(options.maxErrorM) || options.maxErrorM < 0.0) {
    return makeError("--max-error must be a finite number of metres >= 0, not {}",
                     options.maxErrorM);
  }
  const PyramidLayout& layout = store.layout();
  // The level-0 window of the region (sample centres), clipped to the data.
  double col0 = 0, row0 = 0, col1 = layout.dataWidthAt(0) - 1, row1 = layout.dataHeightAt(0) - 1;
  if (options.region) {
    Result<PixelBox> box = pixelBoxOf(store.metadata().georef, *options.region);
    if (!box) return makeError("'{}': {}", store.path().string(), box.error().message);
    col0 = std::max(col0, std::floor(box->col0));
    row0 = std::max(row0, std::floor(box->row0));
    col1 = std::min(col1, std::ceil(box->col1));
    row1 = std::min(row1, std::ceil(box->row1));
    if (col1 - col0 < 1 || row1 - row0 < 1) {
      return makeError("the region {},{},{},{} covers less than 2 x 2 samples of '{}'",
                       options.region->westDeg, options.region->southDeg,
                       options.region->eastDeg, options.region->northDeg, store.path().string());
    }
  }
  // The finest level whose window fits the budget.
  int level = 0;
  auto windowAt = [&](int l, int& c0, int& r0, int& w, int& h) {
    const int stride = PyramidLayout::stride(l);
    c0 = int(std::floor(col0 / stride));
    r0 = int(std::floor(row0 / stride));
    const int c1 = std::min(int(std::ceil(col1 / stride)), layout.dataWidthAt(l) - 1);
    const int r1 = std::min(int(std::ceil(row1 / stride)), layout.dataHeightAt(l) - 1);
    w = c1 - c0 + 1;
    h = r1 - r0 + 1;
  };
  int c0 = 0, r0 = 0, w = 0, h = 0;
  for (;; ++level) {
    windowAt(level, c0, r0, w, h);
    if (std::uint64_t(w) * std::uint64_t(h) <= options.maxSamples ||
        level + 1 == layout.levelCount()) {
      break;
    }
  }
  if (w < 2 || h < 2) {
    return makeError("the region has {} x {} samples at level {}: at least 2 x 2 are needed", w,
                     h, level);
  }
  if (std::uint64_t(w) * std::uint64_t(h) > options.maxSamples) {
    return makeError("the region has {} x {} samples even at the store's coarsest level {}, more "
                     "than --max-samples {}; give a larger --max-samples or a smaller --region",
                     w, h, level, options.maxSamples);
  }
  Result<HeightGrid> window = readStoreWindow(store, level, c0, r0, w, h);
  if (!window) return window.error();
  const HeightGrid& grid = window.value();

  // Every sample's true position in a local east-north-up frame at the window's centre (on the
  // ellipsoid): longitude and latitude from the store's CRS, the store's height, then ECEF, then
  // ENU. No single ground spacing: the east-west scale follows each sample's latitude, and the
  // Earth's curvature is in the heights (a sample 100 km from the centre lies 785 m lower).
  std::vector<double> lons, lats;
  if (Status s = sampleLonLats(grid, lons, lats); !s) {
    return makeError("'{}': {}", store.path().string(), s.error().message);
  }
  const std::size_t centre = std::size_t(h / 2) * std::size_t(w) + std::size_t(w / 2);
  const EnuFrame frame({lats[centre] * wgs84::kDegree, lons[centre] * wgs84::kDegree, 0.0});
  // Points for the insertion: the four corners first (counter-clockwise from the south-west,
  // with rows counted north), then every other sample; plane coordinates (col, row north).
  const auto sampleAt = [&](int col, int rowNorth) {
    return std::uint32_t((h - 1 - rowNorth) * w + col);  // the window's row 0 is its north
  };
  std::vector<std::uint32_t> sampleOfPoint = {sampleAt(0, 0), sampleAt(w - 1, 0),
                                              sampleAt(w - 1, h - 1), sampleAt(0, h - 1)};
  sampleOfPoint.reserve(std::size_t(w) * std::size_t(h));
  for (int rowNorth = 0; rowNorth < h; ++rowNorth) {
    for (int col = 0; col < w; ++col) {
      const bool corner = (col == 0 || col == w - 1) && (rowNorth == 0 || rowNorth == h - 1);
      if (!corner) sampleOfPoint.push_back(sampleAt(col, rowNorth));
    }
  }
  std::vector<std::int32_t> xs(sampleOfPoint.size()), ys(sampleOfPoint.size());
  std::vector<glm::dvec3> enu(sampleOfPoint.size());
  for (std::size_t p = 0; p < sampleOfPoint.size(); ++p) {
    const std::uint32_t s = sampleOfPoint[p];
    xs[p] = std::int32_t(s % std::uint32_t(w));
    ys[p] = std::int32_t(h - 1) - std::int32_t(s / std::uint32_t(w));
    const float height = grid.heights[s];
    if (!std::isfinite(height)) return makeError("'{}' has a void in the region", store.path().string());
    enu[p] = frame.toEnu(wgs84::geodeticToEcef({lats[s] * wgs84::kDegree, lons[s] * wgs84::kDegree, height}));
  }
  ScatteredTinInput input;
  input.x = xs;
  input.y = ys;
  input.positions = enu;
  input.metresPerUnitX = grid.spacingXM;
  input.metresPerUnitY = grid.spacingYM;
  input.maxErrorM = options.maxErrorM;
  GreedyTin tin = buildScatteredTin(input);
  TerrainMesh mesh;
  mesh.samples = std::move(tin.vertices);  // point indices
  mesh.indices = std::move(tin.triangles);
  mesh.maxErrorM = tin.maxErrorM;
  orderForRendering(mesh);
  const std::vector<std::uint32_t>& indices = mesh.indices;
  const std::vector<std::uint32_t>& points = mesh.samples;

  // glTF frame: x east, y up, z south (glTF's y up, right-handed), metres from the centre.
  const std::size_t count = points.size();
  std::vector<float> positions(3 * count), normals(3 * count, 0.0f);
  std::vector<std::uint8_t> colours;
  std::vector<float> heightOfVertex(count);
  for (std::size_t k = 0; k < count; ++k) {
    const glm::dvec3& e = enu[points[k]];
    const glm::vec3 p(float(e.x), float(e.z), float(-e.y));
    heightOfVertex[k] = grid.heights[sampleOfPoint[points[k]]];
    std::memcpy(&positions[3 * k], &p, sizeof(p));
  }
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::vec3 a = glm::make_vec3(&positions[3 * indices[t]]);
    const glm::vec3 face = glm::cross(glm::make_vec3(&positions[3 * indices[t + 1]]) - a,
                                      glm::make_vec3(&positions[3 * indices[t + 2]]) - a);
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) normals[3 * indices[t + std::size_t(k)] + std::size_t(c)] += face[c];
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    glm::vec3 n = glm::make_vec3(&normals[3 * k]);
    n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 1, 0);
    std::memcpy(&normals[3 * k], &n, sizeof(n));
  }
  if (options.hypsometricColours) {
    const ColourRamp ramp = ColourRamp::hypsometric();
    colours.resize(4 * count);
    for (std::size_t k = 0; k < count; ++k) {
      const glm::vec3 c = ramp.evaluate(heightOfVertex[k]);
      for (int i = 0; i < 3; ++i) {
        colours[4 * k + std::size_t(i)] = std::uint8_t(std::lround(std::clamp(c[i], 0.0f, 1.0f) * 255.0f));
      }
      colours[4 * k + 3] = 255;
    }
  }

  // The draped texture: the image warped onto the window's longitude/latitude box (sample
  // centres), TEXCOORD_0 each vertex's place in that box (s east, t south).
  GlbMesh glbMesh;
  GltfExportReport report;
  if (!options.texture.empty()) {
    double west = 180.0, east = -180.0, south = 90.0, north = -90.0;
    for (std::size_t s = 0; s < lons.size(); ++s) {
      west = std::min(west, lons[s]);
      east = std::max(east, lons[s]);
      south = std::min(south, lats[s]);
      north = std::max(north, lats[s]);
    }
    const double midLat = 0.5 * (south + north) * wgs84::kDegree;
    const double widthM = wgs84::eastWestMetres(midLat, (east - west) * wgs84::kDegree);
    const double heightM = wgs84::northSouthMetres(midLat, (north - south) * wgs84::kDegree);
    // Sides of powers of two (what mipmapping wants; the validator notes others): the longest
    // textureMaxSide rounded down to one, the other the power of two nearest the box's aspect.
    const auto powerOfTwoAtMost = [](int n) { return int(std::bit_floor(unsigned(std::max(n, 1)))); };
    const auto nearestPowerOfTwo = [](double n) {
      return int(std::exp2(std::clamp(std::round(std::log2(std::max(n, 1.0))), 0.0, 14.0)));
    };
    const int longest = powerOfTwoAtMost(options.textureMaxSide);
    LonLatImageRequest request{west, south, east, north, longest, longest};
    if (widthM >= heightM) {
      request.height = std::min(longest, nearestPowerOfTwo(longest * heightM / widthM));
    } else {
      request.width = std::min(longest, nearestPowerOfTwo(longest * widthM / heightM));
    }
    Result<LonLatImage> drape = warpImageToLonLat(options.texture, request);
    if (!drape) return drape.error();
    Result<std::vector<std::uint8_t>> jpeg = encodeJpeg(drape->image, 90);
    if (!jpeg) return jpeg.error();
    glbMesh.textureJpeg = std::move(jpeg.value());
    glbMesh.texcoords.resize(2 * count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t s = sampleOfPoint[points[k]];
      glbMesh.texcoords[2 * k] = float((lons[s] - west) / (east - west));
      glbMesh.texcoords[2 * k + 1] = float((north - lats[s]) / (north - south));
    }
    report.textureWidth = request.width;
    report.textureHeight = request.height;
    report.textureCoverage = drape->coveredFraction;
  }
  glbMesh.name = store.path().stem().string();
  glbMesh.generator = "Tellus " TELLUS_VERSION;
  glbMesh.positions = std::move(positions);
  glbMesh.normals = std::move(normals);
  glbMesh.colours = std::move(colours);
  glbMesh.indices = indices;
  glbMesh.quantize = options.quantize;
  // Where the frame lies: its origin (longitude, latitude, 0 m on the ellipsoid) and the matrix
  // taking the glTF frame to ECEF (column-major, as glTF writes matrices), for GIS and globe
  // users; and the store's CRS.
  const glm::dvec3 east = frame.east(), north = frame.north(), up = frame.up(), o = frame.originEcef();
  // glTF (x, y, z) = (east, up, -north): ECEF = o + x east + y up - z north.
  glbMesh.extras = {
      {"frame", "local east-north-up at the origin on the WGS84 ellipsoid; x east, y up, z south, metres"},
      {"originLonLatHeight", {lons[centre], lats[centre], 0.0}},
      {"ecefFromLocal", {east.x, east.y, east.z, 0.0, up.x, up.y, up.z, 0.0, -north.x, -north.y,
                         -north.z, 0.0, o.x, o.y, o.z, 1.0}},
      {"crs", grid.georef.crsWkt},
      {"crsName", grid.georef.crsName},
      {"heights", "the store's, taken as ellipsoidal"},
      {"storeLevel", level},
      {"maxErrorM", mesh.maxErrorM},
      {"texture", options.texture.empty() ? std::string() : options.texture.filename().string()},
      {"errorMeasure", fmt::format("the largest 3-D distance between a sample of store level {} and "
                                   "the triangle over it", level)}};
  Result<std::string> encoded = encodeGlb(glbMesh);
  if (!encoded) return makeError("'{}': {}", store.path().string(), encoded.error().message);
  const std::string& bytes = encoded.value();
  if (Status s = writeBytesAtomically(output, std::as_bytes(std::span(bytes))); !s) {
    return s.error();
  }
  report.storeLevel = level;
  report.width = w;
  report.height = h;
  report.vertices = count;
  report.triangles = indices.size() / 3;
  report.maxErrorM = mesh.maxErrorM;
  report.bytes = bytes.size();
  report.spacingXM = grid.spacingXM;
  report.spacingYM = grid.spacingYM;
  const auto [minIt, maxIt] = std::minmax_element(grid.heights.begin(), grid.heights.end());
  report.originLonDeg = lons[centre];
  report.originLatDeg = lats[centre];
  report.minHeightM = *minIt;
  report.maxHeightM = *maxIt;
  return report;
}

}  // namespace tellus
