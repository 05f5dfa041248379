// The global store on synthetic sources with known heights: a coarse source over the whole
// globe and a fine one over a small box. Sparse depths, finest-source precedence, exact shared
// edges (the antimeridian too), nesting, poles, exact errors, missing tiles read from their
// ancestors, and corruption caught with a message naming the tile.
#include <cmath>
#include <fstream>
#include <optional>

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/dem/latlon_warper.hpp"
#include "tellus/tiles/global_store.hpp"
#include "tellus/tiles/global_store_builder.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// The coarse source's heights: smooth, kilometres of relief.
double coarseHeight(double lat, double lon) {
  return 3000.0 * std::sin(2.0 * lat * kDeg) * std::cos(3.0 * lon * kDeg);
}
// The fine source's: the coarse field plus a sharp 500 m bump at (41 N, 11 E).
double fineHeight(double lat, double lon) {
  const double r2 = (lat - 41.0) * (lat - 41.0) + (lon - 11.0) * (lon - 11.0);
  return coarseHeight(lat, lon) + 500.0 * std::exp(-r2 / 0.02);
}

// A pixel-is-area lat/lon GeoTIFF whose pixel centres run from (north, west) in `step`s.
fs::path writeSource(const fs::path& path, double west, double north, double step, int width,
                     int height, double (*heights)(double, double)) {
  HeightGrid grid(width, height);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) grid.at(i, j) = float(heights(north - j * step, west + i * step));
  }
  grid.georef.crsWkt = kWgs84Wkt;
  grid.georef.crsName = "WGS 84";
  grid.georef.isGeographic = true;
  grid.georef.hasGeoTransform = true;
  grid.georef.geoTransform = {west - 0.5 * step, step, 0.0, north + 0.5 * step, 0.0, -step};
  EXPECT_TRUE(writeGeoTiff(grid, path));
  return path;
}

struct Sources {
  fs::path dir, coarse, fine;
};

// Coarse: 2-degree samples over the globe (-180..178 E, 90..-90 N); fine: 0.02-degree samples
// over 10..12 E, 40..42 N.
const Sources& sources() {
  static const Sources s = [] {
    Sources made;
    made.dir = test::freshTestDir();
    made.coarse = writeSource(made.dir / "coarse.tif", -180.0, 90.0, 2.0, 180, 91, coarseHeight);
    made.fine = writeSource(made.dir / "fine.tif", 10.0, 42.0, 0.02, 101, 101, fineHeight);
    return made;
  }();
  return s;
}

// 16-cell tiles: the coarse source feeds depths 0..3 (1.41-degree samples), the fine one down
// to depth 9 (0.022 degrees).
fs::path buildStore(const std::string& name, std::vector<fs::path> inputs) {
  GlobalBuildOptions options;
  options.tileCells = 16;
  const fs::path out = sources().dir / name;
  Result<GlobalBuildReport> report = buildGlobalStore(inputs, out, options);
  EXPECT_TRUE(report) << report.error().message;
  return out;
}

const fs::path& earth() {
  static const fs::path path =
      buildStore("earth.tstore", {sources().coarse, sources().fine});
  return path;
}

std::vector<float> readTile(const GlobalStore& store, GeoTileKey key) {
  std::vector<float> h(store.tileShape().sampleCount());
  EXPECT_TRUE(store.readTileMetres(key, h)) << GlobalStore::describe(key);
  return h;
}

TEST(GlobalStore, NativeDepths) {
  EXPECT_EQ(nativeDepth(5.0 / 60.0, 256, 12), 3);     // ETOPO5
  EXPECT_EQ(nativeDepth(3.0 / 3600.0, 256, 12), 10);  // SRTM3
  EXPECT_EQ(nativeDepth(1.0 / 3600.0, 256, 12), 12);  // SRTM1: depth 11 is 1.24", too coarse
  EXPECT_EQ(nativeDepth(1.0 / 3600.0, 256, 9), 9);    // capped
}

TEST(GlobalStore, SparseBelowTheGlobalSource) {
  Result<std::shared_ptr<GlobalStore>> opened = GlobalStore::open(earth());
  ASSERT_TRUE(opened) << opened.error().message;
  const GlobalStore& store = *opened.value();
  const GlobalStoreMetadata& m = store.metadata();
  ASSERT_EQ(m.deepestDepth, 9);
  // Complete down to depth 3 (2 + 8 + 32 + 128 tiles), then only where the fine source lies.
  EXPECT_EQ(m.tilesPerDepth[0], 2u);
  EXPECT_EQ(m.tilesPerDepth[3], 128u);
  for (int d = 4; d <= 9; ++d) {
    Result<std::vector<GeoTileKey>> covering =
        GlobalTiling::tilesCovering(d, {10.0 + 1e-7, 40.0 + 1e-7, 12.0 - 1e-7, 42.0 - 1e-7});
    ASSERT_TRUE(covering);
    EXPECT_EQ(m.tilesPerDepth[std::size_t(d)], covering->size()) << "depth " << d;
    for (const GeoTileKey& key : *covering) EXPECT_TRUE(store.find(key)) << GlobalStore::describe(key);
  }
  EXPECT_EQ(m.sources.front().path, sources().fine.string()) << "finest first";
  EXPECT_EQ(m.uncoveredSamples, 0u);
  // A tile far from the fine source is its depth-3 ancestor.
  const GeoTileKey far = GlobalTiling::tileAt(9, -30.0, -100.0);
  EXPECT_FALSE(store.find(far));
  EXPECT_EQ(store.deepestStored(far).depth, 3);
}

