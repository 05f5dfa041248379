// tellus_export: the adaptive terrain mesh and its error bound, Cesium's quantized-mesh tiles
// (encoding, decoding, normals, horizon culling), the quantized-mesh tile set of a store and
// the glTF export read back with tinygltf, the 3D Tiles set (implicit subtrees, contents).
#include <cmath>
#include <cstring>
#include <numbers>
#include <set>
#include <fstream>
#include <map>
#include <tuple>
#include <random>

#include <gdal_priv.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/core/enu_frame.hpp"
#include "tellus/core/geodesic.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/dem/gdal_support.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/dem/water_mask.hpp"
#include "tellus/export/gltf_export.hpp"
#include "tellus/export/geographic_pyramid.hpp"
#include "tellus/export/glb_writer.hpp"
#include "tellus/export/greedy_tin.hpp"
#include "tellus/export/implicit_subtree.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/export/quantized_mesh.hpp"
#include "tellus/export/quantized_mesh_tiler.hpp"
#include "tellus/export/terrain_mesh.hpp"
#include "tellus/export/tiles3d_export.hpp"
#include "tellus/tiles/pyramid_builder.hpp"

namespace tellus {
namespace {

namespace fs = std::filesystem;

HeightGrid smallTerrain(int size, double spacingM = 30.0) {
  TerrainParams params;
  params.size = size;
  params.spacingM = spacingM;
  params.reliefM = 1500.0;
  return generateTerrain(params);
}

GridHeights gridOf(const HeightGrid& grid) {
  return {grid.width, grid.height, grid.spacingXM, grid.spacingYM, grid.heights};
}

TEST(TerrainMesh, MeasuresTheErrorOfAKnownMesh) {
  // 3 x 3 samples, all 0 but the centre at 5 m; the two-triangle mesh of the corners misses
  // the centre by 5 m.
  std::vector<float> heights(9, 0.0f);
  heights[4] = 5.0f;
  const GridHeights grid{3, 3, 1.0, 1.0, heights};
  const std::vector<std::uint32_t> samples{0, 2, 8, 6};
  EXPECT_DOUBLE_EQ(measureVerticalError(grid, samples, std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}), 5.0);
  // One triangle leaves half the samples uncovered: a hole.
  EXPECT_TRUE(std::isinf(measureVerticalError(grid, samples, std::vector<std::uint32_t>{0, 1, 2})));
}

TEST(TerrainMesh, StaysWithinEveryBoundAndSimplifiesMoreForLooserOnes) {
  const HeightGrid terrain = smallTerrain(129);
  std::uint64_t previousTriangles = std::numeric_limits<std::uint64_t>::max();
  for (const double bound : {0.0, 0.5, 2.0, 8.0, 32.0}) {
    Result<TerrainMesh> mesh = buildTerrainMesh(gridOf(terrain), {.maxErrorM = bound});
    ASSERT_TRUE(mesh) << mesh.error().message;
    const std::uint64_t triangles = mesh->indices.size() / 3;
    EXPECT_LE(mesh->maxErrorM, bound) << "bound " << bound;
    // Measured again from scratch: the report is the mesh's real error.
    EXPECT_DOUBLE_EQ(measureVerticalError(gridOf(terrain), mesh->samples, mesh->indices),
                     mesh->maxErrorM);
    // A triangulation of the grid: counter-clockwise triangles whose areas add up to the
    // grid's (no overlap, no hole).
    std::int64_t twiceArea = 0;
    for (std::size_t t = 0; t < mesh->indices.size(); t += 3) {
      std::int64_t c[3], r[3];
      for (int k = 0; k < 3; ++k) {
        c[k] = mesh->samples[mesh->indices[t + std::size_t(k)]] % 129;
        r[k] = mesh->samples[mesh->indices[t + std::size_t(k)]] / 129;
      }
      const std::int64_t area = (c[1] - c[0]) * (r[2] - r[0]) - (c[2] - c[0]) * (r[1] - r[0]);
      ASSERT_GT(area, 0) << "triangle " << t / 3;
      twiceArea += area;
    }
    EXPECT_EQ(twiceArea, 2 * 128 * 128);
    if (bound == 0.0) {
      EXPECT_EQ(triangles, 2u * 128u * 128u);
    } else {
      EXPECT_LT(triangles, previousTriangles) << "bound " << bound;
    }
    previousTriangles = triangles;
  }
}

TEST(TerrainMesh, KeepsEveryBorderSampleWhenAsked) {
  const HeightGrid terrain = smallTerrain(65);
  Result<TerrainMesh> mesh = buildTerrainMesh(gridOf(terrain), {.maxErrorM = 50.0, .lockBorder = true});
  ASSERT_TRUE(mesh);
  std::vector<bool> kept(terrain.heights.size(), false);
  for (const std::uint32_t s : mesh->samples) kept[s] = true;
  for (int i = 0; i < 65; ++i) {
    EXPECT_TRUE(kept[std::size_t(i)] && kept[std::size_t(64 * 65 + i)] &&
                kept[std::size_t(i * 65)] && kept[std::size_t(i * 65 + 64)])
        << "border sample " << i;
  }
  EXPECT_LT(mesh->indices.size() / 3, 2u * 64u * 64u / 2u);
}

TEST(TerrainMesh, RefusesNonsense) {
  std::vector<float> heights(4, 0.0f);
  EXPECT_FALSE(buildTerrainMesh({1, 4, 1.0, 1.0, heights}, {}));
  EXPECT_FALSE(buildTerrainMesh({2, 2, 1.0, 1.0, heights}, {.maxErrorM = -1.0}));
  EXPECT_FALSE(buildTerrainMesh({2, 2, 1.0, 1.0, heights}, {.maxErrorM = std::nan("")}));
  heights[2] = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(buildTerrainMesh({2, 2, 1.0, 1.0, heights}, {}));
  EXPECT_FALSE(buildTerrainMesh({3, 2, 1.0, 1.0, heights}, {}));
}

QuantizedMeshTile randomTile(std::size_t vertices, std::mt19937& random) {
  QuantizedMeshTile tile;
  std::uniform_int_distribution<int> coordinate(0, kQuantizedMeshMaxCoordinate);
  for (std::size_t i = 0; i < vertices; ++i) {
    tile.u.push_back(std::uint16_t(coordinate(random)));
    tile.v.push_back(std::uint16_t(coordinate(random)));
    tile.height.push_back(std::uint16_t(coordinate(random)));
    tile.octNormals.push_back({std::uint8_t(random() & 255), std::uint8_t(random() & 255)});
  }
  // Triangles that introduce vertices in order (high-water mark), then reuse random ones.
  std::uint32_t next = 0;
  while (next < vertices) {
    for (int k = 0; k < 3; ++k) {
      tile.indices.push_back(next < vertices && (k == 0 || random() % 2) ? next++
                                                                         : std::uint32_t(random() % std::max<std::uint32_t>(next, 1)));
    }
  }
  tile.westEdge = {0, 1};
  tile.southEdge = {2};
  tile.northEdge = {std::uint32_t(vertices - 1)};
  tile.header.centreEcef = {1.5e6, 4.5e6, 3.9e6};
  tile.header.minHeightM = -12.5f;
  tile.header.maxHeightM = 1915.0f;
  tile.header.boundingSphereCentreEcef = {1.4e6, 4.4e6, 3.8e6};
  tile.header.boundingSphereRadiusM = 12345.5;
  tile.header.horizonOcclusionPoint = {0.2, 0.7, 0.65};
  return tile;
}

void expectSameTile(const QuantizedMeshTile& a, const QuantizedMeshTile& b) {
  EXPECT_EQ(a.u, b.u);
  EXPECT_EQ(a.v, b.v);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.westEdge, b.westEdge);
  EXPECT_EQ(a.southEdge, b.southEdge);
  EXPECT_EQ(a.eastEdge, b.eastEdge);
  EXPECT_EQ(a.northEdge, b.northEdge);
  EXPECT_EQ(a.octNormals, b.octNormals);
  EXPECT_EQ(a.header.centreEcef, b.header.centreEcef);
  EXPECT_EQ(a.header.minHeightM, b.header.minHeightM);
  EXPECT_EQ(a.header.maxHeightM, b.header.maxHeightM);
  EXPECT_EQ(a.header.boundingSphereRadiusM, b.header.boundingSphereRadiusM);
  EXPECT_EQ(a.header.horizonOcclusionPoint, b.header.horizonOcclusionPoint);
}

