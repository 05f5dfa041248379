#pragma once
// 3D Tiles 1.1 implicit tiling, quadtree subtrees (specification/ImplicitTiling): which tiles of
// a subtree exist, and the binary .subtree file that says so. GL-free.
//
// A subtree holds `levels` levels of the quadtree under its root tile. Its availability
// bitstreams list, level after level, the tiles of that level in Morton order (x in the even
// bits, y in the odd bits of the index, relative to the subtree's root), least significant bit
// first in each byte: tile (d, x, y) of the subtree is bit (4^d - 1) / 3 + morton(x, y). Child
// subtree availability has one bit per tile one level below the subtree's last
// (4^levels bits). A bitstream whose bits are all alike is written as a constant.
//
// The binary form: "subt", version 1 (uint32), the JSON's length and the binary chunk's length
// (uint64 each), the JSON padded with spaces to 8 bytes, the bitstreams (each at an offset that
// is a multiple of 8), the chunk padded with zeros to 8 bytes.
#include <cstdint>
#include <string>
#include <vector>

namespace tellus {

// interleave(x, y): x's bits at the even positions, y's at the odd.
std::uint64_t quadtreeMortonIndex(std::uint32_t x, std::uint32_t y);

struct QuadtreeSubtreeAvailability {
  int levels = 1;
  std::vector<bool> tiles;     // (4^levels - 1) / 3 bits, as above
  std::vector<bool> children;  // 4^levels bits: child subtrees
  // Content availability is that of the tiles (every tile has content) when true, none when
  // false.
  bool contentEverywhereTilesAre = true;
};

// An empty availability of `levels` levels (1..12).
QuadtreeSubtreeAvailability emptySubtreeAvailability(int levels);
// The bit of tile (depth, x, y) of the subtree, depth 0 being its root.
std::size_t subtreeTileBit(int depth, std::uint32_t x, std::uint32_t y);

// The .subtree bytes. The subtree must have at least one available tile (the specification's
// rule), which the caller guarantees.
std::string encodeSubtree(const QuadtreeSubtreeAvailability& availability);

}  // namespace tellus