TEST(GlobalStore, SamplesComeFromTheFinestSourceThatCoversThem) {
  const std::shared_ptr<GlobalStore> store = GlobalStore::open(earth()).value();
  const double q = store->metadata().quantumM;
  const int n = store->tileCells();
  // Inside the fine source: its field (bilinear between 0.02-degree samples of a smooth bump).
  const GeoTileKey inside = GlobalTiling::tileAt(9, 41.0, 11.0);
  const std::vector<float> h = readTile(*store, inside);
  double worstInside = 0.0;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double lat = GlobalTiling::sampleLatDeg(inside, n, j);
      const double lon = GlobalTiling::sampleLonDeg(inside, n, i);
      worstInside = std::max(worstInside, std::abs(h[std::size_t(j * (n + 1) + i)] - fineHeight(lat, lon)));
    }
  }
  EXPECT_LT(worstInside, 15.0) << "the fine source's bump must be there";
  EXPECT_GT(*std::max_element(h.begin(), h.end()), coarseHeight(41.0, 11.0) + 300.0);
  // Far away: the coarse source, to its interpolation error.
  const GeoTileKey outside{3, 3, 2};
  const std::vector<float> c = readTile(*store, outside);
  for (int j = 0; j <= n; j += 4) {
    for (int i = 0; i <= n; i += 4) {
      const double lat = GlobalTiling::sampleLatDeg(outside, n, j);
      const double lon = GlobalTiling::sampleLonDeg(outside, n, i);
      EXPECT_NEAR(c[std::size_t(j * (n + 1) + i)], coarseHeight(lat, lon), 60.0 + q);
    }
  }
}

// Every stored tile shares its east edge with its neighbour and nests in its parent bit for
// bit, and the poles hold one height.
void expectEdgesNestingAndPolesExact(const fs::path& path) {
  const std::shared_ptr<GlobalStore> store = GlobalStore::open(path).value();
  const GlobalStoreMetadata& m = store->metadata();
  const int n = store->tileCells(), side = n + 1;
  const auto at = [side](const std::vector<float>& t, int i, int j) { return t[std::size_t(j * side + i)]; };
  std::size_t edges = 0, nested = 0;
  for (const TileRecord& record : store->records()) {
    const GeoTileKey key = GlobalStore::toGeoKey(record.key);
    const std::vector<float> h = readTile(*store, key);
    const GeoNeighbour east = GlobalTiling::neighbour(key, GeoSide::East);
    if (store->find(east.key)) {
      const std::vector<float> e = readTile(*store, east.key);
      for (int j = 0; j <= n; ++j) ASSERT_EQ(at(h, n, j), at(e, 0, j)) << GlobalStore::describe(key);
      ++edges;
    }
    if (key.depth > 0) {
      const std::vector<float> p = readTile(*store, GlobalTiling::parent(key));
      const int ox = (key.x % 2) * n / 2, oy = (key.y % 2) * n / 2;
      for (int j = 0; j <= n; j += 2) {
        for (int i = 0; i <= n; i += 2) {
          ASSERT_EQ(at(h, i, j), at(p, ox + i / 2, oy + j / 2)) << GlobalStore::describe(key);
        }
      }
      ++nested;
    }
    if (key.y == 0) {
      for (int i = 0; i <= n; ++i) ASSERT_EQ(at(h, i, 0), m.northPoleM);
    }
    if (key.y == GlobalTiling::tilesY(key.depth) - 1) {
      for (int i = 0; i <= n; ++i) ASSERT_EQ(at(h, i, n), m.southPoleM);
    }
    EXPECT_EQ(record.stats.geometricErrorM == 0.0f, !store->hasStoredChildren(key))
        << GlobalStore::describe(key);
  }
  EXPECT_GT(edges, 150u) << "the antimeridian pairs included";
  EXPECT_EQ(nested, store->records().size() - 2);
}

TEST(GlobalStore, EdgesNestingAndPolesAreExact) {
  expectEdgesNestingAndPolesExact(earth());
  const GlobalStoreMetadata& m = GlobalStore::open(earth()).value()->metadata();
  EXPECT_NEAR(m.northPoleM, coarseHeight(90.0, 0.0), 1.0);
}