TEST(QuantizedMesh, RoundTripsWith16And32BitIndices) {
  std::mt19937 random(7);
  for (const std::size_t vertices : {std::size_t(3), std::size_t(500), std::size_t(70000)}) {
    const QuantizedMeshTile tile = randomTile(vertices, random);
    Result<std::vector<std::byte>> bytes = encodeQuantizedMesh(tile);
    ASSERT_TRUE(bytes) << bytes.error().message;
    // Header, vertex count, three uint16 arrays: the layout the format fixes.
    EXPECT_GE(bytes->size(), 88 + 4 + 6 * vertices);
    Result<QuantizedMeshTile> decoded = decodeQuantizedMesh(bytes.value(), "test tile");
    ASSERT_TRUE(decoded) << decoded.error().message;
    expectSameTile(tile, decoded.value());
  }
}

// The watermask extension: one byte for a tile all land or all water, 256 x 256 otherwise;
// other sizes are refused both ways.
TEST(QuantizedMesh, WaterMasksRoundTripAndOddSizesAreRefused) {
  std::mt19937 random(11);
  QuantizedMeshTile tile = randomTile(50, random);
  for (const std::size_t size : {std::size_t(1), std::size_t(65536)}) {
    tile.waterMask.assign(size, 0);
    for (std::size_t k = 0; k < size; ++k) tile.waterMask[k] = std::uint8_t((k * 7) % 256);
    Result<std::vector<std::byte>> bytes = encodeQuantizedMesh(tile);
    ASSERT_TRUE(bytes) << bytes.error().message;
    Result<QuantizedMeshTile> decoded = decodeQuantizedMesh(bytes.value(), "water tile");
    ASSERT_TRUE(decoded) << decoded.error().message;
    EXPECT_EQ(decoded->waterMask, tile.waterMask) << size;
    EXPECT_EQ(decoded->octNormals.size(), tile.octNormals.size());
  }
  tile.waterMask.assign(2, 255);
  EXPECT_FALSE(encodeQuantizedMesh(tile));
  // A 2-byte mask written by hand after a valid tile is refused by the reader.
  tile.waterMask.clear();
  std::vector<std::byte> bytes = encodeQuantizedMesh(tile).value();
  for (const int b : {2, 2, 0, 0, 0, 255, 255}) bytes.push_back(std::byte(b));
  Result<QuantizedMeshTile> odd = decodeQuantizedMesh(bytes, "odd tile");
  ASSERT_FALSE(odd);
  EXPECT_NE(odd.error().message.find("water mask"), std::string::npos) << odd.error().message;
}

// The metadata extension: a uint32 length and the JSON text, after the other extensions; a text
// longer than its extension is refused.
TEST(QuantizedMesh, MetadataRoundTripsAndAnOverlongTextIsRefused) {
  std::mt19937 random(13);
  QuantizedMeshTile tile = randomTile(40, random);
  tile.waterMask = {255};
  tile.metadataJson = R"({"available":[[{"startX":0,"startY":0,"endX":1,"endY":1}]]})";
  Result<std::vector<std::byte>> bytes = encodeQuantizedMesh(tile);
  ASSERT_TRUE(bytes) << bytes.error().message;
  Result<QuantizedMeshTile> decoded = decodeQuantizedMesh(bytes.value(), "metadata tile");
  ASSERT_TRUE(decoded) << decoded.error().message;
  EXPECT_EQ(decoded->metadataJson, tile.metadataJson);
  EXPECT_EQ(decoded->waterMask, tile.waterMask);
  expectSameTile(tile, decoded.value());
  // The text's length (the extension's last 4 + N bytes) raised past the extension's end.
  std::vector<std::byte> overlong = bytes.value();
  const std::size_t textLengthAt = overlong.size() - tile.metadataJson.size() - 4;
  overlong[textLengthAt] = std::byte(std::uint8_t(tile.metadataJson.size() + 1));
  Result<QuantizedMeshTile> refused = decodeQuantizedMesh(overlong, "overlong tile");
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("metadata extension"), std::string::npos) << refused.error().message;
}

// BlueMarbleWater.jpg as a water mask: the open Pacific is water, the Sahara land, the
// antimeridian wraps; a colour image is refused.
TEST(WaterMask, BlueMarbleWaterIsWaterAtSeaAndLandInTheSahara) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<WaterMask> mask = WaterMask::load(data / "bluemarble8k-global/BlueMarbleWater.jpg");
  ASSERT_TRUE(mask) << mask.error().message;
  EXPECT_EQ(mask->bounds().width, 8192);
  EXPECT_GT(mask->at(-150.0, 0.0), 200);  // the Pacific
  EXPECT_GT(mask->at(180.0, 0.0), 200);   // on the antimeridian
  EXPECT_EQ(mask->at(-180.0, 0.0), mask->at(180.0, 0.0));
  EXPECT_LT(mask->at(15.0, 23.0), 50);    // the Sahara
  EXPECT_LT(mask->at(127.7, 35.3), 50);   // Jirisan
  Result<WaterMask> colour = WaterMask::load(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg");
  ASSERT_FALSE(colour);
  EXPECT_NE(colour.error().message.find("3 bands"), std::string::npos) << colour.error().message;
}

TEST(QuantizedMesh, TruncatedOrCorruptTilesAreErrorsNotCrashes) {
  std::mt19937 random(3);
  const QuantizedMeshTile tile = randomTile(40, random);
  const std::vector<std::byte> bytes = encodeQuantizedMesh(tile).value();
  for (std::size_t length = 0; length < bytes.size(); ++length) {
    Result<QuantizedMeshTile> decoded =
        decodeQuantizedMesh(std::span(bytes).first(length), "cut tile");
    // A cut inside the extension block can leave a shorter, valid tile only at its start.
    if (decoded) {
      EXPECT_LT(length, bytes.size());
    }
  }
  std::vector<std::byte> corrupt = bytes;
  corrupt[88 + 4 + 6 * 40 + 4] = std::byte{0xff};  // the first index code: above the mark
  EXPECT_FALSE(decodeQuantizedMesh(corrupt, "corrupt tile"));
  QuantizedMeshTile outOfOrder = tile;
  outOfOrder.indices[0] = 5;
  EXPECT_FALSE(encodeQuantizedMesh(outOfOrder));
}

TEST(QuantizedMesh, OctNormalsRoundTripWithinOneDegree) {
  std::mt19937 random(11);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(gauss(random), gauss(random), gauss(random)));
    const glm::dvec3 back = octDecodeNormal(octEncodeNormal(n));
    EXPECT_GT(glm::dot(n, back), std::cos(1.0 * wgs84::kDegree)) << n.x << " " << n.y << " " << n.z;
  }
}

// Cesium's EllipsoidalOccluder.isScaledSpacePointVisible.
bool visibleFrom(const glm::dvec3& cameraScaled, const glm::dvec3& pointScaled) {
  const double vhMagnitudeSquared = glm::dot(cameraScaled, cameraScaled) - 1.0;
  const glm::dvec3 vt = pointScaled - cameraScaled;
  const double vtDotVc = -glm::dot(vt, cameraScaled);
  const bool occluded = vhMagnitudeSquared < 0.0
                            ? vtDotVc > 0.0
                            : vtDotVc > vhMagnitudeSquared &&
                                  vtDotVc * vtDotVc / glm::dot(vt, vt) > vhMagnitudeSquared;
  return !occluded;
}

glm::dvec3 scaled(const glm::dvec3& ecef) {
  return {ecef.x / wgs84::kSemiMajorAxisM, ecef.y / wgs84::kSemiMajorAxisM,
          ecef.z / wgs84::kSemiMinorAxisM};
}

