// Writes seed inputs for the fuzz targets: valid encodings of small tiles for each codec (with
// the fuzz targets' two shape bytes in front) and a small valid store.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "tellus/tiles/tile_codec.hpp"
#include "tellus/tiles/tile_store_writer.hpp"

namespace fs = std::filesystem;
using namespace tellus;

namespace {

std::vector<std::int32_t> hill(TileShape shape, int seed) {
  std::vector<std::int32_t> v(shape.sampleCount());
  for (int j = 0; j < shape.height; ++j)
    for (int i = 0; i < shape.width; ++i)
      v[std::size_t(j * shape.width + i)] = std::int32_t(
          500.0 * std::sin(0.2 * i + seed) * std::cos(0.15 * j) + 37 * ((i * j + seed) % 7));
  return v;
}

bool writeBytes(const fs::path& path, const std::vector<std::byte>& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fwrite(bytes.data(), 1, bytes.size(), f);
  return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seed_corpus OUTPUT_FOLDER\n");
    return 2;
  }
  const fs::path root = argv[1];
  for (const std::string& name : codecNames()) {
    fs::create_directories(root / name);
    auto codec = makeCodec(name, {.maxErrorSteps = 3, .zstdLevel = 3});
    int index = 0;
    for (TileShape shape : {TileShape{17, 17}, TileShape{5, 9}, TileShape{33, 2}}) {
      std::vector<std::byte> bytes{std::byte(shape.width - 1), std::byte(shape.height - 1)};
      if (!codec.value()->encode(hill(shape, index), shape, bytes)) return 1;
      if (!writeBytes(root / name / ("seed" + std::to_string(index++)), bytes)) return 1;
    }
  }
  // A 3-level store of 33x33 samples in 16-cell tiles, zstd.
  fs::create_directories(root / "store");
  const fs::path store = root / "store" / "seed.tstore";
  auto codec = makeCodec("zstd", {.maxErrorSteps = 0, .zstdLevel = 3});
  StoreMetadata m;
  m.layout = PyramidLayout::create(33, 33, 16).value();
  m.codec = "zstd";
  m.producer = "make_seed_corpus";
  auto writer = TileStoreWriter::create(store, CodecId::Zstd);
  if (!writer) return 1;
  for (int level = 0; level < m.layout.levelCount(); ++level) {
    for (int y = 0; y < m.layout.tilesY(level); ++y) {
      for (int x = 0; x < m.layout.tilesX(level); ++x) {
        std::vector<std::byte> payload;
        if (!codec.value()->encode(hill(m.layout.tileShape(), level + x + y), m.layout.tileShape(),
                                   payload))
          return 1;
        if (!writer.value()->append({level, x, y}, payload, {0.0f, 1.0f, 0.0f})) return 1;
      }
    }
  }
  return writer.value()->finish(m) ? 0 : 1;
}
