#include "tellus/lod/imagery/imagery_placement.hpp"

#include <cmath>

namespace tellus {

ImageryPlacement placeOnFlatStore(const std::array<double, 6>& layer,
                                  const std::array<double, 6>& store, int dataHeight,
                                  double spacingXM, double spacingYM) {
  // World x -> store column x / spacingX (sample centres at +0.5 in pixel coordinates) -> CRS
  // X -> layer texel (X - layer[0]) / layer[1]; the same north to south for y.
  ImageryPlacement p;
  p.scale.x = store[1] / (spacingXM * layer[1]);
  p.offset.x = (store[0] + 0.5 * store[1] - layer[0]) / layer[1];
  p.scale.y = -store[5] / (spacingYM * layer[5]);
  p.offset.y = (store[3] + (dataHeight - 0.5) * store[5] - layer[3]) / layer[5];
  return p;
}

ImageryResolved imageryResolve(const ImageryPageLayout& layout, std::span<const std::uint32_t> pageTable,
                               int tileSize, int layer, const glm::dvec2& texel, int level) {
  ImageryResolved r;
  const double t = double(tileSize);
  const glm::dvec2 atLevel = texel / std::ldexp(1.0, level);
  const int px = int(std::floor(atLevel.x / t)), py = int(std::floor(atLevel.y / t));
  const int page = layout.pageIndex({layer, level, px, py});
  if (page < 0) return r;
  const std::uint32_t entry = pageTable[std::size_t(page)];
  if (entry == 0u) return r;
  r.found = true;
  r.slot = imageryEntrySlot(entry);
  r.level = imageryEntryLevel(entry);
  const glm::dvec2 atResolved = texel / std::ldexp(1.0, r.level);
  r.local = atResolved - glm::floor(atResolved / t) * t;
  return r;
}

}  // namespace tellus
