#include "tellus/lod/ringo/ringo_morph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "tellus/lod/ringo/ringo_block_data.hpp"

namespace tellus {

RingoMorphSource::RingoMorphSource(int depth, float remaining)
    : depth_(depth), remaining_(std::clamp(remaining, 0.0f, 1.0f)) {}

void RingoMorphSource::add(const GeoTileKey& key, Block block) {
  auto stored = std::make_unique<Stored>();
  stored->block = std::move(block);
  blocks_[key] = std::move(stored);
}

std::span<const float> RingoMorphSource::drawnHeights(const Stored& stored) const {
  const Block& block = stored.block;
  if (!block.deltas || remaining_ <= 0.0f) return *block.heights;
  std::call_once(stored.summed, [&] {
    stored.drawn.resize(block.heights->size());
    for (std::size_t k = 0; k < stored.drawn.size(); ++k) {
      stored.drawn[k] = (*block.heights)[k] + remaining_ * (*block.deltas)[k];
    }
  });
  return stored.drawn;
}

double RingoMorphSource::eastFraction(const GeoTileKey& key, double lonDeg) {
  const GeoBounds box = GlobalTiling::bounds(key);
  // The longitude on the tile's side of the antimeridian.
  if (lonDeg - box.westDeg > 180.0) lonDeg -= 360.0;
  if (lonDeg - box.westDeg < -180.0) lonDeg += 360.0;
  return (lonDeg - box.westDeg) / (box.eastDeg - box.westDeg);
}

double RingoMorphSource::southFraction(const GeoTileKey& key, double latDeg) {
  const GeoBounds box = GlobalTiling::bounds(key);
  return (box.northDeg - latDeg) / (box.northDeg - box.southDeg);
}

double RingoMorphSource::heightIn(const Stored& stored, double fu, double fv) const {
  const int cells = stored.block.cells;
  return ringoDrawnHeight(drawnHeights(stored), cells, fu * cells, fv * cells);
}

double RingoMorphSource::heightAt(double latDeg, double lonDeg) const {
  const GeoTileKey key = GlobalTiling::tileAt(depth_, latDeg, lonDeg);
  const auto it = blocks_.find(key);
  if (it == blocks_.end() || !it->second->block.heights) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return heightIn(*it->second, eastFraction(key, lonDeg), southFraction(key, latDeg));
}

void RingoMorphSource::heightsOnLattice(std::span<const double> latDeg,
                                        std::span<const double> lonDeg,
                                        std::span<double> out) const {
  // tileAt's column depends on the longitude alone, its row on the latitude alone.
  std::vector<GeoTileKey> columnKeys(lonDeg.size()), rowKeys(latDeg.size());
  std::vector<double> fu(lonDeg.size()), fv(latDeg.size());
  const double anyLat = latDeg.empty() ? 0.0 : latDeg[0];
  const double anyLon = lonDeg.empty() ? 0.0 : lonDeg[0];
  for (std::size_t i = 0; i < lonDeg.size(); ++i) {
    columnKeys[i] = GlobalTiling::tileAt(depth_, anyLat, lonDeg[i]);
    fu[i] = eastFraction(columnKeys[i], lonDeg[i]);
  }
  for (std::size_t j = 0; j < latDeg.size(); ++j) {
    rowKeys[j] = GlobalTiling::tileAt(depth_, latDeg[j], anyLon);
    fv[j] = southFraction(rowKeys[j], latDeg[j]);
  }
  for (std::size_t j = 0; j < latDeg.size(); ++j) {
    const Stored* block = nullptr;
    GeoTileKey cached{-1, -1, -1};
    for (std::size_t i = 0; i < lonDeg.size(); ++i) {
      const GeoTileKey key{depth_, columnKeys[i].x, rowKeys[j].y};
      if (key != cached) {
        const auto it = blocks_.find(key);
        block = it == blocks_.end() || !it->second->block.heights ? nullptr : it->second.get();
        cached = key;
      }
      out[j * lonDeg.size() + i] =
          block ? heightIn(*block, fu[i], fv[j]) : std::numeric_limits<double>::quiet_NaN();
    }
  }
}

float ringoMorphStep(float remaining, int morphFrames, double depthsMoved) {
  if (morphFrames <= 0) return 0.0f;
  const double step = std::max(1.0 / morphFrames, std::abs(depthsMoved) / kRingoMorphDepthSpan);
  return float(std::max(0.0, double(remaining) - step));
}

}  // namespace tellus
