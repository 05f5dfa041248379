#pragma once
// GAMeR's per-frame classification on the GPU, as the paper does it (Boubekeur & Schlick 2005:
// the depth tags and pattern choice run on the GPU): two compute passes (shaders/gamer/) over
// the coarse mesh, following the CPU reference (lod/gamer/gamer_refinement.hpp: depthTags,
// select) step for step. The first culls every cell against the frustum, tags its corners
// (each cell computes its own corners' tags) and picks each of its triangles' pattern, counted
// per pattern; its last work group to finish makes a prefix sum of the counts into one indirect
// draw command a pattern. The second scatters every triangle into its pattern's run of
// instances. (Two dispatches, not four: each costs the render thread a fixed time.) Nothing is
// read back to draw: the commands and instances stay on the GPU. The frame's totals (coarse and
// refined triangles, patterns in use) land in a small buffer read a frame or more later behind
// a fence. Needs a current GL 4.5 context.
#include <cstdint>
#include <optional>

#include <glm/vec4.hpp>

#include "tellus/core/result.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/fence.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/lod/gamer/gamer_patterns.hpp"
#include "tellus/lod/gamer/gamer_refinement.hpp"
#include "tellus/lod/lod_view.hpp"

namespace tellus {

class GamerGpuSelection {
 public:
  // One frame's output: the draw commands (one a pattern, DrawElementsIndirectCommand) and the
  // instances (gamer::Instance) they draw, and the totals (uvec4: coarse triangles, refined
  // triangles, patterns in use).
  struct Output {
    gl::Buffer commands, instances, stats;
    gl::Fence ran;  // after the last run's passes
  };
  struct Totals {
    std::uint32_t coarseTriangles = 0, triangles = 0, patternsUsed = 0;
  };

  // Uploads the coarse mesh's points, errors and height ranges and the pattern table.
  static Result<GamerGpuSelection> create(const gamer::CoarseTerrain& terrain, const gamer::PatternPool& pool);

  // Buffers for one frame's output (a renderer keeps two: the popping metric redraws the last).
  Output makeOutput() const;
  // Classifies the coarse mesh for `view` into `out`.
  void run(const LodView& view, const gamer::GamerSettings& settings, Output& out);
  int patternCount() const { return patternCount_; }

  // The totals of `out`'s last run once its fence has passed (no wait), else none.
  static std::optional<Totals> totalsIfDone(Output& out);
  // The totals of `out`'s last run: waits for the GPU (the bench's finishStats, tests).
  static Totals readTotals(Output& out);
  // The selection in `out`, as the CPU reference's Selection (tests: waits for the GPU); the
  // order of instances within a pattern is the GPU's.
  gamer::Selection readSelection(const Output& out) const;

 private:
  gl::Program classify_, scatter_;
  gl::Buffer points_, errors_, groupsDone_, cellHeights_, patterns_, counts_, chosen_;
  int cellsX_ = 0, cellsY_ = 0, maxDepth_ = 0, patternCount_ = 0;
  float targetPx_ = -1.0f;  // the classification's uniforms as last set (none yet)
  float morphBand_ = -1.0f;
  bool culling_ = false;
};

}  // namespace tellus
