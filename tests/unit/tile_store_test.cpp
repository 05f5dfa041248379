// The pyramid builder and the store: real DEMs in, every tile checked against the source;
// shared edges, level consistency, exact geometric errors, georeferencing, and corruption of
// every part of the file detected with a message naming the tile.
#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/tiles/pyramid_builder.hpp"
#include "tellus/tiles/store_container.hpp"
#include "tellus/tiles/store_format.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

struct BuiltStore {
  fs::path path;
  HeightGrid source;
};

// N37E127 (1201x1201 SRTM, integer metres) with 128-cell tiles: 10x10 tiles, 5 levels.
BuiltStore buildN37E127(const fs::path& data, const std::string& codec,
                        std::optional<double> maxError = std::nullopt) {
  const fs::path input = data / "srtm3-hgt-east-asia/N37E127.hgt";
  BuiltStore built;
  built.path = test::freshTestDir() / ("n37e127-" + codec + ".tstore");
  BuildOptions options;
  options.tileSize = 128;
  options.codec = codec;
  options.maxErrorM = maxError;
  Result<BuildReport> report = buildPyramid({input}, built.path, options);
  EXPECT_TRUE(report) << report.error().message;
  Result<HeightGrid> grid = loadDem({input});
  EXPECT_TRUE(grid);
  built.source = std::move(grid.value());
  return built;
}

float clampedSource(const HeightGrid& g, long col, long row) {
  return g.at(int(std::min<long>(col, g.width - 1)), int(std::min<long>(row, g.height - 1)));
}

TEST(PyramidBuilder, EveryTileIsTheSubsampledSourceAndEdgesAreShared) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const BuiltStore built = buildN37E127(data, "zstd");
  Result<std::shared_ptr<TileStore>> store = TileStore::open(built.path);
  ASSERT_TRUE(store) << store.error().message;
  const PyramidLayout& layout = store.value()->layout();
  EXPECT_EQ(layout.levelCount(), 5);
  EXPECT_EQ(layout.tilesX(0), 10);
  EXPECT_EQ(layout.tilesX(4), 1);
  EXPECT_EQ(store.value()->metadata().maxErrorM, 0.0);  // integer input, lossless codec
  const int n = layout.tileSize();
  std::vector<float> tile(layout.tileShape().sampleCount()), east(tile.size());
  for (const TileRecord& record : store.value()->records()) {
    const TileKey k = record.key;
    ASSERT_TRUE(store.value()->readTileMetres(k, tile)) << TileStore::describe(k);
    const long stride = PyramidLayout::stride(k.level);
    float lo = 1e9f, hi = -1e9f;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const float v = tile[std::size_t(j * (n + 1) + i)];
        const float source =
            clampedSource(built.source, (long(k.x) * n + i) * stride, (long(k.y) * n + j) * stride);
        // Integer input heights are stored exactly; filled voids are rounded to the quantum.
        ASSERT_LE(std::abs(v - source), source == std::round(source) ? 0.0f : 0.5f)
            << TileStore::describe(k) << " sample " << i << "," << j;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    EXPECT_EQ(record.stats.minHeightM, lo);
    EXPECT_EQ(record.stats.maxHeightM, hi);
    if (k.x + 1 < layout.tilesX(k.level)) {
      ASSERT_TRUE(store.value()->readTileMetres({k.level, k.x + 1, k.y}, east));
      for (int j = 0; j <= n; ++j) {
        ASSERT_EQ(tile[std::size_t(j * (n + 1) + n)], east[std::size_t(j * (n + 1))]);
      }
    }
  }
}

