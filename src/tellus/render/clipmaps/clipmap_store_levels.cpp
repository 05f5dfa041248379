#include "tellus/render/clipmaps/clipmap_store_levels.hpp"

#include <algorithm>
#include <cmath>

#include <spdlog/spdlog.h>

namespace tellus {

ClipmapStoreLevels::ClipmapStoreLevels(std::shared_ptr<const TileStore> store, std::size_t cacheBytes)
    : store_(store), cache_(store, TileCacheOptions{cacheBytes, 1, {}, false}) {
  lastTile_.resize(std::size_t(store_->layout().levelCount()));
}

ClipmapStoreLevels::TileErrors ClipmapStoreLevels::tileErrors(int level) const {
  const PyramidLayout& layout = store_->layout();
  const int storeLevel = std::min(level, layout.levelCount() - 1);
  TileErrors t;
  t.tilesX = layout.tilesX(storeLevel);
  t.tilesY = layout.tilesY(storeLevel);
  t.spanSamples = std::ldexp(double(layout.tileSize()), storeLevel);
  t.errorM.assign(std::size_t(t.tilesX) * std::size_t(t.tilesY), 0.0f);
  for (const TileRecord& record : store_->records()) {
    if (record.key.level != storeLevel) continue;
    t.errorM[std::size_t(record.key.y) * std::size_t(t.tilesX) + std::size_t(record.key.x)] =
        record.stats.geometricErrorM;
  }
  return t;
}

float ClipmapStoreLevels::sample(int level, glm::ivec2 at) {
  const PyramidLayout& layout = store_->layout();
  const int storeLevel = std::min(level, layout.levelCount() - 1);
  const int factor = 1 << (level - storeLevel);
  const glm::ivec2 s(std::clamp(at.x * factor, 0, layout.dataWidthAt(storeLevel) - 1),
                     std::clamp(at.y * factor, 0, layout.dataHeightAt(storeLevel) - 1));
  const int tileSize = layout.tileSize();
  const TileKey key{storeLevel, std::min(s.x / tileSize, layout.tilesX(storeLevel) - 1),
                    std::min(s.y / tileSize, layout.tilesY(storeLevel) - 1)};
  TileHandle& last = lastTile_[std::size_t(storeLevel)];
  if (!last || last->key != key) {
    Result<TileHandle> tile = cache_.get(key);
    if (!tile) {
      if (!firstError_) {
        spdlog::error("clipmaps: {}", tile.error().message);
        firstError_ = tile.error();
      }
      return 0.0f;
    }
    last = std::move(tile.value());
  }
  const glm::ivec2 local = s - glm::ivec2(key.x, key.y) * tileSize;
  return last->heightsM[std::size_t(local.y) * std::size_t(tileSize + 1) + std::size_t(local.x)];
}

}  // namespace tellus
