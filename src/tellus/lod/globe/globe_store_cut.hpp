#pragma once
// Which tiles of a global store the globe reference draws for a view (GL-free): a cut through
// the store's quadtree in which every tile is either the finest the store has there or so close
// to it that the difference cannot show: its geometric error (TileStats::geometricErrorM, the
// largest |full-resolution height - the tile's surface| over its ground, plus the codec's bound)
// projects to at most `tolerancePx` pixels from the nearest point of the tile's bounding box.
//
// That is "every visible sample at the finest depth the store has, where it matters": near the
// camera the store's deepest tiles, towards the horizon shallower ones whose error is sub-pixel
// there, and where the store has no deeper data (ETOPO5-only ocean) the depth it has. A tile
// outside the frustum is left out. The cut is a reference, not a level of detail to run fast:
// its bound holds at every pixel (the bounding box is conservative), it ignores frame time,
// and it refines until the bound holds or the store has nothing deeper.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/aabb.hpp"
#include "tellus/core/frustum.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus::globe {

struct GlobeStoreCutView {
  glm::dvec3 eyeEcef{0.0};
  Frustum frustum;        // camera-relative (ECEF - eye), as ViewSetup::relativeViewProjection
  double focalPx = 1.0;   // pixels per radian at the image centre: height / (2 tan(fovY / 2))
};

struct GlobeStoreCutOptions {
  double tolerancePx = 1.0;  // the screen-space error a tile may have, pixels
  // Heights are drawn this far above or below the stored ones at most (the geoid's undulation
  // when one is applied: 110 m), for the tiles' bounding boxes.
  double heightMarginM = 0.0;
  // Tiles hang skirts this deep (metres below their lowest sample), for the bounding boxes.
  double skirtM = 0.0;
  // The cut stops refining before it holds more tiles than this (the most projected error
  // refined first); GlobeStoreCut::capped says how many tiles stayed coarser for it.
  std::size_t maxTiles = 6000;
};

struct GlobeStoreCut {
  std::vector<GeoTileKey> tiles;  // disjoint, covering every visible part of the globe
  std::size_t capped = 0;         // tiles left coarser than the tolerance asks by maxTiles
  // The largest projected error of a selected tile the store has deeper data under (within
  // the tolerance unless capped); tiles that are the finest there count 0.
  double worstErrorPx = 0.0;
};

// The error a tile drawn from the store carries against the store's finest data, metres: its
// record's geometric error when stored; 0 for a tile that is not stored (the store has nothing
// deeper there: its deepest stored ancestor's surface is the finest). Plus the codec's bound.
double globeStoreTileErrorM(const GlobalStore& store, GeoTileKey key);

// A box around every point of `key` drawn between its lowest and highest height (metres above
// the ellipsoid, margins included): a 9 x 9 lattice of its latitudes and longitudes at both
// heights, widened by the sagitta of the arcs between lattice points.
Aabb globeTileEcefBounds(GeoTileKey key, double lowestM, double highestM);

GlobeStoreCut cutGlobeStore(const GlobalStore& store, const GlobeStoreCutView& view,
                            const GlobeStoreCutOptions& options);

}  // namespace tellus::globe