TEST(QuantizedMesh, HorizonPointIsHiddenOnlyWhenTheTileIs) {
  // A 0.5-degree tile over Korea with 2 km of relief.
  std::vector<glm::dvec3> points;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 8; ++j) {
      points.push_back(wgs84::geodeticToEcef({(36.0 + j / 16.0) * wgs84::kDegree,
                                              (127.0 + i / 16.0) * wgs84::kDegree,
                                              2000.0 * ((i * 7 + j * 3) % 5) / 4.0}));
    }
  }
  const glm::dvec3 centre = wgs84::geodeticToEcef({36.25 * wgs84::kDegree, 127.25 * wgs84::kDegree, 1000.0});
  glm::dvec3 point;
  ASSERT_TRUE(horizonOcclusionPoint(centre, points, point));
  EXPECT_GE(glm::length(point), 1.0);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> lat(-90.0, 90.0), lon(-180.0, 180.0), altitude(10.0, 2e7);
  int hidden = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const glm::dvec3 camera = scaled(wgs84::geodeticToEcef(
        {lat(random) * wgs84::kDegree, lon(random) * wgs84::kDegree, altitude(random)}));
    if (visibleFrom(camera, point)) continue;
    ++hidden;
    for (const glm::dvec3& p : points) {
      ASSERT_FALSE(visibleFrom(camera, scaled(p))) << "a vertex is visible behind the point";
    }
  }
  EXPECT_GT(hidden, 1000);  // the test saw many occluded views
  // Half the globe has no such point.
  std::vector<glm::dvec3> hemisphere{wgs84::geodeticToEcef({0.0, -100.0 * wgs84::kDegree, 0.0}),
                                     wgs84::geodeticToEcef({0.0, 100.0 * wgs84::kDegree, 0.0})};
  EXPECT_FALSE(horizonOcclusionPoint(wgs84::geodeticToEcef({0.0, 0.0, 0.0}), hemisphere, point));
}

double koreaLikeRelief(double latDeg, double lonDeg) {
  return 600.0 + 500.0 * std::sin(latDeg * 40.0) * std::cos(lonDeg * 30.0) +
         80.0 * std::sin(latDeg * 310.0 + lonDeg * 170.0);
}

// A WGS84 store of 0.2 x 0.2 degrees at 1/300 degree (61 x 61 samples), built once per run
// in a folder of its own (each test's fresh folder is removed by the next).
const fs::path& latLonStore() {
  static const fs::path store = [] {
    const fs::path dir = test::processFixtureDir("export-latlon-store");
    const fs::path tif = test::writeLatLonTerrain(dir / "latlon.tif", 127.3, 36.4, 1.0 / 300.0,
                                                  61, 61, koreaLikeRelief);
    BuildOptions build;
    build.tileSize = 16;
    Result<BuildReport> built = buildPyramid({tif}, dir / "latlon.tstore", build);
    if (!built) throw std::runtime_error(built.error().message);
    return dir / "latlon.tstore";
  }();
  return store;
}

TEST(QuantizedMeshTiler, WritesAValidTileSetWithinCesiumsErrors) {
  std::shared_ptr<TileStore> store = TileStore::open(latLonStore()).value();
  const fs::path folder = test::freshTestDir() / "tiles";
  QuantizedMeshExportOptions options;
  options.tileSamples = 17;
  Result<QuantizedMeshExportReport> report = exportQuantizedMesh(*store, folder, options);
  ASSERT_TRUE(report) << report.error().message;
  // Lattice spacing 180 / 2^L / 16 reaches the store's 1/300 degree at level 12.
  ASSERT_EQ(report->levels.size(), 13u);
  for (const QuantizedMeshLevelReport& level : report->levels) {
    EXPECT_LE(level.maxErrorM, level.geometricErrorM) << "level " << level.level;
    EXPECT_DOUBLE_EQ(level.geometricErrorM, cesiumGeometricErrorM(level.level));
  }
  EXPECT_NEAR(cesiumGeometricErrorM(0), 77067.34, 0.01);

  std::ifstream layerFile(folder / "layer.json");
  const nlohmann::json layer = nlohmann::json::parse(layerFile);
  EXPECT_EQ(layer["format"], "quantized-mesh-1.0");
  EXPECT_EQ(layer["projection"], "EPSG:4326");
  ASSERT_EQ(layer["available"].size(), 13u);

  // Every available tile decodes; its vertices lie on the store's finest heights (source
  // samples moved to their quantized positions, or edge points between samples).
  const LonLatSampler finest = LonLatSampler::create(readStoreLevel(*store, 0).value()).value();
  const LonLatSampler* sampler = &finest;
  std::uint64_t tiles = 0;
  for (std::size_t level = 0; level < layer["available"].size(); ++level) {
    EXPECT_EQ(report->levels[level].truthStride, 1);
    // The samples inside; coarse levels' quanta (180 / 2^L / 32767 degrees) hold several.
    if (level >= 4) {
      EXPECT_GE(report->levels[level].truthSamples, 59u * 59u) << level;
    }
    const nlohmann::json range = layer["available"][level][0];
    const double extent = 180.0 / double(1 << level);
    for (int x = range["startX"]; x <= int(range["endX"]); ++x) {
      for (int y = range["startY"]; y <= int(range["endY"]); ++y) {
        const fs::path file = folder / std::to_string(level) / std::to_string(x) / (std::to_string(y) + ".terrain");
        const std::string bytes = test::readFileBytes(file);
        Result<QuantizedMeshTile> tile = decodeQuantizedMesh(std::as_bytes(std::span(bytes)), file.string());
        ASSERT_TRUE(tile) << tile.error().message;
        ++tiles;
        const QuantizedMeshHeader& h = tile->header;
        const double heightStep = (h.maxHeightM - h.minHeightM) / 32767.0;
        for (std::size_t k = 0; k < tile->u.size(); ++k) {
          const double lon = -180.0 + (x + tile->u[k] / 32767.0) * extent;
          const double lat = -90.0 + (y + tile->v[k] / 32767.0) * extent;
          const double height = h.minHeightM + tile->height[k] * heightStep;
          // A point between samples (edges, the lattice where there is no data) has the
          // data's height there; a source sample moved to its quantized position (half a
          // quantum each way at most) has its own.
          float between = 0.0f;
          sampler->sample(std::span(&lon, 1), std::span(&lat, 1), std::span(&between, 1));
          if (std::isnan(between)) between = 0.0f;
          double nearest = std::abs(height - between);
          const HeightGrid& g = sampler->grid();
          const auto& gt = g.georef.geoTransform;
          const double quantum = extent / 32767.0;
          const double col = (lon - gt[0]) / gt[1] - 0.5, row = (lat - gt[3]) / gt[5] - 0.5;
          const double reachCols = 0.5 * quantum / std::abs(gt[1]) + 1e-6;
          const double reachRows = 0.5 * quantum / std::abs(gt[5]) + 1e-6;
          for (int r = int(std::ceil(row - reachRows)); r <= int(std::floor(row + reachRows)); ++r) {
            for (int c = int(std::ceil(col - reachCols)); c <= int(std::floor(col + reachCols)); ++c) {
              if (r >= 0 && c >= 0 && r < g.height && c < g.width) {
                nearest = std::min(nearest, std::abs(height - double(g.at(c, r))));
              }
            }
          }
          ASSERT_LE(nearest, heightStep + 0.01) << file << " vertex " << k;
          const glm::dvec3 ecef = wgs84::geodeticToEcef({lat * wgs84::kDegree, lon * wgs84::kDegree, height});
          ASSERT_LE(glm::length(ecef - h.boundingSphereCentreEcef), h.boundingSphereRadiusM + 1.0);
        }
        for (const std::uint32_t k : tile->westEdge) ASSERT_EQ(tile->u[k], 0);
        for (const std::uint32_t k : tile->eastEdge) ASSERT_EQ(tile->u[k], 32767);
        for (const std::uint32_t k : tile->southEdge) ASSERT_EQ(tile->v[k], 0);
        for (const std::uint32_t k : tile->northEdge) ASSERT_EQ(tile->v[k], 32767);
        EXPECT_GE(tile->westEdge.size(), 2u);  // at least the corners
        EXPECT_EQ(tile->octNormals.size(), tile->u.size());
      }
    }
  }
  EXPECT_EQ(tiles, report->tiles);
}

// Points of a sphere's patch as scattered points: the flat triangles between vertices sag
// below the sphere, which only a 3-D error sees.
struct SpherePatch {
  std::vector<std::int32_t> x, y;
  std::vector<glm::dvec3> positions;
  std::uint32_t borderCount = 4;
};

SpherePatch spherePatch(int side, double extentRad, double radiusM) {
  SpherePatch p;
  auto add = [&](int i, int j) {
    p.x.push_back(i);
    p.y.push_back(j);
    const double lon = extentRad * (double(i) / (side - 1) - 0.5), lat = extentRad * (double(j) / (side - 1) - 0.5);
    p.positions.push_back(radiusM * glm::dvec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)));
  };
  const int last = side - 1;
  add(0, 0);
  add(last, 0);
  add(last, last);
  add(0, last);
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const bool corner = (i == 0 || i == last) && (j == 0 || j == last);
      if (!corner) add(i, j);
    }
  }
  return p;
}

