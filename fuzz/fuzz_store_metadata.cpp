// libFuzzer target: the JSON metadata of tile stores, flat (tellus/tiles/store_metadata.hpp)
// and global (tellus/tiles/global_store_metadata.hpp: its depths and source list), straight
// from text. Input: [kind u8][JSON text]; an even kind is a flat store's, an odd one a global
// store's. Parsing must fail with a message or give metadata whose every field the store
// readers rely on holds; a parse that succeeds must survive being written and parsed again.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "tellus/tiles/global_store_metadata.hpp"
#include "tellus/tiles/store_metadata.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] % 2 == 0) {
    tellus::Result<tellus::StoreMetadata> m = tellus::metadataFromJson(text);
    if (!m) return 0;
    if (!(m->quantumM > 0.0) || !(m->minHeightM <= m->maxHeightM) || m->layout.levelCount() < 1) std::abort();
    if (!tellus::metadataFromJson(tellus::metadataToJson(m.value()))) std::abort();
    return 0;
  }
  tellus::Result<tellus::GlobalStoreMetadata> g = tellus::globalMetadataFromJson(text);
  if (!g) return 0;
  if (g->sources.empty() || !(g->quantumM > 0.0) || !(g->minHeightM <= g->maxHeightM) ||
      g->tilesPerDepth.size() != std::size_t(g->deepestDepth + 1)) {
    std::abort();
  }
  for (const tellus::GlobalStoreSource& s : g->sources) {
    if (!(s.bounds.westDeg < s.bounds.eastDeg) || !(s.bounds.southDeg < s.bounds.northDeg) ||
        s.depth < 0 || s.depth > g->deepestDepth) {
      std::abort();
    }
  }
  if (!tellus::globalMetadataFromJson(tellus::globalMetadataToJson(g.value()))) std::abort();
  return 0;
}
