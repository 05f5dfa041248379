// libFuzzer target: the tile store reader on arbitrary file contents. Opening must fail cleanly
// or succeed, and then every tile must read, or fail with a message, without crashing.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "tellus/tiles/tile_store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("tellus-fuzz-store-" + std::to_string(::getpid()));
  if (std::FILE* file = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, file);
    std::fclose(file);
  }
  auto store = tellus::TileStore::open(path);
  if (!store) return 0;
  std::vector<std::int32_t> samples(store.value()->layout().tileShape().sampleCount());
  for (const tellus::TileRecord& record : store.value()->records()) {
    (void)store.value()->readTile(record.key, samples);
  }
  return 0;
}