// The largest distance from any point to the mesh's triangle over it, at the same plane
// coordinates, measured here by brute force over every triangle.
double worstMiss(const SpherePatch& p, const GreedyTin& tin) {
  double worst = 0.0;
  std::vector<std::uint8_t> covered(p.x.size(), 0);
  for (std::size_t t = 0; t < tin.triangles.size(); t += 3) {
    const std::uint32_t a = tin.vertices[tin.triangles[t]], b = tin.vertices[tin.triangles[t + 1]],
                        c = tin.vertices[tin.triangles[t + 2]];
    const double area = double(p.x[b] - p.x[a]) * (p.y[c] - p.y[a]) - double(p.x[c] - p.x[a]) * (p.y[b] - p.y[a]);
    EXPECT_GT(area, 0.0);  // counter-clockwise
    for (std::size_t k = 0; k < p.x.size(); ++k) {
      const double wa = (double(p.x[b] - p.x[k]) * (p.y[c] - p.y[k]) - double(p.x[c] - p.x[k]) * (p.y[b] - p.y[k])) / area;
      const double wb = (double(p.x[c] - p.x[k]) * (p.y[a] - p.y[k]) - double(p.x[a] - p.x[k]) * (p.y[c] - p.y[k])) / area;
      const double wc = 1.0 - wa - wb;
      if (wa < 0 || wb < 0 || wc < -1e-12) continue;
      covered[k] = 1;
      worst = std::max(worst, glm::length(p.positions[k] - (wa * p.positions[a] + wb * p.positions[b] + wc * p.positions[c])));
    }
  }
  for (const std::uint8_t c : covered) EXPECT_EQ(c, 1);
  return worst;
}

TEST(ScatteredTin, KeepsTheCurvedSurfaceWithinTheBoundIn3D) {
  // 60 degrees of a 6,371 km sphere on 33 x 33 points: the two corner triangles alone sag by
  // hundreds of kilometres; a 1 km bound needs interior vertices.
  const SpherePatch patch = spherePatch(33, 60.0 * wgs84::kDegree, 6371e3);
  for (const double bound : {1000.0, 20e3, 200e3}) {
    ScatteredTinInput input;
    input.x = patch.x;
    input.y = patch.y;
    input.positions = patch.positions;
    input.metresPerUnitX = input.metresPerUnitY = 6371e3 * 60.0 * wgs84::kDegree / 32;
    input.maxErrorM = bound;
    const GreedyTin tin = buildScatteredTin(input);
    const double measured = worstMiss(patch, tin);
    EXPECT_LE(measured, bound) << bound;
    EXPECT_NEAR(tin.maxErrorM, measured, 1e-6) << bound;
    EXPECT_GT(tin.vertices.size(), 4u) << bound;
  }
  // Unbounded, the corners are enough; the same points measured flat would have no error.
  ScatteredTinInput loose;
  loose.x = patch.x;
  loose.y = patch.y;
  loose.positions = patch.positions;
  loose.maxErrorM = 1e9;
  const GreedyTin corners = buildScatteredTin(loose);
  EXPECT_EQ(corners.vertices.size(), 4u);
  EXPECT_GT(worstMiss(patch, corners), 400e3);  // R (1 - cos 30 deg * cos 30 deg) and more
}

TEST(ScatteredTin, FlatPositionsGiveTheGridsVerticalError) {
  // Positions (col, row, height) on a grid: the 3-D miss at the same coordinates is the
  // vertical one, so both insertions stop within the same bound.
  const HeightGrid grid = smallTerrain(41);
  SpherePatch p;  // the grid's samples as scattered points, corners first
  auto add = [&](int col, int row) {
    p.x.push_back(col);
    p.y.push_back(row);
    p.positions.push_back({col * grid.spacingXM, row * grid.spacingYM, grid.at(col, row)});
  };
  add(0, 0);
  add(40, 0);
  add(40, 40);
  add(0, 40);
  for (int row = 0; row < 41; ++row) {
    for (int col = 0; col < 41; ++col) {
      if (!((col == 0 || col == 40) && (row == 0 || row == 40))) add(col, row);
    }
  }
  ScatteredTinInput input;
  input.x = p.x;
  input.y = p.y;
  input.positions = p.positions;
  input.metresPerUnitX = grid.spacingXM;
  input.metresPerUnitY = grid.spacingYM;
  input.maxErrorM = 5.0;
  const GreedyTin scattered = buildScatteredTin(input);
  EXPECT_LE(worstMiss(p, scattered), 5.0);
  Result<TerrainMesh> gridMesh = buildTerrainMesh(gridOf(grid), {.maxErrorM = 5.0});
  ASSERT_TRUE(gridMesh);
  // Same algorithm, ties broken in another order: about the same size.
  EXPECT_NEAR(double(scattered.vertices.size()), double(gridMesh->samples.size()),
              0.1 * double(gridMesh->samples.size()));
}

TEST(QuantizedMeshTiler, RefusesAFolderThatIsNotATileSet) {
  std::shared_ptr<TileStore> store = TileStore::open(latLonStore()).value();
  const fs::path folder = test::freshTestDir() / "precious";
  fs::create_directories(folder);
  std::ofstream(folder / "notes.txt") << "keep me";
  Result<QuantizedMeshExportReport> report = exportQuantizedMesh(*store, folder, {});
  ASSERT_FALSE(report);
  EXPECT_NE(report.error().message.find("not part of a quantized-mesh tile set"), std::string::npos);
  EXPECT_TRUE(fs::exists(folder / "notes.txt"));
}

// --- 3D Tiles: implicit subtrees, the pyramid's bounds, the tile set of a store ---------------

// The specification's examples (ImplicitTiling/AVAILABILITY.adoc): x in the even bits.
TEST(ImplicitSubtree, MortonIndexInterleavesXIntoTheEvenBits) {
  EXPECT_EQ(quadtreeMortonIndex(0b11, 0b00), 0b0101u);
  EXPECT_EQ(quadtreeMortonIndex(0b1010, 0b0011), 0b01001110u);
  EXPECT_EQ(quadtreeMortonIndex(0b0110, 0b0101), 0b00110110u);
  EXPECT_EQ(subtreeTileBit(0, 0, 0), 0u);
  EXPECT_EQ(subtreeTileBit(1, 1, 0), 2u);        // level 1 starts at bit 1
  EXPECT_EQ(subtreeTileBit(2, 3, 3), 5u + 15u);  // level 2 at bit 5, Morton 15
}

// A subtree file read back by hand: the header, the 8-byte alignment of both chunks and of
// every bitstream, the bits where the Morton order puts them, least significant first.
struct DecodedSubtree {
  nlohmann::json json;
  std::string binary;
};
DecodedSubtree decodeSubtreeBytes(const std::string& bytes) {
  EXPECT_EQ(bytes.substr(0, 4), "subt");
  std::uint32_t version = 0;
  std::uint64_t jsonLength = 0, binaryLength = 0;
  std::memcpy(&version, bytes.data() + 4, 4);
  std::memcpy(&jsonLength, bytes.data() + 8, 8);
  std::memcpy(&binaryLength, bytes.data() + 16, 8);
  EXPECT_EQ(version, 1u);
  EXPECT_EQ(jsonLength % 8, 0u);
  EXPECT_EQ(binaryLength % 8, 0u);
  EXPECT_EQ(bytes.size(), 24 + jsonLength + binaryLength);
  return {nlohmann::json::parse(bytes.substr(24, jsonLength)), bytes.substr(24 + jsonLength)};
}

