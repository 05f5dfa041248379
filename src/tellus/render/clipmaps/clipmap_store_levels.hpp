#pragma once
// The clipmap levels' heights, read from a tile store's pyramid through a CPU tile cache:
// level l is the store's level l (every 2^l-th sample, row 0 north), and levels beyond the
// store's coarsest subsample the coarsest. Samples outside a level's data repeat its edge.
// Reads happen on the calling thread (a toroidal update needs its samples now); the first
// failed tile read (a corrupt store) is kept and reported by firstError(), its samples read 0.
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/core/result.hpp"
#include "tellus/tiles/tile_cache.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

class ClipmapStoreLevels {
 public:
  ClipmapStoreLevels(std::shared_ptr<const TileStore> store, std::size_t cacheBytes);

  float sample(int level, glm::ivec2 sample);
  // The geometric error of every tile of a level (levels beyond the store's coarsest take the
  // coarsest's), row by row, row 0 north; a tile spans `spanSamples` full-resolution samples.
  struct TileErrors {
    int tilesX = 0, tilesY = 0;
    double spanSamples = 0.0;
    std::vector<float> errorM;
  };
  TileErrors tileErrors(int level) const;
  const std::optional<Error>& firstError() const { return firstError_; }

 private:
  std::shared_ptr<const TileStore> store_;
  TileCache cache_;
  // The tile each store level read last: a texel reads two levels in turn, so one slot per
  // level saves a cache lookup (a lock) for almost every sample.
  std::vector<TileHandle> lastTile_;
  std::optional<Error> firstError_;
};

}  // namespace tellus
