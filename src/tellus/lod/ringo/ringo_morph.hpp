#pragma once
// RINGO (seed 002): the geomorph across a change of the matrix's depth. GL-free.
//
// When the viewer's height above the ground asks for another depth, RINGO replaces its whole
// matrix: every block at once, near ones finer, far ones coarser. Drawn as it is, that is a
// step (popping) on every frame that changes depth, every few frames of a descent. Instead the
// new matrix starts on the surface the old one drew and morphs to its own over `morphFrames`
// frames:
//
//  - When a matrix starts, the surface drawn then is captured (RingoMorphSource: the drawn
//    blocks' heights and their own morph state, frozen from that frame on: a matrix that is
//    being replaced morphs no further).
//  - Each vertex of the new matrix's blocks carries `morphDeltaM`: the captured surface's height
//    at the vertex's latitude and longitude minus the vertex's own height (0 where the captured
//    surface has no block). The vertex is drawn that many metres along its ellipsoid normal,
//    times the matrix's remaining morph (1 before its first frame ... 0 once morphed; each
//    frame takes off at least 1 / morphFrames, more when the viewer's height changes fast).
//  - The delta is one function of the vertex's latitude and longitude, which blocks sharing a
//    vertex compute with the same bits, and the remaining morph is one uniform a matrix: shared
//    vertices stay shared (no crack), and a collapsed edge vertex takes its target's delta.
//
// The surface is continuous from frame to frame then: popping at a depth change is spread over
// up to `morphFrames` frames. (Block changes within a depth, as the viewer crosses a block border,
// still switch at once; they are small: the level changes by one, far from the viewer.)
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "tellus/tiles/global_tiling.hpp"

namespace tellus {

// The surface a matrix drew when its successor started: per block, its heights (metres above
// the geoid, as stored) and its vertices' morph deltas (empty: none) at the remaining morph it
// was drawn with. Filled on the render thread, then only read, by the workers that build the
// new blocks, several at once (a mid-morph block's drawn heights are summed once, on first use).
class RingoMorphSource {
 public:
  struct Block {
    int cells = 0;
    std::shared_ptr<const std::vector<float>> heights;  // (cells + 1)^2, row 0 north
    std::shared_ptr<const std::vector<float>> deltas;   // the same count, or null
  };
  // `depth`: the depth of the matrix's blocks; `remaining`: its remaining morph (0 .. 1).
  RingoMorphSource(int depth, float remaining);
  void add(const GeoTileKey& key, Block block);

  // The height drawn at (lat, lon) degrees (the block tileAt(depth, lat, lon) names, as its
  // triangles draw it: ringoDrawnHeight, morphed), NaN where no block was drawn.
  double heightAt(double latDeg, double lonDeg) const;
  // heightAt() at every point of a lattice, the same bits: `out[j * lonDeg.size() + i]` is the
  // height at (latDeg[j], lonDeg[i]). A block's vertices at a fraction of the cost (their tiles
  // and positions in them found once a row and once a column).
  void heightsOnLattice(std::span<const double> latDeg, std::span<const double> lonDeg,
                        std::span<double> out) const;
  int depth() const { return depth_; }
  float remaining() const { return remaining_; }
  bool empty() const { return blocks_.empty(); }

 private:
  struct Stored {
    Block block;
    mutable std::once_flag summed;
    mutable std::vector<float> drawn;  // heights + remaining x deltas, once needed
  };
  // The heights `stored` draws: its own, or summed with its deltas' remaining share.
  std::span<const float> drawnHeights(const Stored& stored) const;
  // The height drawn in `stored` at fractions (fu east, fv south) of its tile.
  double heightIn(const Stored& stored, double fu, double fv) const;
  // The fraction of the way across tile column `x` (row `y`) that `lonDeg` (`latDeg`) lies.
  static double eastFraction(const GeoTileKey& key, double lonDeg);
  static double southFraction(const GeoTileKey& key, double latDeg);

  int depth_;
  float remaining_;
  std::map<GeoTileKey, std::unique_ptr<Stored>> blocks_;
};

// The morph a matrix has left after one more frame, from `remaining` (1 before its first frame):
// each frame moves at least 1 / `morphFrames` of the way (0 frames: at once), and at least as
// far as the viewer's height moved the ideal depth, over `kRingoMorphDepthSpan`: a morph is
// done by the time the viewer has moved a quarter depth on. Slow flights (the viewer's) morph
// over `morphFrames` frames; a time-lapse whose height changes a depth in a few frames morphs
// within a frame or two, or it would show ever older, coarser surfaces.
// `depthsMoved`: |log4(clearance now / clearance last frame)|.
constexpr double kRingoMorphDepthSpan = 0.25;
float ringoMorphStep(float remaining, int morphFrames, double depthsMoved);

}  // namespace tellus