TEST(PyramidBuilder, GeometricErrorsMatchABruteForceMeasurement) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const BuiltStore built = buildN37E127(data, "zstd");
  Result<std::shared_ptr<TileStore>> store = TileStore::open(built.path);
  ASSERT_TRUE(store);
  const int n = store.value()->layout().tileSize();
  for (const TileKey key : {TileKey{1, 2, 3}, TileKey{2, 1, 1}, TileKey{4, 0, 0}}) {
    const long s = PyramidLayout::stride(key.level);
    const long x0 = long(key.x) * n * s, y0 = long(key.y) * n * s;
    double worst = 0.0;
    for (long y = y0; y <= y0 + n * s; ++y) {
      for (long x = x0; x <= x0 + n * s; ++x) {
        // The level's cell holding (x, y): its north-west sample (cx, cy).
        const long cx = x0 + std::min((x - x0) / s, long(n) - 1) * s;
        const long cy = y0 + std::min((y - y0) / s, long(n) - 1) * s;
        const double tx = double(x - cx) / double(s), ty = double(y - cy) / double(s);
        const double h00 = clampedSource(built.source, cx, cy),
                     h10 = clampedSource(built.source, cx + s, cy);
        const double h01 = clampedSource(built.source, cx, cy + s),
                     h11 = clampedSource(built.source, cx + s, cy + s);
        const double surface =
            (h00 * (1 - tx) + h10 * tx) * (1 - ty) + (h01 * (1 - tx) + h11 * tx) * ty;
        worst = std::max(worst, std::abs(double(clampedSource(built.source, x, y)) - surface));
      }
    }
    EXPECT_NEAR(store.value()->find(key)->stats.geometricErrorM, worst, 1e-3)
        << TileStore::describe(key);
    EXPECT_GT(worst, 1.0);
  }
  EXPECT_EQ(store.value()->find({0, 3, 3})->stats.geometricErrorM, 0.0f);
}

TEST(PyramidBuilder, LossyStoresKeepTheirBoundAgainstTheSource) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  for (const char* codec : {"bounded", "lerc"}) {
    const BuiltStore built = buildN37E127(data, codec, 2.0);
    Result<std::shared_ptr<TileStore>> store = TileStore::open(built.path);
    ASSERT_TRUE(store);
    EXPECT_EQ(store.value()->metadata().maxErrorM, 2.0);
    Result<HeightGrid> level0 = readStoreLevel(*store.value(), 0);
    ASSERT_TRUE(level0);
    float worst = 0.0f, worstFilled = 0.0f;
    for (std::size_t i = 0; i < level0->heights.size(); ++i) {
      const float source = built.source.heights[i];
      const float error = std::abs(level0->heights[i] - source);
      float& bucket =
          source == std::round(source) ? worst : worstFilled;  // filled voids are fractional
      bucket = std::max(bucket, error);
    }
    EXPECT_LE(worst, 2.0f) << codec;
    EXPECT_LE(worstFilled, 2.5f) << codec << ": filled voids add the quantum's rounding";
    EXPECT_GE(worst, 1.0f) << codec;
  }
}

TEST(PyramidBuilder, ReadStoreLevelKeepsTheGeoreferencing) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const BuiltStore built = buildN37E127(data, "zstd");
  Result<std::shared_ptr<TileStore>> store = TileStore::open(built.path);
  ASSERT_TRUE(store);
  Result<HeightGrid> level0 = readStoreLevel(*store.value(), 0);
  Result<HeightGrid> level2 = readStoreLevel(*store.value(), 2);
  ASSERT_TRUE(level0 && level2);
  for (std::size_t i = 0; i < level0->heights.size(); ++i) {
    ASSERT_NEAR(level0->heights[i], built.source.heights[i], 0.5f);
  }
  EXPECT_EQ(level0->georef.geoTransform, built.source.georef.geoTransform);
  EXPECT_EQ(level2->width, 301);
  EXPECT_DOUBLE_EQ(level2->spacingXM, 4 * built.source.spacingXM);
  // Sample centre (c, r) of level 2 is sample centre (4c, 4r) of level 0.
  const auto& g0 = level0->georef.geoTransform;
  const auto& g2 = level2->georef.geoTransform;
  EXPECT_NEAR(g2[0] + 0.5 * g2[1], g0[0] + 0.5 * g0[1], 1e-12);
  EXPECT_NEAR(g2[0] + 10.5 * g2[1], g0[0] + 40.5 * g0[1], 1e-12);
  EXPECT_NEAR(g2[3] + 10.5 * g2[5], g0[3] + 40.5 * g0[5], 1e-12);
  EXPECT_FALSE(readStoreLevel(*store.value(), 5));
}

