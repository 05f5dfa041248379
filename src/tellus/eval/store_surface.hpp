#pragma once
// The globe's ground truth at a global store's finest depth, wherever a pixel lands: the
// surface the globe reference would draw if it drew the whole store at its deepest depth (every
// depth-D sample on the ellipsoid at H + N, two planar triangles a cell split from north-east to
// south-west, as globe_surface.hpp). Where the store is sparse, the depth-D samples are the
// deepest stored ancestor's bilinear surface, as every store reader upsamples (tileSurfaceAt),
// and on tile edges the deepest source wins (storeSampleSource).
//
// A bench's globe reference draws a region at the deepest depth that fits its sample budget,
// which from near the ground looking at the horizon is coarser than what a streaming globe
// renderer draws under the camera; measuring both against this surface scores each by the
// store's own finest data. GL-free. Not thread-safe (tiles are cached as they are met).
#include <map>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/dem/geoid.hpp"
#include "tellus/eval/frame_metrics.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus {

class StoreSurface {
 public:
  // `geoid` may be null (heights are then ellipsoidal); it must outlive this object.
  StoreSurface(std::shared_ptr<const GlobalStore> store, const Geoid* geoid);

  // The true point at the latitude and longitude of `drawnEcef` (moved along the ellipsoid's
  // normal there onto the surface's triangle); false where a tile cannot be read.
  bool trueSurfacePoint(const glm::dvec3& drawnEcef, glm::dvec3& surfaceEcef);
  // A TrueSurfaceFn bound to this object (which must outlive it).
  TrueSurfaceFn truth();
  // The surface's height above the ellipsoid at (lat, lon), metres; NaN where unreadable.
  double ellipsoidalHeightM(double latDeg, double lonDeg);
  int depth() const { return depth_; }

 private:
  // Height (above the geoid) of sample (column, row) of `key`, a tile of the finest depth.
  bool sampleHeight(GeoTileKey key, int column, int row, double& heightM);
  const std::vector<float>* storedTile(GeoTileKey stored);
  glm::dvec3 vertex(GeoTileKey key, int column, int row, double heightM) const;

  std::shared_ptr<const GlobalStore> store_;
  const Geoid* geoid_;
  int depth_ = 0;
  int cells_ = 0;
  std::map<GeoTileKey, std::vector<float>> tiles_;  // decoded stored tiles, cleared when full
};

}  // namespace tellus
