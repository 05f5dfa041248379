// libFuzzer target: the tile store readers (flat and global) on arbitrary file contents. The fuzzing build compares
// no checksums (store_checksums.hpp), so mutations reach metadata parsing, index validation and
// decoding with the options the metadata chooses. The container is read once and opened as the
// store its metadata says it is. Opening must fail cleanly or succeed; then
// the first and the last tile are read (in metres too), which must give samples or a message.
// Decoding itself is fuzzed tile by tile by the decoder targets; here it is the store's tile
// shape and codec options, from untrusted metadata, that reach the decoder. The bytes live in
// a memfd (a regular file in memory), so no disk is touched.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_memfd.hpp"
#include "tellus/tiles/global_store.hpp"
#include "tellus/tiles/store_container.hpp"
#include "tellus/tiles/tile_store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = tellus::fuzz::memoryFile(data, size);
  if (path.empty()) return 0;
  static std::vector<std::int32_t> samples;
  static std::vector<float> metres;
  // The container is read once and the store of its format opened from it, as a reader that
  // looks before it opens would.
  tellus::Result<tellus::StoreContainer> container = tellus::readStoreContainer(path);
  if (!container) return 0;
  const bool isGlobal = tellus::storeFormatName(container->metadataJson) == "tellus-global-store";
  if (isGlobal) {
    auto global = tellus::GlobalStore::open(path, std::move(container.value()));
    if (!global) return 0;
    const tellus::GlobalStore& g = *global.value();
    samples.resize(g.tileShape().sampleCount());
    metres.resize(samples.size());
    const auto records = g.records();
    (void)g.readTile(tellus::GlobalStore::toGeoKey(records.front().key), samples);
    (void)g.readTileMetres(tellus::GlobalStore::toGeoKey(records.back().key), metres);
    (void)g.deepestStored(tellus::GlobalTiling::tileAt(tellus::GlobalTiling::kMaxDepth, 10.0, 20.0));
    (void)tellus::readGlobalRegion(g, g.metadata().deepestDepth, {-10.0, -5.0, 10.0, 5.0}, 1 << 16);
    return 0;
  }
  auto store = tellus::TileStore::open(path, std::move(container.value()));
  if (!store) return 0;
  const tellus::TileStore& s = *store.value();
  // Kept between runs (above): a fresh 257 x 257 pair is half a megabyte to zero and page in,
  // which cost more than the parsing this target exists to exercise. The reader writes every
  // sample.
  samples.resize(s.layout().tileShape().sampleCount());
  metres.resize(samples.size());
  const auto records = s.records();
  if (records.empty()) return 0;
  (void)s.readTile(records.front().key, samples);
  (void)s.readTileMetres(records.back().key, metres);
  (void)s.find({records.back().key.level, -1, 0});  // outside the pyramid: nullptr
  return 0;
}
