#include "terrain_input.hpp"

#include "stack_cli.hpp"
#include "tellus/tiles/byte_source.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus::cli {

TerrainInput classifyTerrainInput(const std::vector<std::string>& inputs) {
  TerrainInput input;
  if (inputs.size() != 1) return input;
  const std::string& path = inputs.front();
  if (isStackFile(path)) {
    input.kind = TerrainInputKind::Stacks;
    return input;
  }
  if (!isUrl(path) && !looksLikeTileStore(path)) return input;
  input.kind = TerrainInputKind::TileStore;
  Result<StoreContainer> container = readStoreContainer(path);
  if (!container) return input;
  if (storeFormatName(container->metadataJson) == "tellus-global-store")
    input.kind = TerrainInputKind::GlobalStore;
  input.container = std::move(container.value());
  return input;
}

}  // namespace tellus::cli