// The error of a tile is the largest deviation of its stored descendants from its surface:
// recomputed here from every depth-9 tile under a depth-5 tile.
TEST(GlobalStore, GeometricErrorsAreExact) {
  const std::shared_ptr<GlobalStore> store = GlobalStore::open(earth()).value();
  const int n = store->tileCells(), side = n + 1;
  const GeoTileKey coarse = GlobalTiling::tileAt(5, 41.0, 11.0);
  const std::vector<float> c = readTile(*store, coarse);
  float worst = 0.0f;
  for (const TileRecord& record : store->records()) {
    GeoTileKey key = GlobalStore::toGeoKey(record.key);
    if (key.depth <= coarse.depth) continue;
    GeoTileKey up = key;
    while (up.depth > coarse.depth) up = GlobalTiling::parent(up);
    if (up != coarse) continue;
    const std::vector<float> h = readTile(*store, key);
    const double scale = 1.0 / double(1 << (key.depth - coarse.depth));
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double u = (double(key.x) * n + i) * scale - double(coarse.x) * n;
        const double v = (double(key.y) * n + j) * scale - double(coarse.y) * n;
        const int u0 = std::min(int(u), n - 1), v0 = std::min(int(v), n - 1);
        const double fu = u - u0, fv = v - v0;
        const auto s = [&](int a, int b) { return double(c[std::size_t(b * side + a)]); };
        const double top = s(u0, v0) + (s(u0 + 1, v0) - s(u0, v0)) * fu;
        const double bottom = s(u0, v0 + 1) + (s(u0 + 1, v0 + 1) - s(u0, v0 + 1)) * fu;
        worst = std::max(worst, float(std::abs(h[std::size_t(j * side + i)] - (top + (bottom - top) * fv))));
      }
    }
  }
  EXPECT_GT(worst, 100.0f) << "the bump is not on the depth-5 surface";
  EXPECT_FLOAT_EQ(store->find(coarse)->stats.geometricErrorM, worst);
}

TEST(GlobalStore, RegionsReadMissingTilesFromTheirAncestors) {
  const std::shared_ptr<GlobalStore> store = GlobalStore::open(earth()).value();
  // Depth 6 over a box half inside the fine source: stored tiles and upsampled ones.
  Result<HeightGrid> grid = readGlobalRegion(*store, 6, {8.0, 39.0, 12.0, 42.0});
  ASSERT_TRUE(grid) << grid.error().message;
  const double step = GlobalTiling::tileSizeDeg(6) / store->tileCells();
  EXPECT_NEAR(grid->georef.geoTransform[1], step, 1e-12);
  EXPECT_TRUE(grid->georef.isGeographic);
  // Every sample is the store's surface there (the coarse field away from the bump).
  for (int j = 0; j < grid->height; j += 7) {
    for (int i = 0; i < grid->width; i += 7) {
      const double lat = grid->georef.geoTransform[3] + (j + 0.5) * grid->georef.geoTransform[5];
      const double lon = grid->georef.geoTransform[0] + (i + 0.5) * grid->georef.geoTransform[1];
      EXPECT_NEAR(grid->at(i, j), fineHeight(lat, lon), 150.0) << lat << " " << lon;
    }
  }
  // The whole globe at depth 1: all longitudes once (the mesh closes the seam).
  Result<HeightGrid> globe = readGlobalRegion(*store, 1, {-180.0, -90.0, 180.0, 90.0});
  ASSERT_TRUE(globe);
  EXPECT_EQ(globe->width, 4 * 16);
  EXPECT_EQ(globe->height, 2 * 16 + 1);
  EXPECT_FALSE(readGlobalRegion(*store, 9, {-180.0, -90.0, 180.0, 90.0}, 1'000'000));
}

// The store's surface is one function of the point (storeSampleSource): on a tile edge where
// the store's depth changes the deepest source wins, so the surface of one depth equals the next
// depth's on every common sample point, across the fine source's border too (where an upsampled
// tile's interpolation and a stored tile's data differ), and each sample is what
// storeSampleSource says.
TEST(GlobalStore, RegionsOfConsecutiveDepthsAgreeOnTheirCommonPoints) {
  const std::shared_ptr<GlobalStore> store = GlobalStore::open(earth()).value();
  const GeoBounds box{8.0, 38.5, 13.5, 43.5};  // the fine area and sparse ground around it
  const int n = store->tileCells();
  int edgeWins = 0;  // edge samples whose source is a neighbour's, deeper one
  for (int depth = 4; depth <= 10; ++depth) {
    Result<HeightGrid> coarse = readGlobalRegion(*store, depth, box);
    Result<HeightGrid> fine = readGlobalRegion(*store, depth + 1, box);
    ASSERT_TRUE(coarse && fine);
    // Sample (i, j) of `coarse` is sample (2i + di, 2j + dj) of `fine`: both grids start at the
    // box's west and north snapped outward to their own samples (di, dj: -1, 0 or 1).
    const auto& gc = coarse->georef.geoTransform;
    const auto& gf = fine->georef.geoTransform;
    const int di = int(std::lround((gc[0] + 0.5 * gc[1] - gf[0] - 0.5 * gf[1]) / gf[1]));
    const int dj = int(std::lround((gc[3] + 0.5 * gc[5] - gf[3] - 0.5 * gf[5]) / gf[5]));
    for (int j = dj < 0 ? 1 : 0; j < coarse->height && 2 * j + dj < fine->height; ++j) {
      for (int i = di < 0 ? 1 : 0; i < coarse->width && 2 * i + di < fine->width; ++i) {
        ASSERT_EQ(coarse->at(i, j), fine->at(2 * i + di, 2 * j + dj))
            << "depth " << depth << " sample " << i << "," << j;
      }
    }
    // The samples on tile edges come from storeSampleSource's choice.
    const double step = GlobalTiling::tileSizeDeg(depth) / n;
    const std::int64_t i0 = std::int64_t(std::lround((gc[0] + 0.5 * gc[1] + 180.0) / step));
    const std::int64_t j0 = std::int64_t(std::lround((90.0 - gc[3] - 0.5 * gc[5]) / step));
    for (int j = 0; j < coarse->height; ++j) {
      for (int i = 0; i < coarse->width; ++i) {
        const std::int64_t gi = i0 + i, gj = j0 + j;
        if (gi % n != 0 && gj % n != 0) continue;
        const GeoTileKey key{depth, int(gi / n), int(gj / n)};
        const StoreSampleSource at = storeSampleSource(*store, key, int(gi % n), int(gj % n));
        std::vector<float> tile(store->tileShape().sampleCount());
        ASSERT_TRUE(store->readTileMetres(at.source, tile));
        EXPECT_EQ(coarse->at(i, j), float(tileSurfaceAt(tile, n, at.u, at.v)));
        edgeWins += at.source.depth > store->deepestStored(key).depth ? 1 : 0;
      }
    }
  }
  EXPECT_GT(edgeWins, 50);
}

