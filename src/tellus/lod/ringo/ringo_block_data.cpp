#include "tellus/lod/ringo/ringo_block_data.hpp"

#include <algorithm>
#include <optional>
#include <utility>

namespace tellus {

Result<std::vector<float>> loadRingoBlock(const GlobalStore& store, const RingoLayout& layout,
                                          const RingoBlock& block) {
  if (!block.exists) return makeError("internal error: loading a RINGO block beyond a pole");
  const int n = store.tileCells();
  if (n != layout.tileCells) {
    return makeError("the store's tiles have {} cells, the RINGO layout {}", n, layout.tileCells);
  }
  const int cells = layout.cellsAt(block.level);
  const int stride = n / cells;  // the tile's samples per block sample
  // A sample inside the tile, on one of its edges or on a corner: nine places, each read from
  // one source (storeSampleSource), found at the first sample met there.
  struct Place {
    StoreSampleSource at;
    int column = 0, row = 0;
    const std::vector<float>* heights = nullptr;
  };
  std::optional<Place> places[3][3];
  std::vector<std::pair<GeoTileKey, std::vector<float>>> sources;  // one per place at most
  sources.reserve(9);  // places point into it
  const auto placeOf = [n](int c) { return c == 0 ? 0 : (c == n ? 2 : 1); };
  std::vector<float> heights(std::size_t(cells + 1) * std::size_t(cells + 1));
  for (int j = 0; j <= cells; ++j) {
    const int row = j * stride;
    for (int i = 0; i <= cells; ++i) {
      const int column = i * stride;
      std::optional<Place>& place = places[placeOf(row)][placeOf(column)];
      if (!place) {
        place.emplace();
        place->at = storeSampleSource(store, block.key, column, row);
        place->column = column, place->row = row;
        auto it = std::find_if(sources.begin(), sources.end(),
                               [&](const auto& s) { return s.first == place->at.source; });
        if (it == sources.end()) {
          std::vector<float> tile(store.tileShape().sampleCount());
          if (Status s = store.readTileMetres(place->at.source, tile); !s) return s.error();
          sources.emplace_back(place->at.source, std::move(tile));
          it = sources.end() - 1;
        }
        place->heights = &it->second;
      }
      const double u = place->at.u + (column - place->column) * place->at.scale;
      const double v = place->at.v + (row - place->row) * place->at.scale;
      heights[std::size_t(j) * std::size_t(cells + 1) + std::size_t(i)] =
          float(tileSurfaceAt(*place->heights, n, u, v));
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
