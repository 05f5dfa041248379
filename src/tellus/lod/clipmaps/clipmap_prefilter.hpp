#pragma once
// Prefiltered clipmap levels (beyond the papers; issue 45). GL-free.
//
// The tile store's pyramid subsamples: level l's sample (i, j) is level 0's sample (2^l i,
// 2^l j). Drawn as triangles between those samples a coarse level is exact at its vertices and
// off by the terrain's detail between them. Prefiltering instead makes each coarse sample a
// weighted sum of the next finer level's samples around it, with the weights of the least-squares
// fit: the coarse values whose surface (SW-NE triangles, as the clipmap draws them) is nearest,
// in the mean square over the finer samples, to the finer level. On the Korea flyover that
// lowers the clipmaps' SSE p99 by about a fifth (docs/clipmaps.md, "Prefiltered levels").
//
// The exact fit is global (a linear solve over the whole level); its weights fall off within a
// few samples, so the kernel keeps those within kRadius finer samples of the coarse sample's
// position (a 9 x 9 window), renormalised to sum to 1; the truncation costs under 2 % of that
// gain. Level 0 stays the store's own samples. Every filtered level is computed from the store's
// next finer (subsampled) level, not from a filtered one, so a sample needs 81 stored samples.
// Near the terrain's edge, where the window would reach past the data (and read clamped
// samples), a level keeps the stored sample: the terrain's outline stays the one every other
// renderer draws, so the far edge's silhouette does not sink below the reference's.
#include <array>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/lod/clipmaps/clipmap_heights.hpp"
#include "tellus/lod/clipmaps/clipmap_layout.hpp"

namespace tellus::clipmaps {

struct PrefilterKernel {
  static constexpr int kRadius = 4;
  static constexpr int kSide = 2 * kRadius + 1;
  // weights[(dy + kRadius) * kSide + dx + kRadius]: the weight of the finer sample at
  // (2i + dx, 2j + dy) in the coarse sample (i, j). They sum to 1.
  std::array<float, kSide * kSide> weights{};
};

// The least-squares kernel, computed once (a conjugate-gradient solve on a small grid).
const PrefilterKernel& leastSquaresKernel();

// What a clipmap level's heights are made of.
struct LevelFilter {
  bool prefilter = true;  // false: the store's subsampled levels, as the papers draw them
  // Filtered heights are clamped to the terrain's range, so that bounds taken from it hold.
  float minHeightM = -1.0e9f;
  float maxHeightM = 1.0e9f;
  // The terrain's full-resolution samples (columns, rows); 0: unbounded (no edge).
  glm::ivec2 dataSize{0};
};

// The height of level `level`'s sample `sample` made with `filter` from the stored (subsampled)
// levels `stored`. One sample at a time: the definition, for references and tests.
float filteredHeight(const LevelSampler& stored, const LevelFilter& filter, int level, glm::ivec2 sample);

// A sampler that returns filteredHeight() (81 stored samples a call above level 0).
LevelSampler filteredSampler(LevelSampler stored, LevelFilter filter);

// Level `level`'s filtered heights over the samples [rect.min, rect.max), row by row: equal, bit
// for bit, to filteredHeight() at each sample, but reading each stored sample once.
std::vector<float> filteredBlock(const LevelSampler& stored, const LevelFilter& filter, int level, const SampleRect& rect);

}  // namespace tellus::clipmaps