TEST(GlobalStore, WithoutAGlobalSourceTheRestIsSeaLevel) {
  const fs::path path = buildStore("fine-only.tstore", {sources().fine});
  const std::shared_ptr<GlobalStore> store = GlobalStore::open(path).value();
  EXPECT_GT(store->metadata().uncoveredSamples, 0u);
  const std::vector<float> h = readTile(*store, {0, 0, 0});
  EXPECT_EQ(*std::max_element(h.begin(), h.end()), 0.0f);
}

std::string fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// The split depth moves work between ranks and between warping and taking every second sample
// of a child: the bytes never change. Sources: the global one with a fine one (complete coarse
// depths), the fine one alone (coarse tiles partly warped, partly taken from their children, and
// every uncovered sample counted once), and a cap over the north pole against the antimeridian
// (warped quarters on the pole row and the 180 E column).
TEST(GlobalStore, TheSplitDepthNeverChangesTheBytes) {
  const fs::path cap =
      writeSource(sources().dir / "cap.tif", 150.0, 90.0, 0.25, 121, 121, coarseHeight);
  const std::vector<std::vector<fs::path>> cases{
      {sources().coarse, sources().fine}, {sources().fine}, {cap}};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    std::string reference;
    std::uint64_t uncovered = 0;
    for (const std::optional<int> split : {std::optional<int>(), std::optional<int>(0),
                                           std::optional<int>(2), std::optional<int>(5),
                                           std::optional<int>(9)}) {
      GlobalBuildOptions options;
      options.tileCells = 16;
      options.splitDepth = split;
      const fs::path out = sources().dir / fmt::format("split-{}-{}.tstore", c, split.value_or(-1));
      Result<GlobalBuildReport> report = buildGlobalStore(cases[c], out, options);
      ASSERT_TRUE(report) << report.error().message;
      const std::string bytes = fileBytes(out);
      if (reference.empty()) {
        reference = bytes;
        uncovered = report->metadata.uncoveredSamples;
        EXPECT_GE(report->subtrees, 1u);
      } else {
        EXPECT_TRUE(bytes == reference) << "case " << c << ", split depth " << *split;
        EXPECT_EQ(report->metadata.uncoveredSamples, uncovered) << "case " << c;
      }
    }
  }
}

