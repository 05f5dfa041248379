#pragma once
// What a command's terrain inputs are, decided once from what was read: rasters (one or a
// mosaic), a flat tile store, a global store or material stacks. A store's container (header,
// metadata, index) is kept as read, its byte source open, so that opening the store reads
// nothing again: for a URL, no second round of requests.
#include <optional>
#include <string>
#include <vector>

#include "tellus/tiles/store_container.hpp"

namespace tellus::cli {

enum class TerrainInputKind {
  Rasters,      // DEM files GDAL reads (several are mosaicked)
  TileStore,    // one flat .tstore, a file or an http(s):// URL
  GlobalStore,  // one global .tstore (tellus build --global)
  Stacks,       // one .tstack
};

struct TerrainInput {
  TerrainInputKind kind = TerrainInputKind::Rasters;
  // A store's container as read. A store whose container cannot be read stays a TileStore
  // without one: opening it then reports why (a URL always counts as a store, so that the
  // error is what the server said).
  std::optional<StoreContainer> container;
  bool isStore() const {
    return kind == TerrainInputKind::TileStore || kind == TerrainInputKind::GlobalStore;
  }
};

// Reads what it must of `inputs` (a local file's first 8 bytes, a store's container) once.
TerrainInput classifyTerrainInput(const std::vector<std::string>& inputs);

}  // namespace tellus::cli
