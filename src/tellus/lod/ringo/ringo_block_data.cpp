#include "tellus/lod/ringo/ringo_block_data.hpp"

#include <algorithm>

namespace tellus {

Result<std::vector<float>> loadRingoBlock(const GlobalStore& store, const RingoLayout& layout,
                                          const RingoBlock& block) {
  if (!block.exists) return makeError("internal error: loading a RINGO block beyond a pole");
  const int n = store.tileCells();
  if (n != layout.tileCells) {
    return makeError("the store's tiles have {} cells, the RINGO layout {}", n, layout.tileCells);
  }
  const GeoTileKey& key = block.key;
  // The ancestor whose samples the block's points are (at depth 0 at the shallowest), and the
  // deepest tile the store holds of it.
  const int up = std::min(block.level, key.depth);
  const GeoTileKey ancestor{key.depth - up, key.x >> up, key.y >> up};
  const GeoTileKey stored = store.deepestStored(ancestor);
  std::vector<float> source(store.tileShape().sampleCount());
  if (Status s = store.readTileMetres(stored, source); !s) return s.error();
  // Block sample (i, j) in the stored tile's sample grid: origin plus i times the step, with
  // the depth-D tile's sample spacing 2^-(D - stored depth) of the stored tile's.
  const double scale = 1.0 / double(std::int64_t(1) << (key.depth - stored.depth));
  const double originX = double(key.x) * n * scale - double(stored.x) * n;
  const double originY = double(key.y) * n * scale - double(stored.y) * n;
  const double step = double(std::int64_t(1) << block.level) * scale;
  const int cells = layout.cellsAt(block.level);
  std::vector<float> heights(std::size_t(cells + 1) * std::size_t(cells + 1));
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      heights[std::size_t(j) * std::size_t(cells + 1) + std::size_t(i)] =
          float(tileSurfaceAt(source, n, originX + i * step, originY + j * step));
    }
  }
  return heights;
}

std::vector<float> coarsenRingoBlock(std::span<const float> finer, int finerCells, int levels) {
  const int stride = 1 << levels;
  const int cells = std::max(1, finerCells / stride);
  std::vector<float> heights(std::size_t(cells + 1) * std::size_t(cells + 1));
  const std::size_t finerRow = std::size_t(finerCells + 1);
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      heights[std::size_t(j) * std::size_t(cells + 1) + std::size_t(i)] =
          finer[std::size_t(j * stride) * finerRow + std::size_t(i * stride)];
    }
  }
  return heights;
}

double ringoDrawnHeight(std::span<const float> heights, int cells, double u, double v) {
  u = std::clamp(u, 0.0, double(cells));
  v = std::clamp(v, 0.0, double(cells));
  const int i = std::min(int(u), cells - 1), j = std::min(int(v), cells - 1);
  const double fu = u - i, fv = v - j;
  const std::size_t row = std::size_t(cells + 1);
  const auto at = [&](int a, int b) { return double(heights[std::size_t(b) * row + std::size_t(a)]); };
  const double ne = at(i + 1, j), sw = at(i, j + 1);
  if (fu + fv <= 1.0) {  // the north-west triangle (NW, NE, SW)
    const double nw = at(i, j);
    return nw + (ne - nw) * fu + (sw - nw) * fv;
  }
  const double se = at(i + 1, j + 1);  // the south-east triangle (NE, SE, SW)
  return se + (sw - se) * (1.0 - fu) + (ne - se) * (1.0 - fv);
}

}  // namespace tellus
