#pragma once
// Heights for the spiral globe (seed 001, "Managing Elevation"): the spiral's vertices move over
// the terrain, so their heights cannot live in the vertex buffer; the vertex shader fetches them
// from textures (the vertex texture fetch the seed's hardware lacked). GL-free; the CPU twin of
// the lookup in shaders/spiral/spiral.vert.
//
// The textures are a stack of windows onto the global store's surface (the surface of each
// depth, storeSampleSource's rule, geoid added: ellipsoidal metres):
//   - the base: the whole Earth at `baseDepth` (the deepest whose samples round the world fit
//     kSpiralBaseColumns), loaded once;
//   - one window a depth from baseDepth + 1 to the finest depth stored near the focal point,
//     `windowSamples` a side in the depth's latitude/longitude samples, centred on the focal
//     point and moved when the focal point strays more than an eighth of the window from its
//     centre.
// A vertex takes the depth whose sample spacing just resolves the spiral's spacing there
// (spiralLevelDepthFor), or the deepest coarser one whose window holds it (with a sample of
// margin for the normal's differences), or the base: every vertex has a height, and heights of
// coarser depths are the finer surfaces' samples (the store nests), so a vertex changing depth
// changes little.
//
// Blended (`--spiral-blend-depths`): a vertex's spacing lies between two depths' sample spacings, and its
// height is the finer one's (the depth above) mixed with the next coarser one's by how far the
// spacing lies towards the coarser (spiralCoarserShare). As the spiral's radii shrink on a
// descent, a vertex's height then moves from the coarser depth's surface to the finer one's
// continuously instead of switching at once (issue 45's "heights of a vertex blended between
// the windows it crosses").
//
// Sample (column i, row j) of depth d is at longitude -180 + i * step, latitude 90 - j * step,
// step = 180 / 2^d / tileCells degrees; columns wrap round the world, rows clamp at the poles.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/core/result.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/tiles/global_store.hpp"

namespace tellus {

inline constexpr int kSpiralBaseColumns = 2048;  // the base level's samples round the world, at most

// A square (or, for the base, whole-world) block of one depth's samples, heights in metres
// above the ellipsoid, row 0 north.
struct SpiralHeightWindow {
  int depth = 0;
  int tileCells = 0;
  std::int64_t column0 = 0, row0 = 0;  // the north-west sample's indices at `depth`
  int columns = 0, rows = 0;
  bool wholeWorld = false;  // the base: columns wrap (columns - 1 == samples round the world)
  std::vector<float> heights;  // columns * rows
  std::vector<float> geoidM;   // the undulation added to each (empty: no geoid)

  double stepRad() const;  // the sample spacing, radians of latitude (and longitude)
  std::int64_t columnsRoundTheWorld() const;  // 2^(depth+1) * tileCells
  // Where the focal point (degrees) falls in the window, in samples (x east, y south).
  glm::dvec2 samplePosition(double latDeg, double lonDeg) const;
};

// The deepest depth whose samples round the world fit kSpiralBaseColumns.
int spiralBaseDepth(int tileCells);

// The depth whose sample spacing (pi / 2^d / tileCells radians) is at most `spacingRad`, the
// spiral's vertex spacing at the vertex (its radius times 2 pi / n), clamped to
// [baseDepth, finestDepth].
int spiralLevelDepthFor(float spacingRad, int tileCells, int baseDepth, int finestDepth);
// The share (0 .. 1) of the depth above spiralLevelDepthFor's in a blended vertex's height: how
// far log2(pi / (tileCells x spacing)) lies below that depth; 0 at the base and past the finest.
float spiralCoarserShare(float spacingRad, int tileCells, int baseDepth, int finestDepth);

// The window of `depth`, `samples` a side, centred on (latDeg, lonDeg) (snapped to a sample).
SpiralHeightWindow spiralWindowAround(int depth, int tileCells, int samples, double latDeg,
                                      double lonDeg);
// The base: the whole Earth at `depth` (columns round the world + 1, rows pole to pole + 1).
SpiralHeightWindow spiralWholeWorld(int depth, int tileCells);

// True when the focal point has strayed more than an eighth of the window from its centre.
bool spiralWindowNeedsMove(const SpiralHeightWindow& window, double latDeg, double lonDeg);

// Fills window.heights from the store's surface of window.depth (columns wrapped round the
// world, rows clamped at the poles), plus the geoid's undulation when `geoid` is given.
// Errors: unreadable tiles.
Status readSpiralHeightWindow(const GlobalStore& store, const Geoid* geoid,
                              SpiralHeightWindow& window);

// The window's surface at sample position (x, y) (floats, as the shader computes it): each cell
// two triangles split from its north-east to its south-west sample, the store's mesh as the
// reference renderer draws it; for the base, x wraps round the world; y and, elsewhere, x clamp
// to the window.
float spiralWindowHeight(const SpiralHeightWindow& window, float x, float y);

// Whether (x, y) lies inside the window with a sample of margin (the base holds every point).
bool spiralWindowHolds(const SpiralHeightWindow& window, float x, float y);

// The stack as the vertex shader sees it: the base and one window a depth, each with the focal
// point's position in its samples (float, as the uniforms).
struct SpiralHeightStack {
  const SpiralHeightWindow* base = nullptr;
  glm::vec2 baseFocal{0.0f};
  std::vector<const SpiralHeightWindow*> levels;  // depth base->depth + 1 + i; null: none yet
  std::vector<glm::vec2> levelFocal;
};

struct SpiralHeightLookup {
  float heightM = 0.0f;  // above the ellipsoid
  float geoidM = 0.0f;   // the geoid's undulation there (height above the geoid: the difference)
  int depth = 0;         // the depth it came from (blended: the finer of the two)
  int coarserDepth = 0;  // blended: the other depth (the same when there is none)
  float coarserShare = 0.0f;  // its share of the height
};

// What spiral.vert fetches for a vertex at `latLonOffset` (spiralLatLonOffset) and (corrected)
// `radius`, on a spiral of `stepsPerRevolution`: the depth that resolves the spiral's spacing
// there (spiralLevelDepthFor), or the deepest coarser window holding the vertex, or the base;
// with `blendDepths`, mixed with the same lookup a depth coarser by spiralCoarserShare.
SpiralHeightLookup spiralLookupHeight(const SpiralHeightStack& stack, glm::vec2 latLonOffset,
                                      float radius, float stepsPerRevolution,
                                      bool blendDepths = false);

}  // namespace tellus
