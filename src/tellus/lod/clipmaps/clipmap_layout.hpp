#pragma once
// Geometry clipmaps (Losasso & Hoppe 2004; GPU version: Asirvatham & Hoppe 2005; seed 004
// section 2.3): L nested square grids of n x n vertices (n = 4m - 1) centred on the viewer,
// level l having a spacing of 2^l samples. GL-free: the placement of the levels, the footprints
// that tile each level's ring, the toroidal update regions, and the geomorph.
//
// Coordinates are (col, row) samples of a level, as in the tile store's pyramid (row 0 north):
// level-l vertex (i, j) is full-resolution sample (i * 2^l, j * 2^l), and its height is the
// store's level-l sample there (levels beyond the store's coarsest subsample the coarsest).
// A level's vertices are origin + (x, y) with x, y in [0, n - 1] ("local" coordinates).
//
// Footprints (Asirvatham & Hoppe, figure 2-4), with m = (n + 1) / 4:
//   - 12 blocks of m x m vertices around the ring, 4 fix-ups of m x 3 vertices in the gaps
//     between them, the interior trim (an L of 2m + 1 vertices a side and 2 wide) on the two
//     sides of the hole that the finer level leaves free, and zero-area triangles along the
//     outer border (they close the T-junctions with the coarser level under rasterisation);
//   - the finest level fills its hole with one (2m + 1)^2 centre patch instead of a trim.
// Every piece indexes one shared n x n vertex grid (vertex id y * n + x), so the GPU pulls a
// vertex's local position from gl_VertexID.
//
// Nesting: a level's origin is chosen top-down so that the finer level sits in its hole with
// the trim on one side per axis, and every level's centre is within 1 of its units of the
// viewer. Transition (geomorph): within w units of a level's outer border its heights blend to
// the coarser level's surface (exactly at the border), so neighbouring levels meet without
// cracks and a level can move without a pop.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/core/result.hpp"

namespace tellus::clipmaps {

struct ClipmapShape {
  int n = 255;  // vertices a side, 4m - 1 (the papers use 2^k - 1; any 4m - 1 tiles the ring)
  int m = 64;   // block side, (n + 1) / 4 vertices
  int textureSize = 256;  // n + 1 texels a side, addressed toroidally (sample mod n + 1)
  int levels = 1;
  // w, level units: n / 5 by default (Asirvatham and Hoppe use n / 10; twice as wide halves
  // the popping on a fast flyover, docs/clipmaps.md), at most maxTransitionWidth().
  float transitionWidth = 51.0f;

  // Errors: n not 4m - 1 in [31, 1023] (smaller levels leave no room for a transition band),
  // levels outside [1, 24].
  static Result<ClipmapShape> create(int n, int levels);
  // The smallest level count whose coarsest level spans twice the grid's larger side.
  static int levelsFor(int n, int gridWidth, int gridHeight);
  // |vertex - viewer| (level units) from which the blend starts: it reaches 1 half a unit
  // before the nearest the border can be (a level's centre is within 1 unit of the viewer), so
  // rounding never leaves a border vertex short of the coarser surface.
  float blendStart() const { return float(n - 1) * 0.5f - 1.5f - transitionWidth; }
  // The widest band that leaves the vertices around the level's hole (m + 1 units from the
  // viewer at most) unblended: m - 3.5.
  float maxTransitionWidth() const { return float(m) - 3.5f; }
};

// Each level's origin (level units) for a viewer at `viewer`, full-resolution (col, row)
// samples (fractional). Index 0 is the finest level.
std::vector<glm::ivec2> placeLevels(const ClipmapShape& shape, glm::dvec2 viewer);

// Which side of the hole the finer level leaves for the trim: per axis 1 when the trim is on
// the low side (the finer level starts one unit in), 0 on the high side.
glm::ivec2 trimSide(const ClipmapShape& shape, glm::ivec2 coarserOrigin, glm::ivec2 finerOrigin);

enum class PieceKind { Block, FixUp, Trim, Centre, Degenerate };

struct Piece {
  PieceKind kind = PieceKind::Block;
  glm::ivec2 min{0}, max{0};  // local vertex box
  glm::ivec2 trim{0};         // Trim: the trimSide() it is for
  std::uint32_t firstIndex = 0, indexCount = 0;
};

struct Footprints {
  std::vector<std::uint32_t> indices;  // into the n x n vertex grid, counter-clockwise from above
  std::vector<Piece> pieces;
};

Footprints buildFootprints(const ClipmapShape& shape);

// The pieces level `level` draws: the blocks and fix-ups, then the centre (finest level) or
// the trim for `trim`, then the degenerate border (all but the coarsest level).
std::vector<const Piece*> piecesForLevel(const Footprints& footprints, const ClipmapShape& shape,
                                         int level, glm::ivec2 trim);

// Geomorph weight (0: the level's own heights, 1: the coarser level's surface) of the vertex at
// level coordinates `vertex` for a viewer at `viewerLevel` (the viewer in level units).
float blendWeight(const ClipmapShape& shape, glm::ivec2 vertex, glm::dvec2 viewerLevel);

// A rectangle of level samples [min, max) (level units).
struct SampleRect {
  glm::ivec2 min{0}, max{0};
  bool empty() const { return max.x <= min.x || max.y <= min.y; }
};

// The samples a level's window [origin, origin + n) gains when its origin moves from `from` to
// `to`: at most two rectangles (an L), or the whole new window when they do not overlap.
std::vector<SampleRect> exposedRegions(const ClipmapShape& shape, glm::ivec2 from, glm::ivec2 to);

// A rectangle cut where it wraps around the toroidal texture: up to four pieces, each a texel
// rectangle (texel = sample mod textureSize) and the samples it holds.
struct ToroidalPiece {
  glm::ivec2 texel{0};  // first texel
  SampleRect samples;
};
std::vector<ToroidalPiece> wrapToroidally(const SampleRect& rect, int textureSize);

// Texel of a sample in the toroidal texture: sample mod textureSize in [0, textureSize), also
// for negative samples.
inline glm::ivec2 toroidalTexel(glm::ivec2 sample, int textureSize) {
  const auto wrap = [textureSize](int v) { return ((v % textureSize) + textureSize) % textureSize; };
  return {wrap(sample.x), wrap(sample.y)};
}

}  // namespace tellus::clipmaps