// build --global --update: a new fine source added to a store rebuilds only what it reaches and
// gives the bytes of a build of all the sources; what cannot be an update is refused.
TEST(GlobalStore, AnUpdateEqualsAFullBuildAndRewritesOnlyWhatTheNewSourceReaches) {
  const fs::path dir = sources().dir;
  // A second fine source across the first one's north-eastern corner (11.5..12.5 E, 41.5..42.5
  // N): tiles of the old store below the split that it reaches must be warped again.
  const fs::path second = writeSource(dir / "second.tif", 11.5, 42.5, 0.02, 51, 51, coarseHeight);
  GlobalBuildOptions options;
  options.tileCells = 16;
  const fs::path before = dir / "update-before.tstore";
  Result<GlobalBuildReport> built = buildGlobalStore({sources().coarse, sources().fine}, before, options);
  ASSERT_TRUE(built) << built.error().message;
  EXPECT_EQ(built->tilesRewritten, built->tiles) << "without an update every tile is written";
  const GlobalStoreMetadata& m = built->metadata;
  // The previous store's sources, in its order (finest first), then the new one.
  std::vector<fs::path> inputs;
  for (const GlobalStoreSource& source : m.sources) inputs.emplace_back(source.path);
  inputs.push_back(second);
  GlobalBuildOptions update = options;
  update.update = GlobalBuildOptions::Update{before, m.sources.size()};
  const fs::path after = dir / "update-after.tstore";
  Result<GlobalBuildReport> updated = buildGlobalStore(inputs, after, update);
  ASSERT_TRUE(updated) << updated.error().message;
  const fs::path full = dir / "update-full.tstore";
  Result<GlobalBuildReport> rebuilt = buildGlobalStore(inputs, full, options);
  ASSERT_TRUE(rebuilt) << rebuilt.error().message;
  EXPECT_TRUE(fileBytes(after) == fileBytes(full)) << "the update differs from a full build";
  // Only the new source's tiles and their ancestors change; most of the old ones are read back.
  EXPECT_GT(updated->tilesRewritten, 0u);
  EXPECT_LT(updated->tilesRewritten, updated->tiles / 2);
  EXPECT_GT(updated->tilesReadBack, 0u);
  EXPECT_LT(updated->tilesWarped, rebuilt->tilesWarped);
  // Refused: writing over the store it reads, other options, a store without per-tile counts.
  Result<GlobalBuildReport> over = buildGlobalStore(inputs, before, update);
  ASSERT_FALSE(over);
  EXPECT_NE(over.error().message.find("another path"), std::string::npos) << over.error().message;
  GlobalBuildOptions otherTiles = update;
  otherTiles.tileCells = 32;
  Result<GlobalBuildReport> other = buildGlobalStore(inputs, dir / "update-other.tstore", otherTiles);
  ASSERT_FALSE(other);
  EXPECT_NE(other.error().message.find("--tile 16"), std::string::npos) << other.error().message;
  EXPECT_TRUE(fs::exists(before));
  EXPECT_FALSE(fs::exists(dir / "update-other.tstore"));
}

TEST(GlobalStore, CorruptionAndWrongKindsAreReported) {
  const fs::path copy = sources().dir / "corrupt.tstore";
  fs::copy_file(earth(), copy, fs::copy_options::overwrite_existing);
  const std::shared_ptr<GlobalStore> store = GlobalStore::open(earth()).value();
  const TileRecord& victim = store->records()[5];
  {
    std::fstream f(copy, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(victim.payloadOffset + victim.payloadBytes / 2));
    const char x = 0x5a;
    f.write(&x, 1);
  }
  const std::shared_ptr<GlobalStore> corrupt = GlobalStore::open(copy).value();
  std::vector<float> h(corrupt->tileShape().sampleCount());
  const Status read = corrupt->readTileMetres(GlobalStore::toGeoKey(victim.key), h);
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("corrupt"), std::string::npos);
  EXPECT_NE(read.error().message.find(GlobalStore::describe(GlobalStore::toGeoKey(victim.key))),
            std::string::npos);
  // Truncated: refused on open.
  fs::resize_file(copy, fs::file_size(copy) - 10);
  EXPECT_FALSE(GlobalStore::open(copy));
  // A global store is not a flat one, and the other way round.
  Result<std::shared_ptr<TileStore>> flat = TileStore::open(earth());
  ASSERT_FALSE(flat);
  EXPECT_NE(flat.error().message.find("global store"), std::string::npos);
  EXPECT_TRUE(isGlobalStore(earth()));
  EXPECT_FALSE(isGlobalStore(sources().coarse));
}

// Terrarium's heights at the fine source's samples: whole 1/256 m, as the encoding stores them.
double terrariumHeight(double lat, double lon) {
  return std::round(fineHeight(lat, lon) * 256.0) / 256.0;
}

// The fine source's grid as a Terrarium-encoded RGB GeoTIFF (R * 256 + G + B / 256 - 32768 m).
fs::path writeTerrariumSource(const fs::path& path) {
  const int side = 101;
  const double west = 10.0, north = 42.0, step = 0.02;
  GDALAllRegister();
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(
      path.c_str(), side, side, 3, GDT_Byte, nullptr);
  EXPECT_NE(ds, nullptr);
  double gt[6] = {west - 0.5 * step, step, 0.0, north + 0.5 * step, 0.0, -step};
  ds->SetGeoTransform(gt);
  ds->SetProjection(kWgs84Wkt);
  std::vector<std::uint8_t> rgb(std::size_t(side) * side * 3);
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const auto v = std::int64_t(std::llround((terrariumHeight(north - j * step, west + i * step) + 32768.0) * 256.0));
      const std::size_t k = std::size_t(j) * side + std::size_t(i);
      rgb[k] = std::uint8_t(v >> 16);
      rgb[std::size_t(side) * side + k] = std::uint8_t((v >> 8) & 0xff);
      rgb[2 * std::size_t(side) * side + k] = std::uint8_t(v & 0xff);
    }
  }
  EXPECT_EQ(ds->RasterIO(GF_Write, 0, 0, side, side, rgb.data(), side, side, GDT_Byte, 3, nullptr,
                         0, 0, 0),
            CE_None);
  GDALClose(ds);
  return path;
}

