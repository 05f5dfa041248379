#include "tellus/export/terrain_mesh.hpp"

#include <meshoptimizer.h>

#include "tellus/export/greedy_tin.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tellus {
namespace {

}  // namespace

double measureVerticalError(const GridHeights& grid, std::span<const std::uint32_t> samples,
                            std::span<const std::uint32_t> indices) {
  const auto w = std::int64_t(grid.width);
  std::vector<std::uint8_t> covered(grid.heightsM.size(), 0);
  double worst = 0.0;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    std::int64_t c[3], r[3];
    double h[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t s = samples[indices[t + std::size_t(k)]];
      c[k] = std::int64_t(s) % w;
      r[k] = std::int64_t(s) / w;
      h[k] = grid.heightsM[s];
    }
    // Twice the signed area; degenerate triangles cover nothing.
    const std::int64_t area = (c[1] - c[0]) * (r[2] - r[0]) - (c[2] - c[0]) * (r[1] - r[0]);
    if (area == 0) continue;
    const std::int64_t sign = area > 0 ? 1 : -1;
    const std::int64_t c0 = std::min({c[0], c[1], c[2]}), c1 = std::max({c[0], c[1], c[2]});
    const std::int64_t r0 = std::min({r[0], r[1], r[2]}), r1 = std::max({r[0], r[1], r[2]});
    for (std::int64_t row = r0; row <= r1; ++row) {
      for (std::int64_t col = c0; col <= c1; ++col) {
        // Barycentric weights (times the area), exact in integers.
        const std::int64_t b0 = sign * ((c[1] - col) * (r[2] - row) - (c[2] - col) * (r[1] - row));
        const std::int64_t b1 = sign * ((c[2] - col) * (r[0] - row) - (c[0] - col) * (r[2] - row));
        const std::int64_t b2 = sign * area - b0 - b1;
        if (b0 < 0 || b1 < 0 || b2 < 0) continue;
        const double interpolated =
            (double(b0) * h[0] + double(b1) * h[1] + double(b2) * h[2]) / double(sign * area);
        const std::size_t s = std::size_t(row * w + col);
        covered[s] = 1;
        worst = std::max(worst, std::abs(interpolated - double(grid.heightsM[s])));
      }
    }
  }
  if (std::find(covered.begin(), covered.end(), std::uint8_t(0)) != covered.end()) {
    return std::numeric_limits<double>::infinity();
  }
  return worst;
}

Result<TerrainMesh> buildTerrainMesh(const GridHeights& grid, const TerrainMeshOptions& options) {
  if (grid.width < 2 || grid.height < 2) {
    return makeError("a terrain mesh needs at least 2 x 2 samples, not {} x {}", grid.width,
                     grid.height);
  }
  const std::size_t sampleCount = std::size_t(grid.width) * std::size_t(grid.height);
  if (grid.heightsM.size() != sampleCount) {
    return makeError("{} heights for a {} x {} grid", grid.heightsM.size(), grid.width,
                     grid.height);
  }
  if (sampleCount >= std::size_t(std::numeric_limits<std::uint32_t>::max())) {
    return makeError("{} x {} samples are too many for one mesh", grid.width, grid.height);
  }
  if (!std::isfinite(options.maxErrorM) || options.maxErrorM < 0.0) {
    return makeError("the mesh's error bound must be a finite number >= 0 metres, not {}",
                     options.maxErrorM);
  }
  if (!std::all_of(grid.heightsM.begin(), grid.heightsM.end(),
                   [](float h) { return std::isfinite(h); })) {
    return makeError("the grid has non-finite heights");
  }
  GreedyTinInput input;
  input.width = grid.width;
  input.height = grid.height;
  input.spacingXM = grid.spacingXM;
  input.spacingYM = grid.spacingYM;
  input.heightsM = grid.heightsM.data();
  input.maxErrorM = options.maxErrorM;
  input.keepBorder = options.lockBorder;
  GreedyTin tin = buildGreedyTin(input);
  TerrainMesh mesh;
  mesh.samples = std::move(tin.vertices);
  mesh.indices = std::move(tin.triangles);
  // Measured again over every sample, independently of the insertion's bookkeeping.
  mesh.maxErrorM = measureVerticalError(grid, mesh.samples, mesh.indices);
  return mesh;
}

void orderForRendering(TerrainMesh& mesh) {
  std::vector<std::uint32_t> ordered(mesh.indices.size());
  meshopt_optimizeVertexCache(ordered.data(), mesh.indices.data(), mesh.indices.size(),
                              mesh.samples.size());
  std::vector<std::uint32_t> remap(mesh.samples.size(), std::numeric_limits<std::uint32_t>::max());
  std::vector<std::uint32_t> samples;
  samples.reserve(mesh.samples.size());
  for (std::uint32_t& index : ordered) {
    if (remap[index] == std::numeric_limits<std::uint32_t>::max()) {
      remap[index] = std::uint32_t(samples.size());
      samples.push_back(mesh.samples[index]);
    }
    index = remap[index];
  }
  mesh.indices = std::move(ordered);
  mesh.samples = std::move(samples);
}

}  // namespace tellus