TEST(ImplicitSubtree, BitstreamsAndConstantsAreWrittenAsTheSpecificationSays) {
  QuadtreeSubtreeAvailability a = emptySubtreeAvailability(3);  // 1 + 4 + 16 = 21 bits
  ASSERT_EQ(a.tiles.size(), 21u);
  ASSERT_EQ(a.children.size(), 64u);
  const std::vector<std::tuple<int, int, int>> available = {{0, 0, 0}, {1, 1, 0}, {2, 2, 1}, {2, 3, 1}};
  for (const auto& [d, x, y] : available) a.tiles[subtreeTileBit(d, std::uint32_t(x), std::uint32_t(y))] = true;
  a.children[quadtreeMortonIndex(5, 2)] = true;
  const DecodedSubtree subtree = decodeSubtreeBytes(encodeSubtree(a));
  const nlohmann::json& tiles = subtree.json["tileAvailability"];
  ASSERT_TRUE(tiles.contains("bitstream")) << subtree.json.dump();
  EXPECT_EQ(tiles["availableCount"], 4);
  EXPECT_EQ(subtree.json["contentAvailability"][0], tiles);
  const auto bitsOf = [&](const nlohmann::json& availability, std::size_t count) {
    const nlohmann::json& view = subtree.json["bufferViews"][availability["bitstream"].get<std::size_t>()];
    const std::size_t offset = view["byteOffset"];
    EXPECT_EQ(offset % 8, 0u);
    EXPECT_EQ(view["byteLength"].get<std::size_t>(), (count + 7) / 8);
    std::vector<bool> bits(count);
    for (std::size_t i = 0; i < count; ++i) bits[i] = (std::uint8_t(subtree.binary[offset + i / 8]) >> (i % 8)) & 1u;
    return bits;
  };
  EXPECT_EQ(bitsOf(tiles, 21), a.tiles);
  EXPECT_EQ(bitsOf(subtree.json["childSubtreeAvailability"], 64), a.children);
  // Tile (2, 2, 1): level 2 starts at bit 5; Morton(2, 1) = 0b0110 = 6: bit 11, byte 1, bit 3.
  EXPECT_EQ((std::uint8_t(subtree.binary[std::size_t(subtree.json["bufferViews"][0]["byteOffset"]) + 1]) >> 3) & 1u, 1u);

  // Everything available, no child subtree: constants and no binary chunk.
  QuadtreeSubtreeAvailability full = emptySubtreeAvailability(2);
  full.tiles.assign(full.tiles.size(), true);
  const DecodedSubtree constant = decodeSubtreeBytes(encodeSubtree(full));
  EXPECT_EQ(constant.json["tileAvailability"], nlohmann::json({{"constant", 1}}));
  EXPECT_EQ(constant.json["childSubtreeAvailability"], nlohmann::json({{"constant", 0}}));
  EXPECT_FALSE(constant.json.contains("buffers"));
  EXPECT_TRUE(constant.binary.empty());
}

// Leaves above the finest level (the globe's tiles beyond the data) are built 3 levels tighter,
// and an edge between a leaf and a tile with children gets the smaller bound on both sides.
TEST(GeographicPyramid, LeavesAreTighterAndSharedEdgesGetTheSmallerBound) {
  const LonLatSampler source = LonLatSampler::create(readStoreLevel(*TileStore::open(latLonStore()).value(), 0).value()).value();
  GeographicPyramidOptions options;
  options.tileSamples = 17;
  options.globeLevels = 2;
  const GeographicPyramid pyramid = planGeographicPyramid(source, "latlon", options).value();
  ASSERT_EQ(pyramid.maxLevel, 12);
  // Level 2 (45 degrees): the data (127.3 E, 36.4 N) lies in tile x 6, y 2; x 7 is a leaf.
  EXPECT_FALSE(pyramid.isLeaf(2, 6, 2));
  EXPECT_TRUE(pyramid.isLeaf(2, 7, 2));
  EXPECT_TRUE(pyramid.isLeaf(12, pyramid.ranges[12].x0, pyramid.ranges[12].y0));
  EXPECT_DOUBLE_EQ(pyramid.tileBoundM(2, 6, 2), kTileBoundShare * cesiumGeometricErrorM(2));
  EXPECT_DOUBLE_EQ(pyramid.tileBoundM(2, 7, 2), kTileBoundShare * cesiumGeometricErrorM(2 + kLeafRefinementLevels));
  EXPECT_DOUBLE_EQ(pyramid.tileBoundM(12, pyramid.ranges[12].x0, pyramid.ranges[12].y0),
                   kTileBoundShare * cesiumGeometricErrorM(12));
  const std::array<double, 4> edges = pyramid.edgeBoundsM(2, 6, 2);  // west, east, south, north
  EXPECT_DOUBLE_EQ(edges[1], pyramid.tileBoundM(2, 7, 2));            // the leaf's, on both sides
  EXPECT_DOUBLE_EQ(pyramid.edgeBoundsM(2, 7, 2)[0], edges[1]);
  // x wraps at the antimeridian: tile 0's west neighbour is tile 7.
  EXPECT_DOUBLE_EQ(pyramid.edgeBoundsM(2, 0, 2)[0], pyramid.tileBoundM(2, 7, 2));
}

