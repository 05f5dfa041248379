#include "tellus/export/terrain_mesh.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace tellus {
namespace {

// The full mesh: every sample a vertex, two counter-clockwise triangles a cell.
std::vector<std::uint32_t> fullGridIndices(int width, int height) {
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(width - 1) * std::size_t(height - 1) * 6);
  for (int row = 0; row + 1 < height; ++row) {
    for (int col = 0; col + 1 < width; ++col) {
      const auto v00 = std::uint32_t(row * width + col);
      const auto v10 = v00 + 1;
      const auto v01 = v00 + std::uint32_t(width);
      const auto v11 = v01 + 1;
      indices.insert(indices.end(), {v00, v10, v11, v00, v11, v01});
    }
  }
  return indices;
}

// Renumbers the vertices a simplified index list uses, in order of first use.
TerrainMesh compact(std::span<const std::uint32_t> gridIndices, std::size_t sampleCount) {
  TerrainMesh mesh;
  std::vector<std::uint32_t> remap(sampleCount, std::numeric_limits<std::uint32_t>::max());
  mesh.indices.reserve(gridIndices.size());
  for (const std::uint32_t sample : gridIndices) {
    if (remap[sample] == std::numeric_limits<std::uint32_t>::max()) {
      remap[sample] = std::uint32_t(mesh.samples.size());
      mesh.samples.push_back(sample);
    }
    mesh.indices.push_back(remap[sample]);
  }
  return mesh;
}

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

namespace {

// One grid small enough for meshoptimizer's precision (see buildTerrainMesh).
TerrainMesh simplifyBlock(const GridHeights& grid, const TerrainMeshOptions& options);

}  // namespace

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
  if (grid.width <= kTerrainMeshBlockSamples && grid.height <= kTerrainMeshBlockSamples) {
    return simplifyBlock(grid, options);
  }
  // Blocks of kTerrainMeshBlockSamples sharing their border samples, each simplified with its
  // border kept, joined through the shared samples: each block within the bound, so the whole.
  const int cells = kTerrainMeshBlockSamples - 1;
  TerrainMesh joined;
  std::vector<std::uint32_t> vertexOf(sampleCount, std::numeric_limits<std::uint32_t>::max());
  std::vector<float> block;
  for (int row0 = 0; row0 + 1 < grid.height; row0 += cells) {
    for (int col0 = 0; col0 + 1 < grid.width; col0 += cells) {
      const int w = std::min(cells, grid.width - 1 - col0) + 1;
      const int h = std::min(cells, grid.height - 1 - row0) + 1;
      block.resize(std::size_t(w) * std::size_t(h));
      for (int row = 0; row < h; ++row) {
        std::copy_n(&grid.heightsM[std::size_t(row0 + row) * std::size_t(grid.width) + std::size_t(col0)],
                    w, &block[std::size_t(row) * std::size_t(w)]);
      }
      const TerrainMesh part = simplifyBlock({w, h, grid.spacingXM, grid.spacingYM, block},
                                             {.maxErrorM = options.maxErrorM, .lockBorder = true});
      for (const std::uint32_t index : part.indices) {
        const std::uint32_t local = part.samples[index];
        const std::uint32_t sample = std::uint32_t((row0 + int(local) / w) * grid.width + col0 + int(local) % w);
        if (vertexOf[sample] == std::numeric_limits<std::uint32_t>::max()) {
          vertexOf[sample] = std::uint32_t(joined.samples.size());
          joined.samples.push_back(sample);
        }
        joined.indices.push_back(vertexOf[sample]);
      }
      joined.maxErrorM = std::max(joined.maxErrorM, part.maxErrorM);
      joined.simplifierRuns += part.simplifierRuns;
    }
  }
  return joined;
}