TEST(GlobalStore, ATerrariumSourceGivesTheStoreItsDecodedHeightsGive) {
  // A folder inside the shared sources' (freshTestDir() would empty theirs when they are made
  // by this test: one folder per test name).
  const fs::path dir = sources().dir / "terrarium";
  fs::create_directories(dir);
  const fs::path terrarium = writeTerrariumSource(dir / "fine-terrarium.tif");
  const fs::path decoded = writeSource(dir / "fine-256.tif", 10.0, 42.0, 0.02, 101, 101,
                                       terrariumHeight);
  GlobalBuildOptions options;
  options.tileCells = 16;
  // Without --encoding the colour image is refused, by name.
  Result<GlobalBuildReport> refused =
      buildGlobalStore({sources().coarse, terrarium}, dir / "refused.tstore", options);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("fine-terrarium.tif"), std::string::npos);
  EXPECT_NE(refused.error().message.find("--encoding"), std::string::npos);

  Result<GlobalBuildReport> plain =
      buildGlobalStore({sources().coarse, decoded}, dir / "plain.tstore", options);
  options.rgbEncoding = HeightEncoding::Terrarium;
  Result<GlobalBuildReport> encoded =
      buildGlobalStore({sources().coarse, terrarium}, dir / "terrarium.tstore", options);
  ASSERT_TRUE(plain) << plain.error().message;
  ASSERT_TRUE(encoded) << encoded.error().message;
  EXPECT_EQ(encoded->metadata.sources.at(0).path, terrarium.string());  // named as given
  Result<std::shared_ptr<GlobalStore>> a = GlobalStore::open(dir / "plain.tstore");
  Result<std::shared_ptr<GlobalStore>> b = GlobalStore::open(dir / "terrarium.tstore");
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a.value()->records().size(), b.value()->records().size());
  EXPECT_EQ(b.value()->metadata().deepestDepth, 9);
  for (const TileRecord& record : a.value()->records()) {
    const GeoTileKey key = GlobalStore::toGeoKey(record.key);
    ASSERT_NE(b.value()->find(key), nullptr) << GlobalStore::describe(key);
    ASSERT_EQ(readTile(*a.value(), key), readTile(*b.value(), key)) << GlobalStore::describe(key);
  }
  // The decoded copy went with its scratch folder.
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tellus-scratch"), std::string::npos)
        << entry.path();
  }
}

// A land source storing its sea as exactly 0 m (as SRTM does) over a coarse source's sea floor:
// by default the sea floor shows through, with the fine source's coastline; --zero-is-land keeps
// the zeros. Land is the fine source's either way.
double coastHeight(double lat, double lon) {
  return lon < 41.0 ? 0.0 : 50.0 + 10.0 * (lat - 40.0);
}

TEST(GlobalStore, AFineSourcesZeroSeaYieldsToTheCoarseSeaFloor) {
  const fs::path dir = sources().dir / "sea";  // (as above)
  fs::create_directories(dir);
  // 40..42 E, 40..42 N, where the coarse field is a sea floor of about -1,500 m.
  const fs::path coast = writeSource(dir / "coast.tif", 40.0, 42.0, 0.02, 101, 101, coastHeight);
  GlobalBuildOptions options;
  options.tileCells = 16;
  ASSERT_TRUE(buildGlobalStore({sources().coarse, coast}, dir / "sea.tstore", options));
  options.zeroYieldsToSeaFloor = false;
  ASSERT_TRUE(buildGlobalStore({sources().coarse, coast}, dir / "zero.tstore", options));
  Result<std::shared_ptr<GlobalStore>> sea = GlobalStore::open(dir / "sea.tstore");
  Result<std::shared_ptr<GlobalStore>> zero = GlobalStore::open(dir / "zero.tstore");
  ASSERT_TRUE(sea && zero);
  EXPECT_TRUE(sea.value()->metadata().zeroYieldsToSeaFloor);
  EXPECT_FALSE(zero.value()->metadata().zeroYieldsToSeaFloor);
  const GeoBounds box{40.2, 40.2, 41.8, 41.8};
  Result<HeightGrid> withSea = readGlobalRegion(*sea.value(), 9, box);
  Result<HeightGrid> withZero = readGlobalRegion(*zero.value(), 9, box);
  ASSERT_TRUE(withSea && withZero);
  ASSERT_EQ(withSea->width, withZero->width);
  const auto& gt = withSea->georef.geoTransform;
  int seaSamples = 0, landSamples = 0;
  for (int j = 0; j < withSea->height; ++j) {
    for (int i = 0; i < withSea->width; ++i) {
      const double lon = gt[0] + (i + 0.5) * gt[1], lat = gt[3] + (j + 0.5) * gt[5];
      if (lon < 40.9) {  // the fine source's sea: the coarse sea floor, or 0 m
        ++seaSamples;
        EXPECT_EQ(withZero->at(i, j), 0.0f);
        EXPECT_NEAR(withSea->at(i, j), coarseHeight(lat, lon), 60.0) << lat << " " << lon;
        EXPECT_LT(withSea->at(i, j), -1000.0f);
      } else if (lon > 41.1) {  // land: the fine source in both
        ++landSamples;
        EXPECT_EQ(withSea->at(i, j), withZero->at(i, j));
        EXPECT_NEAR(withSea->at(i, j), coastHeight(lat, lon), 0.01);
      }
    }
  }
  EXPECT_GT(seaSamples, 1000);
  EXPECT_GT(landSamples, 1000);
}