// The 3D Tiles set of a small store: tileset.json's structure, one content per available tile
// and no other, subtrees that say so, contents that place their vertices on the data (through
// the node's translation and glTF's y-up axes) within their level's error.
TEST(Tiles3dExport, WritesImplicitQuadtreesWhoseSubtreesNameEveryContent) {
  std::shared_ptr<TileStore> store = TileStore::open(latLonStore()).value();
  const fs::path folder = test::freshTestDir() / "tiles3d";
  Tiles3dExportOptions options;
  options.pyramid.tileSamples = 17;
  options.pyramid.globeLevels = 1;
  Result<Tiles3dExportReport> report = exportTiles3d(*store, folder, options);
  ASSERT_TRUE(report) << report.error().message;
  ASSERT_EQ(report->levels.size(), 13u);
  EXPECT_EQ(report->subtreeLevels, 7);
  std::ifstream tilesetFile(folder / "tileset.json");
  const nlohmann::json tileset = nlohmann::json::parse(tilesetFile);
  EXPECT_EQ(tileset["asset"]["version"], "1.1");
  ASSERT_EQ(tileset["root"]["children"].size(), 2u);
  for (int h = 0; h < 2; ++h) {
    const nlohmann::json& root = tileset["root"]["children"][h];
    EXPECT_EQ(root["implicitTiling"]["subdivisionScheme"], "QUADTREE");
    EXPECT_EQ(root["implicitTiling"]["availableLevels"], 13);
    EXPECT_DOUBLE_EQ(root["geometricError"].get<double>(), cesiumGeometricErrorM(0));
    const nlohmann::json& region = root["boundingVolume"]["region"];
    EXPECT_DOUBLE_EQ(region[0].get<double>(), h == 0 ? -std::numbers::pi : 0.0);
    EXPECT_LT(region[4].get<double>(), -5.0 * cesiumGeometricErrorM(0));  // level 0's skirts
  }
  // Every content file is an available tile of the east hemisphere's level-0 subtree (levels
  // 0..6) or of a level-7 subtree, and every available tile has its file.
  std::set<std::string> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder)) {
    if (e.path().extension() == ".glb") files.insert(fs::relative(e.path(), folder).string());
  }
  EXPECT_EQ(files.size(), report->tiles);
  std::set<std::string> named;
  const auto readSubtree = [&](int h, int level, int x, int y) {
    const std::string bytes = test::readFileBytes(folder / fmt::format("{}/subtrees/{}/{}/{}.subtree", h, level, x, y));
    return decodeSubtreeBytes(bytes);
  };
  for (int h = 0; h < 2; ++h) {
    std::vector<std::tuple<int, int, int>> roots{{0, 0, 0}};
    while (!roots.empty()) {
      const auto [level, x, y] = roots.back();
      roots.pop_back();
      const DecodedSubtree subtree = readSubtree(h, level, x, y);
      const auto bit = [&](const nlohmann::json& availability, std::size_t i) {
        if (availability.contains("constant")) return availability["constant"].get<int>() == 1;
        const std::size_t offset = subtree.json["bufferViews"][availability["bitstream"].get<std::size_t>()]["byteOffset"];
        return ((std::uint8_t(subtree.binary[offset + i / 8]) >> (i % 8)) & 1u) == 1u;
      };
      for (int d = 0; d <= 7; ++d) {
        for (int j = 0; j < (1 << d); ++j) {
          for (int i = 0; i < (1 << d); ++i) {
            const int gx = (x << d) + i, gy = (y << d) + j;
            if (d == 7) {
              if (bit(subtree.json["childSubtreeAvailability"], quadtreeMortonIndex(std::uint32_t(i), std::uint32_t(j)))) {
                roots.emplace_back(level + 7, gx, gy);
              }
            } else if (bit(subtree.json["tileAvailability"], subtreeTileBit(d, std::uint32_t(i), std::uint32_t(j)))) {
              named.insert(fmt::format("{}/tiles/{}/{}/{}.glb", h, level + d, gx, gy));
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(named, files);

  // A content of level 12 over the data: its vertices, through the node's translation and
  // back from glTF's y-up axes, lie on the store's surface within the level's bound (and its
  // skirts below it).
  const GeographicTileRange& finest = planGeographicPyramid(
      LonLatSampler::create(readStoreLevel(*store, 0).value()).value(), "latlon", options.pyramid)->ranges[12];
  const int hemisphere = finest.x0 >> 12;
  const fs::path glb = folder / fmt::format("{}/tiles/12/{}/{}.glb", hemisphere, finest.x0 - (hemisphere << 12), finest.y0);
  tinygltf::Model model;
  std::string error, warning;
  tinygltf::TinyGLTF loader;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, glb.string())) << error;
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  ASSERT_TRUE(primitive.attributes.count("TEXCOORD_0"));
  const tinygltf::Accessor& positions = model.accessors[std::size_t(primitive.attributes.at("POSITION"))];
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(positions.bufferView)];
  const auto* xyz = reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset);
  const std::vector<double>& t = model.nodes[0].translation;
  ASSERT_EQ(t.size(), 3u);
  const LonLatSampler sampler = LonLatSampler::create(readStoreLevel(*store, 0).value()).value();
  int onSurface = 0;
  for (std::size_t k = 0; k < positions.count; ++k) {
    const glm::dvec3 ecef(t[0] + xyz[3 * k], -(t[2] + xyz[3 * k + 2]), t[1] + xyz[3 * k + 1]);
    const wgs84::Geodetic g = wgs84::ecefToGeodetic(ecef);
    const double lon = g.lonRad / wgs84::kDegree, lat = g.latRad / wgs84::kDegree;
    float height = 0.0f;
    sampler.sample(std::span(&lon, 1), std::span(&lat, 1), std::span(&height, 1));
    if (!std::isfinite(height)) continue;
    const double miss = g.heightM - double(height);
    if (std::abs(miss) < 0.9 * cesiumGeometricErrorM(12)) {
      ++onSurface;
    } else {
      EXPECT_NEAR(miss, -5.0 * cesiumGeometricErrorM(12), 1.0) << "vertex " << k;  // a skirt's
    }
  }
  EXPECT_GT(onSurface, 10);
}

TEST(Tiles3dExport, RefusesAFolderThatIsNotATileSet) {
  std::shared_ptr<TileStore> store = TileStore::open(latLonStore()).value();
  const fs::path folder = test::freshTestDir() / "precious";
  fs::create_directories(folder);
  std::ofstream(folder / "notes.txt") << "keep me";
  Result<Tiles3dExportReport> report = exportTiles3d(*store, folder, {});
  ASSERT_FALSE(report);
  EXPECT_NE(report.error().message.find("not part of a 3D Tiles tile set"), std::string::npos) << report.error().message;
  EXPECT_TRUE(fs::exists(folder / "notes.txt"));
}

TEST(GltfExport, ReadsBackWithinTheErrorTarget) {
  const fs::path dir = test::freshTestDir();
  TerrainParams params;
  params.size = 257;
  const test::GeneratedStore generated = test::buildGeneratedStore(params, dir, 64);
  ASSERT_TRUE(generated.store);
  std::uint64_t previousTriangles = std::numeric_limits<std::uint64_t>::max();
  for (const double bound : {0.0, 1.0, 10.0}) {
    const fs::path glb = dir / fmt::format("terrain-{}.glb", bound);
    GltfExportOptions options;
    options.maxErrorM = bound;
    options.hypsometricColours = bound == 1.0;
    Result<GltfExportReport> report = exportGltf(*generated.store, glb, options);
    ASSERT_TRUE(report) << report.error().message;
    EXPECT_LE(report->maxErrorM, bound);

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, glb.string())) << error;
    ASSERT_EQ(model.meshes.size(), 1u);
    const tinygltf::Primitive& primitive = model.meshes[0].primitives.at(0);
    const tinygltf::Accessor& positions = model.accessors[std::size_t(primitive.attributes.at("POSITION"))];
    const tinygltf::Accessor& indices = model.accessors[std::size_t(primitive.indices)];
    EXPECT_EQ(indices.count / 3, report->triangles);
    EXPECT_EQ(primitive.attributes.count("NORMAL"), 1u);
    EXPECT_EQ(primitive.attributes.count("COLOR_0"), bound == 1.0 ? 1u : 0u);
    // Every sample's true east-north-up position in the file's frame (its origin from the
    // extras): the store's CRS is a UTM zone whose grid metres are 2.4 % short of the ground's
    // here (the old exporter used them as they were).
    const double dx = report->spacingXM;
    EXPECT_NEAR(dx, 30.0, 0.01);
    std::vector<double> lons, lats;
    ASSERT_TRUE(sampleLonLats(generated.level0, lons, lats));
    const tinygltf::Value& origin = model.nodes.at(0).extras.Get("originLonLatHeight");
    const EnuFrame frame({origin.Get(1).GetNumberAsDouble() * wgs84::kDegree,
                          origin.Get(0).GetNumberAsDouble() * wgs84::kDegree, 0.0});
    std::vector<glm::dvec3> sampleEnu(lons.size());
    glm::dvec3 sampleLo(1e30), sampleHi(-1e30);
    for (std::size_t k = 0; k < lons.size(); ++k) {
      sampleEnu[k] = frame.toEnu(wgs84::geodeticToEcef(
          {lats[k] * wgs84::kDegree, lons[k] * wgs84::kDegree, double(generated.level0.heights[k])}));
      sampleLo = glm::min(sampleLo, sampleEnu[k]);
      sampleHi = glm::max(sampleHi, sampleEnu[k]);
    }
    // Bounds: the samples' (the border's extremes are kept whatever the bound), heights within
    // the bound of theirs.
    EXPECT_NEAR(positions.minValues[0], sampleLo.x, 0.05);
    EXPECT_NEAR(positions.maxValues[0], sampleHi.x, 0.05);
    EXPECT_NEAR(positions.minValues[2], -sampleHi.y, 0.05);
    EXPECT_NEAR(positions.maxValues[2], -sampleLo.y, 0.05);
    EXPECT_NEAR(positions.minValues[1], sampleLo.z, bound + 0.05);
    EXPECT_NEAR(positions.maxValues[1], sampleHi.z, bound + 0.05);
    EXPECT_GE(positions.minValues[1], sampleLo.z - 0.05);
    EXPECT_LE(positions.maxValues[1], sampleHi.z + 0.05);

    // The read-back mesh, mapped onto the grid's samples (each vertex is the sample whose
    // east-north-up position it holds), is within the bound of every sample (vertically, on
    // the grid: the 3-D bound plus the curvature's sag over a triangle, centimetres here).
    const glm::dvec3 first = sampleEnu[0];  // the north-west sample
    const double groundDx = (sampleEnu[256].x - first.x) / 256;
    const double groundDy = (first.y - sampleEnu[256 * 257].y) / 256;
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(positions.bufferView)];
    const auto* xyz = reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset + positions.byteOffset);
    std::vector<std::uint32_t> samples(positions.count);
    for (std::size_t k = 0; k < positions.count; ++k) {
      const glm::dvec3 enu(xyz[3 * k], -xyz[3 * k + 2], xyz[3 * k + 1]);
      const int guessCol = int(std::lround((enu.x - first.x) / groundDx));
      const int guessRow = int(std::lround((first.y - enu.y) / groundDy));
      double best = 1e30;
      // The UTM grid is turned against true north here (grid convergence): search wide.
      for (int r = std::max(0, guessRow - 20); r <= std::min(256, guessRow + 20); ++r) {
        for (int c = std::max(0, guessCol - 20); c <= std::min(256, guessCol + 20); ++c) {
          const double d = glm::length(sampleEnu[std::size_t(r * 257 + c)] - enu);
          if (d < best) {
            best = d;
            samples[k] = std::uint32_t((256 - r) * 257 + c);  // rows counted from the south
          }
        }
      }
      ASSERT_LT(best, 0.05) << "vertex " << k << " is no sample";
    }
    std::vector<std::uint32_t> triangles(indices.count);
    const tinygltf::BufferView& indexView = model.bufferViews[std::size_t(indices.bufferView)];
    const unsigned char* indexBytes = model.buffers[0].data.data() + indexView.byteOffset + indices.byteOffset;
    for (std::size_t k = 0; k < indices.count; ++k) {
      triangles[k] = indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                         ? reinterpret_cast<const std::uint16_t*>(indexBytes)[k]
                         : reinterpret_cast<const std::uint32_t*>(indexBytes)[k];
    }
    std::vector<float> northUp(generated.level0.heights.size());
    for (int row = 0; row < 257; ++row) {
      std::copy_n(&generated.level0.heights[std::size_t(256 - row) * 257], 257, &northUp[std::size_t(row) * 257]);
    }
    EXPECT_LE(measureVerticalError({257, 257, groundDx, groundDy, northUp}, samples, triangles), bound + 0.05);
    if (bound > 0.0) {
      EXPECT_LT(report->triangles, previousTriangles);
    }
    previousTriangles = report->triangles;
  }
}

