// libFuzzer target: the quantized-mesh-1.0 tile parser (tellus/export/quantized_mesh.hpp) on
// arbitrary bytes, as the export's own checks and any tool reading Tellus's tiles meet them.
// Parsing must fail with a message or give a tile whose every index names a vertex and whose
// edge lists name vertices on their edges; such a tile must encode again (its indices are in
// first-use order by construction of the coding) and decode to the same tile.
#include <cstdint>
#include <cstdlib>

#include "tellus/export/quantized_mesh.hpp"

namespace {

bool sameTile(const tellus::QuantizedMeshTile& a, const tellus::QuantizedMeshTile& b) {
  return a.u == b.u && a.v == b.v && a.height == b.height && a.indices == b.indices &&
         a.westEdge == b.westEdge && a.southEdge == b.southEdge && a.eastEdge == b.eastEdge &&
         a.northEdge == b.northEdge && a.octNormals == b.octNormals && a.waterMask == b.waterMask;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
  tellus::Result<tellus::QuantizedMeshTile> tile = tellus::decodeQuantizedMesh(bytes, "fuzz tile");
  if (!tile) return 0;
  const std::size_t vertices = tile->u.size();
  for (std::uint32_t index : tile->indices) {
    if (index >= vertices) std::abort();
  }
  for (const auto* edge : {&tile->westEdge, &tile->southEdge, &tile->eastEdge, &tile->northEdge}) {
    for (std::uint32_t index : *edge) {
      if (index >= vertices) std::abort();
    }
  }
  tellus::Result<std::vector<std::byte>> again = tellus::encodeQuantizedMesh(tile.value());
  if (!again) return 0;  // values the encoder refuses (coordinates over 32767) are fine to refuse
  tellus::Result<tellus::QuantizedMeshTile> back = tellus::decodeQuantizedMesh(again.value(), "fuzz tile again");
  if (!back || !sameTile(tile.value(), back.value())) std::abort();
  return 0;
}