// A fine source 800 m above the coarse field over 20..22 E, 40..42 N: without blending its
// edge is an 800 m cliff.
double raisedHeight(double lat, double lon) { return coarseHeight(lat, lon) + 800.0; }

const fs::path& raisedSource() {
  static const fs::path path =
      writeSource(sources().dir / "raised.tif", 20.0, 42.0, 0.02, 101, 101, raisedHeight);
  return path;
}

// The warper's values on a 0.005-degree grid over the raised source's south-west corner.
std::vector<float> warpCorner(const std::vector<fs::path>& inputs, double edgeBlendM) {
  std::vector<LatLonSource> described;
  for (const fs::path& input : inputs) described.push_back(describeLatLonSource(input).value());
  std::unique_ptr<LatLonWarper> warper =
      LatLonWarper::open(described, false, edgeBlendM).value();
  std::vector<int> use(described.size());
  for (std::size_t i = 0; i < use.size(); ++i) use[i] = int(i);
  std::vector<float> out(200 * 200);
  EXPECT_TRUE(warper->warp(19.8, 40.8, 0.005, 200, 200, use, out));
  return out;
}

// Edge blending: a point takes w * fine + (1 - w) * coarse, w the smoothstep of its distance
// inside the fine source's outermost samples over the band; exactly the fine source beyond the
// band and exactly the coarse one outside the source.
TEST(GlobalStore, TheWarperBlendsASourceIntoTheNextOverItsEdgeBand) {
  constexpr double kBandM = 30'000.0;
  const std::vector<float> blended = warpCorner({raisedSource(), sources().coarse}, kBandM);
  const std::vector<float> fine = warpCorner({raisedSource()}, 0.0);
  const std::vector<float> coarse = warpCorner({sources().coarse}, 0.0);
  const std::vector<float> sharp = warpCorner({raisedSource(), sources().coarse}, 0.0);
  int inBand = 0, beyond = 0, outside = 0;
  for (int j = 0; j < 200; ++j) {
    for (int i = 0; i < 200; ++i) {
      const std::size_t k = std::size_t(j) * 200 + std::size_t(i);
      const double lon = 19.8 + i * 0.005, lat = 40.8 - j * 0.005;
      // Distance inside the west and south edges (the others are over 100 km away).
      const double inside = std::min((lon - 20.0) * 111'320.0 * std::cos(lat * kDeg),
                                     (lat - 40.0) * 111'320.0);
      if (inside <= 0.0) {
        EXPECT_EQ(blended[k], coarse[k]) << lat << " " << lon;
        ++outside;
      } else if (inside >= kBandM) {
        EXPECT_EQ(blended[k], fine[k]) << lat << " " << lon;
        ++beyond;
      } else {
        const double t = inside / kBandM, w = t * t * (3.0 - 2.0 * t);
        ASSERT_NEAR(blended[k], w * fine[k] + (1.0 - w) * coarse[k], 1e-3) << lat << " " << lon;
        ++inBand;
      }
    }
  }
  EXPECT_GT(inBand, 5000);
  EXPECT_GT(beyond, 5000);
  EXPECT_GT(outside, 5000);
  // Without a band the fine source's edge is a cliff; with it no step between neighbours is
  // more than the band's steepest slope allows (800 m * 1.5 / 30 km a metre).
  const auto steepest = [](const std::vector<float>& h) {
    float worst = 0.0f;
    for (int j = 0; j < 200; ++j) {
      for (int i = 0; i + 1 < 200; ++i) {
        worst = std::max(worst, std::abs(h[std::size_t(j * 200 + i + 1)] - h[std::size_t(j * 200 + i)]));
      }
    }
    return worst;
  };
  EXPECT_GT(steepest(sharp), 700.0f);
  EXPECT_LT(steepest(blended), 800.0f * 1.5f * 0.005f * 111'320.0f * 0.76f / 30'000.0f + 10.0f);
}

// A projected source (UTM 33N, like `tellus generate`'s ranges) fades out towards its own grid's
// edges: at its outermost sample centres the coarse field, a band inside them its own heights.
TEST(GlobalStore, AProjectedSourceBlendsTowardsItsGridsEdges) {
  OGRSpatialReference utm;
  utm.importFromEPSG(32633);
  char* wkt = nullptr;
  utm.exportToWkt(&wkt);
  HeightGrid grid(201, 201);  // 20 km at 100 m, its west edge at 500,000 m E (15 E)
  for (float& h : grid.heights) h = 5000.0f;
  grid.georef.crsWkt = wkt ? wkt : "";
  grid.georef.isGeographic = false;
  CPLFree(wkt);
  grid.georef.hasGeoTransform = true;
  grid.georef.geoTransform = {499'950.0, 100.0, 0.0, 5'100'050.0, 0.0, -100.0};
  const fs::path path = sources().dir / "utm.tif";
  ASSERT_TRUE(writeGeoTiff(grid, path));
  std::vector<LatLonSource> described = {describeLatLonSource(path).value(),
                                         describeLatLonSource(sources().coarse).value()};
  std::unique_ptr<LatLonWarper> warper = LatLonWarper::open(described, false, 5'000.0).value();
  std::unique_ptr<OGRCoordinateTransformation> toLatLon(
      OGRCreateCoordinateTransformation(&utm, [] {
        static OGRSpatialReference wgs84;
        wgs84.SetWellKnownGeogCS("WGS84");
        wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        return &wgs84;
      }()));
  ASSERT_TRUE(toLatLon);
  const std::vector<int> both = {0, 1}, coarseOnly = {1};
  // Along the grid's west edge (x = 500,000 m) and over 5 km inside it, every 2 km of northing
  // at least 6 km from its north and south edges.
  for (double northing = 5'086'000.0; northing <= 5'094'000.0; northing += 2'000.0) {
    for (const double easting : {500'000.0, 506'000.0, 510'000.0}) {
      double lon = easting, lat = northing;
      ASSERT_TRUE(toLatLon->Transform(1, &lon, &lat));
      float h = 0.0f, coarse = 0.0f;
      ASSERT_TRUE(warper->warp(lon, lat, 1e-4, 1, 1, both, std::span<float>(&h, 1)));
      ASSERT_TRUE(warper->warp(lon, lat, 1e-4, 1, 1, coarseOnly, std::span<float>(&coarse, 1)));
      if (easting == 500'000.0) {
        EXPECT_NEAR(h, coarse, 0.01) << "on the edge: the coarse field";
        EXPECT_GT(std::abs(coarse - 5000.0f), 1000.0f);
      } else {
        EXPECT_NEAR(h, 5000.0f, 1e-3) << "a band inside: the source's own height";
      }
    }
  }
}

// A store built with a band: its tiles still share edges and nest bit for bit, it says its
// band, and the raised source meets the coarse field without a cliff.
TEST(GlobalStore, AStoreWithBlendedEdgesIsStillExactAndHasNoCliff) {
  GlobalBuildOptions options;
  options.tileCells = 16;
  options.edgeBlendM = 30'000.0;
  const fs::path blended = sources().dir / "blended.tstore";
  ASSERT_TRUE(buildGlobalStore({sources().coarse, raisedSource()}, blended, options));
  options.edgeBlendM = 0.0;
  const fs::path sharp = sources().dir / "sharp.tstore";
  ASSERT_TRUE(buildGlobalStore({sources().coarse, raisedSource()}, sharp, options));
  expectEdgesNestingAndPolesExact(blended);
  const std::shared_ptr<GlobalStore> store = GlobalStore::open(blended).value();
  EXPECT_EQ(store->metadata().edgeBlendM, 30'000.0);
  EXPECT_EQ(GlobalStore::open(sharp).value()->metadata().edgeBlendM, 0.0);
  // Along 41 N across the west edge, at depth 9 (0.022-degree samples).
  const GeoBounds box{19.5, 40.9, 20.8, 41.1};
  const auto steepestStep = [&](const fs::path& path) {
    const HeightGrid grid = readGlobalRegion(*GlobalStore::open(path).value(), 9, box).value();
    float worst = 0.0f;
    const int j = grid.height / 2;
    for (int i = 0; i + 1 < grid.width; ++i) {
      worst = std::max(worst, std::abs(grid.at(i + 1, j) - grid.at(i, j)));
    }
    return worst;
  };
  EXPECT_GT(steepestStep(sharp), 700.0f);
  EXPECT_LT(steepestStep(blended), 100.0f);
  options.edgeBlendM = -1.0;
  EXPECT_FALSE(buildGlobalStore({sources().coarse, raisedSource()}, sources().dir / "bad-band.tstore", options));
  EXPECT_FALSE(fs::exists(sources().dir / "bad-band.tstore"));
}

TEST(GlobalStore, BadBuildsFailCleanly) {
  GlobalBuildOptions options;
  options.tileCells = 16;
  const fs::path out = sources().dir / "bad.tstore";
  EXPECT_FALSE(buildGlobalStore({}, out, options));
  EXPECT_FALSE(buildGlobalStore({sources().coarse}, sources().coarse, options));
  EXPECT_FALSE(buildGlobalStore({sources().dir / "missing.tif"}, out, options));
  // A grid without georeferencing, and one in 0..360 longitudes.
  HeightGrid plain(8, 8);
  ASSERT_TRUE(writeGeoTiff(plain, sources().dir / "plain.tif"));
  Result<GlobalBuildReport> noGeoref = buildGlobalStore({sources().dir / "plain.tif"}, out, options);
  ASSERT_FALSE(noGeoref);
  EXPECT_NE(noGeoref.error().message.find("plain.tif"), std::string::npos);
  writeSource(sources().dir / "wrapped.tif", 100.0, 10.0, 2.0, 100, 5, coarseHeight);
  Result<GlobalBuildReport> wrapped = buildGlobalStore({sources().dir / "wrapped.tif"}, out, options);
  ASSERT_FALSE(wrapped);
  EXPECT_NE(wrapped.error().message.find("-180..180"), std::string::npos) << wrapped.error().message;
  options.tileCells = 100;
  EXPECT_FALSE(buildGlobalStore({sources().coarse}, out, options));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace tellus