// A bowl 1 m a sample squared deep: no sample lies on a plane through others, so a mesh at
// error 0 keeps them all.
double bowlRelief(double latDeg, double lonDeg) {
  const double x = (lonDeg - 127.0) * 300.0 - 127.5, y = (latDeg - 37.0) * 300.0 - 127.5;
  return 0.5 * (x * x + y * y);
}

// 16-bit indices stop below 65,536 vertices: index 65535 is the primitive-restart value, which
// glTF forbids (a 256 x 256 mesh at error 0 has exactly 65,536 vertices).
// KHR_mesh_quantization: the same mesh with 16-bit positions, 8-bit normals and 16-bit texture
// coordinates; the node's translation and scale take the positions back to within half a grid
// step's diagonal of the float ones; the extension is used and required; about half the bytes.
TEST(GlbWriter, QuantizedMeshDequantizesToTheFloatPositions) {
  GlbMesh mesh;
  mesh.name = "quantized";
  std::mt19937 random(3);
  std::uniform_real_distribution<float> coordinate(-3000.0f, 3000.0f);
  for (int k = 0; k < 300; ++k) {
    for (int c = 0; c < 3; ++c) mesh.positions.push_back(coordinate(random) * (c == 1 ? 0.1f : 1.0f));
    mesh.normals.insert(mesh.normals.end(), {0.0f, 1.0f, 0.0f});
    mesh.texcoords.insert(mesh.texcoords.end(), {float(k) / 299.0f, 1.0f - float(k) / 299.0f});
  }
  for (std::uint32_t k = 0; k + 2 < 300; ++k) mesh.indices.insert(mesh.indices.end(), {k, k + 1, k + 2});
  mesh.translation = std::array<double, 3>{4.0e6, 1.0e6, -4.5e6};
  const std::string plain = encodeGlb(mesh).value();
  mesh.quantize = true;
  const std::string packed = encodeGlb(mesh).value();
  EXPECT_LT(double(packed.size()), 0.75 * double(plain.size()));
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(packed.data()),
                                          unsigned(packed.size()))) << error;
  EXPECT_EQ(model.extensionsRequired, std::vector<std::string>{"KHR_mesh_quantization"});
  const tinygltf::Node& node = model.nodes.at(0);
  ASSERT_EQ(node.scale.size(), 3u);
  ASSERT_EQ(node.translation.size(), 3u);
  const double step = node.scale[0];
  EXPECT_NEAR(step, 6000.0 / 65535.0, 1e-3);
  const tinygltf::Primitive& primitive = model.meshes.at(0).primitives.at(0);
  const tinygltf::Accessor& positions = model.accessors[std::size_t(primitive.attributes.at("POSITION"))];
  EXPECT_EQ(positions.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(positions.bufferView)];
  EXPECT_EQ(view.byteStride, 8u);
  for (std::size_t k = 0; k < positions.count; ++k) {
    const auto* q = reinterpret_cast<const std::uint16_t*>(model.buffers[0].data.data() + view.byteOffset + 8 * k);
    for (std::size_t c = 0; c < 3; ++c) {
      const double restored = node.translation[c] + step * q[c];
      const double original = (*mesh.translation)[c] + double(mesh.positions[3 * k + c]);
      ASSERT_NEAR(restored, original, 0.5 * step + 1e-6) << "vertex " << k << " axis " << c;
    }
  }
  EXPECT_EQ(model.accessors[std::size_t(primitive.attributes.at("NORMAL"))].componentType, TINYGLTF_COMPONENT_TYPE_BYTE);
  EXPECT_TRUE(model.accessors[std::size_t(primitive.attributes.at("TEXCOORD_0"))].normalized);
}

// A Landsat 9 scene in Web Mercator (EPSG:3857) draped on a mesh of Tokyo Bay: the texture
// warped to the mesh's latitude/longitude box, JPEG in the glb, TEXCOORD_0 per vertex. Checked
// against the scene itself, read here with GDAL at the pixel that the spherical Mercator
// formulas (x = R lon, y = R ln tan(pi/4 + lat/2), written out here, not through PROJ) give for
// vertices' longitudes and latitudes. A region beyond the scene is refused; one half in it is
// grey where it has no pixel.
TEST(GltfExport, DrapesAWebMercatorLandsatSceneWhereItLies) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path landsat = data / "landsat9-kanto/landsat9_kanto_z12_3857.tif";
  const fs::path dir = test::freshTestDir();
  const fs::path tif = test::writeLatLonTerrain(dir / "bay.tif", 139.75, 35.65, 0.0025, 121, 121,
                                                [](double lat, double lon) { return 50.0 + 40.0 * std::sin(lat * 90.0) * std::cos(lon * 70.0); });
  BuildOptions build;
  build.tileSize = 32;
  ASSERT_TRUE(buildPyramid({tif}, dir / "bay.tstore", build));
  std::shared_ptr<TileStore> store = TileStore::open(dir / "bay.tstore").value();
  GltfExportOptions options;
  options.maxErrorM = 2.0;
  options.texture = landsat;
  options.textureMaxSide = 512;
  Result<GltfExportReport> report = exportGltf(*store, dir / "bay.glb", options);
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report->textureHeight, 512);  // north-south is the longer side here
  EXPECT_EQ(report->textureWidth, 512);   // 0.3 deg x cos 35.5 deg: the nearest power of two
  EXPECT_DOUBLE_EQ(report->textureCoverage, 1.0);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, (dir / "bay.glb").string())) << error;
  ASSERT_EQ(model.images.size(), 1u);
  EXPECT_EQ(model.images[0].mimeType, "image/jpeg");
  const tinygltf::Image& image = model.images[0];  // decoded by tinygltf (stb)
  ASSERT_EQ(image.width, 512);
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  const tinygltf::Accessor& st = model.accessors[std::size_t(primitive.attributes.at("TEXCOORD_0"))];
  const auto* texcoords = reinterpret_cast<const float*>(
      model.buffers[0].data.data() + model.bufferViews[std::size_t(st.bufferView)].byteOffset);
  const tinygltf::Value& origin = model.nodes[0].extras.Get("originLonLatHeight");
  const double originLon = origin.Get(0).GetNumberAsDouble(), originLat = origin.Get(1).GetNumberAsDouble();
  gdal::ensureRegistered();
  gdal::DatasetPtr scene(GDALDataset::FromHandle(GDALOpenEx(landsat.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY,
                                                            nullptr, nullptr, nullptr)));
  ASSERT_TRUE(scene);
  double gt[6];
  ASSERT_EQ(scene->GetGeoTransform(gt), CE_None);
  // The texture's box: the samples' centres.
  const double west = 139.75, east = 139.75 + 120 * 0.0025, north = 35.65, south = 35.65 - 120 * 0.0025;
  std::vector<double> differences;
  for (std::size_t k = 0; k < st.count; k += st.count / 40) {
    const double lon = west + texcoords[2 * k] * (east - west), lat = north - texcoords[2 * k + 1] * (north - south);
    const double x = wgs84::kSemiMajorAxisM * lon * wgs84::kDegree;
    const double y = wgs84::kSemiMajorAxisM * std::log(std::tan(std::numbers::pi / 4 + lat * wgs84::kDegree / 2));
    const int col = int((x - gt[0]) / gt[1]), row = int((y - gt[3]) / gt[5]);
    std::uint8_t truth[3];
    for (int b = 0; b < 3; ++b) {
      ASSERT_EQ(scene->GetRasterBand(b + 1)->RasterIO(GF_Read, col, row, 1, 1, &truth[b], 1, 1, GDT_Byte, 0, 0), CE_None);
    }
    const int px = std::clamp(int(double(texcoords[2 * k]) * image.width), 0, image.width - 1);
    const int py = std::clamp(int(double(texcoords[2 * k + 1]) * image.height), 0, image.height - 1);
    const unsigned char* texel = &image.image[std::size_t(4 * (py * image.width + px))];
    double difference = 0.0;
    for (int b = 0; b < 3; ++b) difference += std::abs(double(texel[b]) - double(truth[b])) / 3.0;
    differences.push_back(difference);
  }
  std::sort(differences.begin(), differences.end());
  EXPECT_LT(differences[differences.size() / 2], 16.0) << "median colour difference";  // JPEG, bilinear
  EXPECT_NEAR(originLon, 139.9, 0.01);
  EXPECT_NEAR(originLat, 35.5, 0.01);

  // Beyond the scene: refused, naming the file.
  const fs::path farTif = test::writeLatLonTerrain(dir / "far.tif", 130.0, 35.0, 0.01, 21, 21,
                                                   [](double, double) { return 10.0; });
  ASSERT_TRUE(buildPyramid({farTif}, dir / "far.tstore", build));
  Result<GltfExportReport> far = exportGltf(*TileStore::open(dir / "far.tstore").value(), dir / "far.glb", options);
  ASSERT_FALSE(far);
  EXPECT_NE(far.error().message.find("covers none of"), std::string::npos) << far.error().message;
  EXPECT_NE(far.error().message.find("landsat9_kanto_z12_3857.tif"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "far.glb"));
  // Across the scene footprint's western edge (near 139.1 E at 35.6 N): grey where it has no pixel.
  const fs::path edgeTif = test::writeLatLonTerrain(dir / "edge.tif", 139.0, 35.7, 0.005, 41, 41,
                                                    [](double, double) { return 10.0; });
  ASSERT_TRUE(buildPyramid({edgeTif}, dir / "edge.tstore", build));
  Result<GltfExportReport> edge = exportGltf(*TileStore::open(dir / "edge.tstore").value(), dir / "edge.glb", options);
  ASSERT_TRUE(edge) << edge.error().message;
  EXPECT_GT(edge->textureCoverage, 0.05);
  EXPECT_LT(edge->textureCoverage, 0.95);
}

