// tellus::Terrain (include/tellus/terrain.hpp): a flat tile store, opened once.
#include "terrain_state.hpp"

#include "tellus/core/memory_budget.hpp"

namespace tellus {

Result<Terrain> Terrain::open(const std::string& pathOrUrl) {
  auto store = TileStore::open(pathOrUrl);
  if (!store) return store.error();
  const StoreMetadata& metadata = store.value()->metadata();
  const PyramidLayout& layout = metadata.layout;

  auto state = std::make_shared<State>();
  state->store = std::move(store.value());
  TerrainFacts& facts = state->facts;
  facts.source = pathOrUrl;
  facts.levels = layout.levelCount();
  facts.samplesX = layout.dataWidth();
  facts.samplesY = layout.dataHeight();
  facts.spacingXM = metadata.spacingXM;
  facts.spacingYM = metadata.spacingYM;
  facts.widthM = (facts.samplesX - 1) * facts.spacingXM;
  facts.depthM = (facts.samplesY - 1) * facts.spacingYM;
  facts.minHeightM = metadata.minHeightM;
  facts.maxHeightM = metadata.maxHeightM;
  facts.maxErrorM = metadata.maxErrorM;
  facts.crs = metadata.georef.crsWkt;
  // As HeightGrid::worldBounds() of the finest level: the same box the renderers draw in.
  state->bounds = Aabb{{0.0, 0.0, facts.minHeightM}, {facts.widthM, facts.depthM, facts.maxHeightM}};
  return Terrain(std::move(state));
}

const TerrainFacts& Terrain::facts() const { return state_->facts; }

Result<std::shared_ptr<const HeightGrid>> Terrain::State::finestGrid(
    double extraBytesPerSample, std::string_view wayOut) const {
  std::lock_guard lock(finestMutex_);
  if (finest_) return finest_;
  const double samples = double(facts.samplesX) * double(facts.samplesY);
  const Status fits = checkMemoryFor(
      fmt::format("the finest level of {} ({} x {} samples)", facts.source, facts.samplesX,
                  facts.samplesY),
      samples * (sizeof(float) + extraBytesPerSample), wayOut);
  if (!fits) return fits.error();
  auto grid = readStoreLevel(*store, 0);
  if (!grid) return grid.error();
  finest_ = std::make_shared<const HeightGrid>(std::move(grid.value()));
  return finest_;
}

}  // namespace tellus
