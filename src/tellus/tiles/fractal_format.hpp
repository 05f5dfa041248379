#pragma once
// The fractal codec's payload: a FractalCode as bytes, and back (untrusted input).
//
// [u8 version = 1][u8 flags: bit 0 residual, bit 1 exact border][u8 smallest range log2][u8 largest
// range log2] [u8 domain step, 0 = range size][u8 iterations][u16 padded side][i32 base][u32
// residual e] [u16 tile width][u16 tile height] then five streams, each [u32 bytes][u32 zstd frame
// bytes][zstd frame], in quadtree order (top blocks row by row, each depth first: top-left,
// top-right, bottom-left, bottom-right):
//   splits      one byte per quadtree node larger than the smallest range: 1 split, 0 leaf
//   scales      one byte per range: scale index + 15 (15 = flat range)
//   means       [u8 planes] then byte planes of zigzag(mean - prediction), steps; the
//               prediction is MED of the left, upper and upper-left range means
//   domains     low then high bytes of each non-flat range's domain index on its size's grid
//   isometries  one byte per non-flat range
// then, with the border flag, a sixth stream of the same form holding the border loop
// (fractal::forEachBorderSample): [u8 planes] then byte planes of zigzag(sample - previous sample
// on the loop), steps above base, the first sample's previous being 0; and, with the residual flag,
// the residual layer as coding::appendPlanedResiduals writes it (zigzag bin indices).
#include <cstddef>
#include <span>
#include <vector>

#include "tellus/tiles/fractal_code.hpp"

namespace tellus::fractal {

// Appends the payload of `code` (made by fractal::encode with `domainStep` and range sizes from
// minLog2 to maxLog2) to out.
Status write(const FractalCode& code, int minLog2, int maxLog2, int domainStep, int zstdLevel,
             std::vector<std::byte>& out);

// Parses and validates a payload for a tile of `shape`.
Result<FractalCode> read(std::span<const std::byte> bytes, TileShape shape);

}  // namespace tellus::fractal
