#pragma once
// What a public tellus::Terrain holds: the open store, its bounds in the world frame, and the
// finest level as one grid, read on first need (the grid renderers draw from it).
#include <memory>
#include <mutex>
#include <string_view>

#include "tellus/core/aabb.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/terrain.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

struct Terrain::State {
  TerrainFacts facts;
  std::shared_ptr<const TileStore> store;
  Aabb bounds;  // world frame: the finest level's extent, its height range

  // The finest level, read once. Before reading, a memory check of the grid and
  // `extraBytesPerSample` (what the renderer asking allocates on top: its
  // RendererEntry::bytesPerSample); `wayOut` is the advice its error gives.
  Result<std::shared_ptr<const HeightGrid>> finestGrid(double extraBytesPerSample,
                                                       std::string_view wayOut) const;

 private:
  mutable std::mutex finestMutex_;
  mutable std::shared_ptr<const HeightGrid> finest_;
};

}  // namespace tellus