namespace {

TerrainMesh simplifyBlock(const GridHeights& grid, const TerrainMeshOptions& options) {
  const std::size_t sampleCount = std::size_t(grid.width) * std::size_t(grid.height);

  // Positions relative to the grid's centre, heights stretched until their range matches the
  // grid's width: meshoptimizer works in single precision on the mesh scaled to a unit cube,
  // where a metre of height on a 20 km grid is lost in the quadrics' rounding (collapses it
  // rates error-free then miss samples by metres); stretched, vertical errors dominate.
  const auto [lowest, highest] = std::minmax_element(grid.heightsM.begin(), grid.heightsM.end());
  const double extentXY = std::max((grid.width - 1) * grid.spacingXM, (grid.height - 1) * grid.spacingYM);
  const double kHeightScale =
      std::clamp(extentXY / std::max(double(*highest) - double(*lowest), 1.0), 1.0, 1000.0);
  const double midHeight = 0.5 * (double(*lowest) + double(*highest));
  const double midX = 0.5 * (grid.width - 1) * grid.spacingXM;
  const double midY = 0.5 * (grid.height - 1) * grid.spacingYM;
  std::vector<float> positions(sampleCount * 3);
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      const std::size_t s = std::size_t(row) * std::size_t(grid.width) + std::size_t(col);
      positions[3 * s + 0] = float(col * grid.spacingXM - midX);
      positions[3 * s + 1] = float(row * grid.spacingYM - midY);
      positions[3 * s + 2] = float((grid.heightsM[s] - midHeight) * kHeightScale);
    }
  }
  const std::vector<std::uint32_t> full = fullGridIndices(grid.width, grid.height);
  if (options.maxErrorM == 0.0) {
    TerrainMesh mesh = compact(full, sampleCount);
    mesh.maxErrorM = measureVerticalError(grid, mesh.samples, mesh.indices);
    return mesh;
  }

  const float scale = meshopt_simplifyScale(positions.data(), sampleCount, 3 * sizeof(float));
  const unsigned simplifyOptions = options.lockBorder ? meshopt_SimplifyLockBorder : 0u;
  std::vector<std::uint32_t> simplified(full.size());
  int runs = 0;
  auto simplifyTo = [&](double target) {
    float resultError = 0.0f;
    const std::size_t count =
        meshopt_simplify(simplified.data(), full.data(), full.size(), positions.data(),
                         sampleCount, 3 * sizeof(float), 3, float(target), simplifyOptions,
                         &resultError);
    ++runs;
    TerrainMesh mesh = compact(std::span(simplified).first(count), sampleCount);
    mesh.maxErrorM = measureVerticalError(grid, mesh.samples, mesh.indices);
    return mesh;
  };
  // The simplifier's error (a quadric: distances to the removed faces' planes) underrates the
  // largest vertical miss, by several times on rough ground: search the target (relative to
  // the mesh's extent) whose mesh keeps the bound, in log steps. `fail` misses the bound,
  // `pass` keeps it (0: no simplification, the full mesh, error 0).
  const double nominal = options.maxErrorM * kHeightScale / std::max(double(scale), 1e-9);
  double fail = 0.0, pass = 0.0;
  std::optional<TerrainMesh> best;
  for (double target = nominal; target > nominal * 1e-4; target /= 8.0) {
    TerrainMesh mesh = simplifyTo(target);
    if (mesh.maxErrorM <= options.maxErrorM) {
      pass = target;
      best = std::move(mesh);
      break;
    }
    fail = target;
  }
  if (best && fail > 0.0) {
    for (int step = 0; step < 4; ++step) {  // the factor of 8 narrowed to 8^(1/16) = 1.14
      const double middle = std::sqrt(pass * fail);
      TerrainMesh mesh = simplifyTo(middle);
      if (mesh.maxErrorM <= options.maxErrorM) {
        pass = middle;
        if (mesh.indices.size() <= best->indices.size()) best = std::move(mesh);
      } else {
        fail = middle;
      }
    }
  }
  TerrainMesh mesh = best ? std::move(*best) : compact(full, sampleCount);
  if (!best) mesh.maxErrorM = measureVerticalError(grid, mesh.samples, mesh.indices);
  mesh.simplifierRuns = runs;
  return mesh;
}

}  // namespace

}  // namespace tellus
