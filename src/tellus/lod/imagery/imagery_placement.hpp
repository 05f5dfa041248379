#pragma once
// Where an imagery layer lies in a renderer's frame, and the page a lookup finds there: the CPU
// twin of shaders/common/imagery.glsl (same names, same maths; keep the two in step). GL-free.
#include <array>
#include <cstdint>
#include <span>

#include <glm/vec2.hpp>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/lod/imagery/imagery_pages.hpp"

namespace tellus {

// A layer's level-0 texel coordinates (x east, y south, texel corners at integers) as an affine
// function of the frame's coordinates: texel = offset + scale * p. Flat renderers: p = world
// (x, y) metres.
struct ImageryPlacement {
  glm::dvec2 offset{0.0};
  glm::dvec2 scale{1.0};
  glm::dvec2 texelAt(const glm::dvec2& p) const { return offset + scale * p; }
};

// A layer whose level-0 grid is `layerGeoTransform` in the store's own CRS (a pyramid built
// with imageryGridOnStore's grid) placed in the flat world of a store whose level-0 grid is
// `storeGeoTransform` (pixel-is-area: sample (col, row) at the centre of its pixel), `dataHeight`
// samples high, with ground spacings `spacingXM` x `spacingYM` (height_grid.hpp's world frame).
ImageryPlacement placeOnFlatStore(const std::array<double, 6>& layerGeoTransform,
                                  const std::array<double, 6>& storeGeoTransform, int dataHeight,
                                  double spacingXM, double spacingYM);

// What a lookup of level `level` at level-0 texel `texel` of `layer` finds in `pageTable`
// (ImageryResidency::pageTable()): the slot of the page it reads, that page's level (the one
// asked for when resident, else the nearest resident ancestor's) and the texel within the
// page, in [0, tileSize)^2. found = false outside the layer's pages (or nothing resident).
struct ImageryResolved {
  bool found = false;
  int slot = -1;
  int level = 0;
  glm::dvec2 local{0.0};
};
ImageryResolved imageryResolve(const ImageryPageLayout& layout, std::span<const std::uint32_t> pageTable,
                               int tileSize, int layer, const glm::dvec2& texel, int level);

}  // namespace tellus