TEST(GltfExport, SixtyFiveThousandFiveHundredAndThirtySixVerticesGet32BitIndices) {
  const fs::path dir = test::freshTestDir();
  for (const int size : {255, 256}) {
    const fs::path tif = test::writeLatLonTerrain(dir / fmt::format("bowl-{}.tif", size), 127.0,
                                                  37.0 + size / 300.0, 1.0 / 300.0, size, size, bowlRelief);
    BuildOptions build;
    build.tileSize = 64;
    build.codec = "raw";
    ASSERT_TRUE(buildPyramid({tif}, dir / fmt::format("bowl-{}.tstore", size), build));
    std::shared_ptr<TileStore> store = TileStore::open(dir / fmt::format("bowl-{}.tstore", size)).value();
    const fs::path glb = dir / fmt::format("{}.glb", size);
    GltfExportOptions options;
    options.maxErrorM = 0.0;
    Result<GltfExportReport> report = exportGltf(*store, glb, options);
    ASSERT_TRUE(report) << report.error().message;
    ASSERT_EQ(report->vertices, std::uint64_t(size) * std::uint64_t(size));
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, glb.string())) << error;
    const tinygltf::Accessor& indices = model.accessors[std::size_t(model.meshes[0].primitives.at(0).indices)];
    EXPECT_EQ(indices.componentType, size == 256 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT
                                                 : TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) << size;
  }
}

double rollingRelief(double latDeg, double lonDeg) {
  return 800.0 + 600.0 * std::sin(latDeg * 3.0) * std::cos(lonDeg * 2.0);
}

// Positions in a local east-north-up frame, per sample through ECEF: over 4 x 4 degrees
// (34 to 38 N), every vertex taken back through the extras' matrix lands on its sample's
// longitude, latitude and height, and the distances between the corners are the ellipsoid's
// (Karney's geodesics) within 0.05 %: one east-west spacing at the centre latitude was 2.4 %
// short at 34 N and 2.65 % long at 38 N.
TEST(GltfExport, PositionsAreTrueInALocalFrameOverDegrees) {
  const fs::path dir = test::freshTestDir();
  const fs::path tif = test::writeLatLonTerrain(dir / "wide.tif", 126.0, 38.0, 1.0 / 60.0, 241, 241, rollingRelief);
  BuildOptions build;
  build.tileSize = 64;
  ASSERT_TRUE(buildPyramid({tif}, dir / "wide.tstore", build));
  std::shared_ptr<TileStore> store = TileStore::open(dir / "wide.tstore").value();
  GltfExportOptions options;
  options.maxErrorM = 50.0;
  Result<GltfExportReport> report = exportGltf(*store, dir / "wide.glb", options);
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_LE(report->maxErrorM, 50.0);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, (dir / "wide.glb").string())) << error;
  const tinygltf::Value& matrix = model.nodes.at(0).extras.Get("ecefFromLocal");
  ASSERT_EQ(matrix.ArrayLen(), 16u);
  glm::dmat4 ecefFromLocal(1.0);
  for (int k = 0; k < 16; ++k) ecefFromLocal[k / 4][k % 4] = matrix.Get(k).GetNumberAsDouble();
  const tinygltf::Primitive& primitive = model.meshes.at(0).primitives.at(0);
  const tinygltf::Accessor& accessor = model.accessors[std::size_t(primitive.attributes.at("POSITION"))];
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(accessor.bufferView)];
  const float* xyz = reinterpret_cast<const float*>(model.buffers[std::size_t(view.buffer)].data.data() +
                                                    view.byteOffset + accessor.byteOffset);
  std::map<std::pair<int, int>, glm::dvec3> corners;  // (col, row) -> the vertex's ECEF
  for (std::size_t k = 0; k < accessor.count; ++k) {
    const glm::dvec3 ecef(ecefFromLocal * glm::dvec4(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2], 1.0));
    const wgs84::Geodetic g = wgs84::ecefToGeodetic(ecef);
    const double col = (g.lonRad / wgs84::kDegree - 126.0) * 60.0, row = (38.0 - g.latRad / wgs84::kDegree) * 60.0;
    // On a sample, at its height (float positions up to 200 km from the origin: centimetres).
    ASSERT_NEAR(col, std::round(col), 1e-4) << k;
    ASSERT_NEAR(row, std::round(row), 1e-4) << k;
    ASSERT_NEAR(g.heightM, rollingRelief(38.0 - std::round(row) / 60.0, 126.0 + std::round(col) / 60.0), 0.05) << k;
    if ((std::round(col) == 0 || std::round(col) == 240) && (std::round(row) == 0 || std::round(row) == 240)) {
      corners[{int(std::round(col)), int(std::round(row))}] = ecef;
    }
  }
  ASSERT_EQ(corners.size(), 4u);  // the corners are always vertices
  for (const auto& [a, b, latDeg] : {std::tuple{std::pair{0, 240}, std::pair{240, 240}, 34.0},
                                     std::tuple{std::pair{0, 0}, std::pair{240, 0}, 38.0}}) {
    const double drawn = glm::length(corners.at(a) - corners.at(b));
    const double truth = geodesicInverse(latDeg, 126.0, latDeg, 130.0).distanceM;
    EXPECT_NEAR(drawn / truth, 1.0, 5e-4) << latDeg;
  }
}

TEST(GltfExport, ExportsARegionAndRefusesOneOutside) {
  std::shared_ptr<TileStore> store = TileStore::open(latLonStore()).value();
  const fs::path dir = test::freshTestDir();
  GltfExportOptions options;
  options.region = LonLatBox{127.35, 36.25, 127.45, 36.35};
  Result<GltfExportReport> report = exportGltf(*store, dir / "region.glb", options);
  ASSERT_TRUE(report) << report.error().message;
  // 0.1 degree at 1/300: 30 cells (31 samples), one more on a side where the box falls
  // between samples.
  EXPECT_GE(report->width, 31);
  EXPECT_LE(report->width, 33);
  options.region = LonLatBox{10.0, 10.0, 11.0, 11.0};
  EXPECT_FALSE(exportGltf(*store, dir / "outside.glb", options));
  EXPECT_FALSE(fs::exists(dir / "outside.glb"));
}

}  // namespace
}  // namespace tellus