// --- corruption ------------------------------------------------------------------------------

std::vector<char> readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
void writeFile(const fs::path& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

TEST(TileStore, CorruptionIsDetectedWhereverItIs) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const BuiltStore built = buildN37E127(data, "bounded", 1.0);
  const std::vector<char> good = readFile(built.path);
  Result<std::shared_ptr<TileStore>> original = TileStore::open(built.path);
  ASSERT_TRUE(original);
  const TileRecord victim = *original.value()->find({1, 2, 2});
  store_format::Header header;
  std::memcpy(&header, good.data(), sizeof(header));
  const fs::path bad = built.path.parent_path() / "bad.tstore";

  // A flipped byte inside a tile's payload: open succeeds, reading that tile names it.
  std::vector<char> bytes = good;
  bytes[victim.payloadOffset + victim.payloadBytes / 2] ^= 0x10;
  writeFile(bad, bytes);
  Result<std::shared_ptr<TileStore>> store = TileStore::open(bad);
  ASSERT_TRUE(store);
  std::vector<std::int32_t> samples(store.value()->layout().tileShape().sampleCount());
  Status read = store.value()->readTile({1, 2, 2}, samples);
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("tile 1/2/2"), std::string::npos) << read.error().message;
  EXPECT_TRUE(store.value()->readTile({1, 2, 1}, samples));

  // Flipped bytes in the header, the metadata and the index; truncation; an empty file.
  const std::vector<std::pair<std::size_t, std::string>> flips = {
      {8, "header"}, {header.metadataOffset + 20, "metadata"}, {header.indexOffset + 50, "index"}};
  for (const auto& [offset, what] : flips) {
    bytes = good;
    bytes[offset] ^= 0x01;
    writeFile(bad, bytes);
    Result<std::shared_ptr<TileStore>> opened = TileStore::open(bad);
    ASSERT_FALSE(opened) << what;
    EXPECT_NE(opened.error().message.find(what), std::string::npos) << opened.error().message;
  }
  for (std::size_t size : {std::size_t(0), std::size_t(40), good.size() / 2, good.size() - 1}) {
    bytes.assign(good.begin(), good.begin() + std::ptrdiff_t(size));
    writeFile(bad, bytes);
    EXPECT_FALSE(TileStore::open(bad)) << "truncated to " << size;
  }
  EXPECT_FALSE(TileStore::open(built.path.parent_path() / "missing.tstore"));
}

TEST(PyramidBuilder, BadOptionsAreRefusedBeforeAnyOutput) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path input = data / "srtm3-hgt-east-asia/N37E127.hgt";
  const fs::path out = test::freshTestDir() / "x.tstore";
  BuildOptions options;
  options.tileSize = 100;
  EXPECT_FALSE(buildPyramid({input}, out, options));
  options = {};
  options.codec = "gzip";
  EXPECT_FALSE(buildPyramid({input}, out, options));
  options = {};
  options.maxErrorM = 1.0;  // zstd is lossless
  EXPECT_FALSE(buildPyramid({input}, out, options));
  options = {};
  options.codec = "bounded";
  options.maxErrorM = -1.0;
  EXPECT_FALSE(buildPyramid({input}, out, options));
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(fs::is_empty(out.parent_path()));
}

TEST(StoreContainer, TheFormatNameIsTheTopLevelObjectsOwn) {
  EXPECT_EQ(storeFormatName(R"({"codec": "zstd", "levels": [{"format": "no"}], "format": "tellus-global-store"})"),
            "tellus-global-store");
  EXPECT_EQ(storeFormatName(R"({"format": "tellus-tile-store", "then": [1, 2)"), "tellus-tile-store");
  EXPECT_EQ(storeFormatName(R"({"inner": {"format": "nested"}})"), "");
  EXPECT_EQ(storeFormatName(R"({"format": 7})"), "");
  EXPECT_EQ(storeFormatName(R"([{"format": "in an array"}])"), "");
  EXPECT_EQ(storeFormatName(R"("format")"), "");
  EXPECT_EQ(storeFormatName("not json"), "");
  EXPECT_EQ(storeFormatName(""), "");
}

}  // namespace
}  // namespace tellus
