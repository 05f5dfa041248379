#pragma once
// Tellus's public API: a terrain to draw or export, opened from a tile store (`tellus build`
// makes one from DEMs: SRTM .hgt, GeoTIFF, BIL...). The store is a .tstore file or the
// http(s):// URL of one (read by ranges: only the tiles drawn are fetched).
//
// The world frame of everything drawn from a terrain: metres, x east and y north of the
// south-west sample of the finest level, z up (height above the vertical datum).
#include <memory>
#include <string>

#include "tellus/result.hpp"

namespace tellus {

// What the store says of its terrain.
struct TerrainFacts {
  std::string source;                  // the path or URL it was opened from
  int levels = 0;                      // levels of detail in the pyramid (0: finest)
  int samplesX = 0, samplesY = 0;      // the finest level's samples, west-east and south-north
  double spacingXM = 0.0, spacingYM = 0.0;  // the finest level's ground spacing, metres
  double widthM = 0.0, depthM = 0.0;   // extent west-east and south-north, metres
  float minHeightM = 0.0f, maxHeightM = 0.0f;  // over every sample of the finest level
  double maxErrorM = 0.0;              // bound on |stored - source height| (0: lossless)
  std::string crs;                     // the source's coordinate system (WKT), empty if none
};

// An opened terrain. Copies share the same open store; it is safe to use from one thread at a
// time (renderers read it on their own loader threads).
class Terrain {
 public:
  // Opens a flat tile store. Errors say which file and what is wrong with it (not a store,
  // truncated, a checksum that fails, a global store: those are drawn by `tellus render`'s
  // globe renderers, not yet by this API).
  static Result<Terrain> open(const std::string& pathOrUrl);

  const TerrainFacts& facts() const;

  // The library's own state (terrain_state.hpp); nothing an embedder needs.
  struct State;
  const State& state() const { return *state_; }

 private:
  explicit Terrain(std::shared_ptr<State> state) : state_(std::move(state)) {}
  std::shared_ptr<State> state_;
};

}  // namespace tellus
