#pragma once
// RINGO (seed 002): the layout of its blocks. GL-free.
//
// The terrain around the viewer is a square matrix of blocks of equal geographic size: a central
// area of 3 x 3 blocks at the finest resolution, then `rings` rings, each ring's blocks with four
// times fewer triangles than those of the ring inside it (half the cells a side). With the
// seed's 4 rings the matrix is 11 x 11 = 121 blocks.
//
// Here a block is a tile of the global store (tiles/global_tiling.hpp) at the layout's depth D:
// blocks are aligned with the store's tiles, a level-0 block is the depth-D tile itself
// (tileCells cells a side) and a level-L block covers the same ground with tileCells / 2^L cells,
// every 2^L-th sample of the store's surface at depth D (which are its depth D - L ancestor's
// samples there: the tiles nest), so a block of any level is read from the store without
// resampling, and a block that coarsens is its own finer samples taken every other one.
#include <cstdint>

namespace tellus {

// The default block size: the distance to the horizon over this many blocks.
constexpr double kRingoBlocksToHorizon = 5.0;

struct RingoLayout {
  int rings = 4;          // rings around the central 3 x 3 blocks (the seed's test: 4)
  int tileCells = 256;    // cells a side of a level-0 block (the store's tiles)

  // Blocks a side of the matrix: 3 + 2 * rings.
  int side() const { return 3 + 2 * rings; }
  // The level of the block at offset (dx, dy) blocks from the central one: 0 in the central
  // 3 x 3, then 1, 2, ... ring by ring outwards. Offsets within +-(side() / 2).
  static int levelAt(int dx, int dy);
  // Cells a side of a block of `level` (at least 1).
  int cellsAt(int level) const;
  // Triangles of one block of `level`, and of the whole matrix (two per cell).
  std::uint64_t trianglesAt(int level) const;
  std::uint64_t totalTriangles() const;
};

// The depth D of the matrix for a viewer `clearanceM` above the ground: blocks about
// 1 / `blocksToHorizon` of the distance to the horizon wide (by default a fifth, so the matrix
// reaches about to the horizon and the central block spans the view below), never deeper than `deepestDepth` (the deepest the store
// holds under the viewer: deeper blocks would only upsample it) and never so shallow that the
// matrix would wrap round the globe (at least `minimumDepth(layout)`).
// `currentDepth` (>= 0: the matrix's depth now) adds hysteresis, so that a flight whose height
// above the ground wavers near a threshold does not rebuild the matrix back and forth: the
// depth goes deeper as soon as the ideal one rounds deeper (ideal >= current + 0.5: a matrix
// coarser than the height asks costs screen-space error) but coarser only once the ideal is
// more than 0.75 of a depth below (a finer matrix than needed costs only triangles).
int ringoDepthFor(double clearanceM, int deepestDepth, const RingoLayout& layout,
                  int currentDepth = -1, double blocksToHorizon = kRingoBlocksToHorizon);
// Frames between starting a matrix and drawing it: built and copied on worker threads during
// one, installed at the start of the next.
constexpr int kRingoMatrixLatencyFrames = 2;
// The clearance to choose a new matrix's depth for, `latencyFrames` frames before it is drawn:
// while descending (clearanceM below the last frame's), the clearance extrapolated that many
// frames at the last frame's rate (at most 4x lower a frame), so that a descent does not see
// matrices a depth or two too coarse; otherwise (climbing, hovering, no last frame: NaN) the
// clearance now, as a finer matrix than needed costs only triangles.
double ringoPlannedClearance(double clearanceM, double lastClearanceM, int latencyFrames);
// The same for a viewer in flight, from its height above the ellipsoid now and at the last frame
// (metres; NaN: no last frame) and the ground under it now and at the last frame (NaN: taken as
// the ground now): only the
// descent that both the viewer's own height and its clearance show is extrapolated, so the
// last clearance is the smaller of the last height over the ground now and over the ground then.
// A level flight over ridges sees the ground rise by hundreds of metres a frame: extrapolating
// the clearance's change read that as a descent, planned a matrix a depth too fine for one
// frame and a depth too coarse the next, and each flip left an old matrix on screen while the
// next one filled. A viewer following the ground down a slope drops but keeps its clearance:
// extrapolating its height alone would plan a matrix too fine. A vertical descent shows both.
double ringoPlannedClearanceInFlight(double eyeHeightM, double lastEyeHeightM, double groundM,
                                     double lastGroundM, int latencyFrames);

// A point of the globe, degrees.
struct RingoLatLon {
  double latDeg = 0.0, lonDeg = 0.0;
};
// Where the viewer will be `latencyFrames` frames from now, moving as it did since the last
// frame: a new matrix, and a recentred one, are centred there, so that a fast flight (a
// time-lapse crosses kilometres a frame) does not draw matrices whose fine centre lies behind
// it. The step is taken along latitude and longitude (across the antimeridian too). No last
// frame (NaN), or a step over `maxStepDeg` in either (a jump across the globe, not a flight):
// the position now.
RingoLatLon ringoPlannedPosition(RingoLatLon now, RingoLatLon last, int latencyFrames,
                                 double maxStepDeg = 1.0);

// The shallowest depth whose rows of tiles round the globe hold the matrix's side.
int minimumRingoDepth(const RingoLayout& layout);

}  // namespace tellus
