#include "tellus/formats/bdam/bdam_patches.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>

#include <glm/common.hpp>
#include <meshoptimizer.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "tellus/core/progress.hpp"

namespace tellus::bdam {
namespace {

constexpr float kHeightScale = 0.05f;  // heights' weight in the simplifier's positions

std::uint64_t positionKey(glm::ivec2 p) { return (std::uint64_t(std::uint32_t(p.x)) << 32) | std::uint32_t(p.y); }

// A triangle soup of grid samples, as children hand it to their parent's square.
using Triangles = std::vector<std::array<glm::ivec2, 3>>;

// The grid's own triangles inside t: its half-cells (the bintree at half-cell level) that lie
// within the grid.
void fullResolution(const Triangle& t, int levelsLeft, int width, int height, Triangles& out) {
  if (levelsLeft == 0) {
    for (const glm::ivec2& p : {t.apex, t.left, t.right}) {
      if (p.x > width - 1 || p.y > height - 1) return;
    }
    out.push_back({t.apex, t.right, t.left});  // counter-clockwise (the bintree's order is clockwise)
    return;
  }
  if (!touchesGrid(t, width, height)) return;
  fullResolution(t.child(0), levelsLeft - 1, width, height, out);
  fullResolution(t.child(1), levelsLeft - 1, width, height, out);
}

void appendPatch(const Patch& patch, Triangles& out) {
  for (std::size_t i = 0; i + 2 < patch.indices.size(); i += 3) {
    out.push_back({patch.positions[patch.indices[i]], patch.positions[patch.indices[i + 1]],
                   patch.positions[patch.indices[i + 2]]});
  }
}

// Simplifies the square (diamond) of one or two level-l triangles from their children's
// triangles and returns their patches (empty optional for a half without triangles).
std::array<std::optional<Patch>, 2> buildDiamond(const HeightGrid& grid, const std::array<std::optional<NodeId>, 2>& nodes,
                                                  const std::array<Triangles, 2>& content, int domainLog2,
                                                  int patchTriangles) {
  std::array<Triangle, 2> tri{};
  for (std::size_t h = 0; h < 2; ++h) {
    if (nodes[h]) tri[h] = nodeTriangle(*nodes[h], domainLog2);
  }
  const Triangle& any = nodes[0] ? tri[0] : tri[1];
  const glm::ivec2 diagonalA = any.left, diagonalB = any.right;
  const auto onLeg = [&](glm::ivec2 p) {
    for (std::size_t h = 0; h < 2; ++h) {
      if (nodes[h] && (onSegment(p, tri[h].apex, tri[h].left) || onSegment(p, tri[h].apex, tri[h].right))) return true;
    }
    const bool gridCorner = (p.x == 0 || p.x == grid.width - 1) && (p.y == 0 || p.y == grid.height - 1);
    return gridCorner;
  };
  // Vertices: one per position, except on the diagonal, where the second half gets its own copy
  // (meshoptimizer then sees a seam and collapses both copies together, along the diagonal).
  std::vector<glm::ivec2> positions;
  std::vector<std::uint32_t> indices;
  std::unordered_map<std::uint64_t, std::uint32_t> shared, secondCopy;
  std::vector<bool> secondHalf;  // the vertex is the second half's copy of a diagonal vertex
  const auto vertexOf = [&](glm::ivec2 p, std::size_t half) {
    auto& map = (half == 1 && onSegment(p, diagonalA, diagonalB)) ? secondCopy : shared;
    auto [it, added] = map.try_emplace(positionKey(p), std::uint32_t(positions.size()));
    if (added) {
      positions.push_back(p);
      secondHalf.push_back(&map == &secondCopy);
    }
    return it->second;
  };
  for (std::size_t h = 0; h < 2; ++h) {
    for (const auto& t : content[h]) {
      for (const glm::ivec2& p : t) indices.push_back(vertexOf(p, h));
    }
  }
  if (indices.empty()) return {};
  // Locks: every vertex on a leg (the square's border, fixed by the neighbours already built)
  // gets an unused twin at its position; meshoptimizer locks positions shared by vertices that
  // do not form a seam, and the twin is never drawn.
  const std::size_t used = positions.size();
  std::unordered_map<std::uint64_t, bool> twinned;
  for (std::size_t i = 0; i < used; ++i) {
    if (onLeg(positions[i]) && twinned.try_emplace(positionKey(positions[i]), true).second) {
      positions.push_back(positions[i]);
    }
  }
  const glm::ivec2 origin = glm::min(any.boxMin(), nodes[1] ? tri[1].boxMin() : any.boxMin());
  std::vector<float> xyz(positions.size() * 3);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    xyz[3 * i + 0] = float(double(positions[i].x - origin.x) * grid.spacingXM);
    xyz[3 * i + 1] = float(double(positions[i].y - origin.y) * grid.spacingYM);
    // Heights flattened: the quadrics then measure (nearly) vertical distances, the error BDAM
    // bounds, and a collapse that would fold a triangle over in plan view turns its normal
    // downwards, which meshoptimizer refuses.
    xyz[3 * i + 2] = sampleHeight(grid, positions[i]) * kHeightScale;
  }
  const std::size_t halves = std::size_t(!content[0].empty()) + std::size_t(!content[1].empty());
  const std::size_t target = std::min(indices.size(), std::size_t(patchTriangles) * 3 * halves);
  // Simplified in halving steps (each a meshoptimizer call) down to the target. meshoptimizer
  // 0.18 checks each collapse for a flipped normal on its own, so two collapses around one
  // triangle in the same pass can fold it over in plan; the surface then overlaps itself
  // locally but stays one manifold sheet over the square (no hole: the border is fixed), so
  // folds cost a little overdraw and no crack. Triangles of three points on one straight line
  // (vertical in plan) join a locked border's vertices to an edge that skips them, like a skirt.
  std::vector<std::uint32_t> simplified = indices, step;
  float reached = 0.0f;
  while (simplified.size() > target) {
    const std::size_t goal = std::max(target, simplified.size() / 6 * 3);
    step.resize(simplified.size());
    step.resize(meshopt_simplify(step.data(), simplified.data(), simplified.size(), xyz.data(), positions.size(),
                                 3 * sizeof(float), goal, 1.0f, 0, &reached));
    if (step.size() == simplified.size()) break;  // nothing more to collapse
    simplified.swap(step);
  }
  spdlog::trace("bdam diamond {}: {} -> {} triangles (target {}), {} vertices, {} locked, error {:.3g}",
                nodes[0] ? *nodes[0] : *nodes[1], indices.size() / 3, simplified.size() / 3, target / 3, used,
                positions.size() - used, reached);
  // Each triangle goes to the half on its side of the diagonal.
  std::array<std::optional<Patch>, 2> out;
  std::array<std::unordered_map<std::uint32_t, std::uint16_t>, 2> local;
  bool tooManyVertices = false;
  const long long apexSide = orient(diagonalA, diagonalB, any.apex) > 0 ? 1 : -1;
  const std::size_t first = nodes[0] ? 0 : 1;
  for (std::size_t i = 0; i + 2 < simplified.size(); i += 3) {
    std::array<std::uint32_t, 3> v{simplified[i], simplified[i + 1], simplified[i + 2]};
    long long side = 0;
    for (std::uint32_t k : v) side += orient(diagonalA, diagonalB, positions[k]);
    std::size_t half = (side > 0 ? 1 : -1) == apexSide ? first : 1 - first;
    if (side == 0) {  // three points on the diagonal: the copies it uses tell its half
      half = secondHalf[v[0]] || secondHalf[v[1]] || secondHalf[v[2]] ? 1 : 0;
    }
    if (!nodes[half]) half = 1 - half;  // cannot happen: a half without a node has no triangles
    if (!out[half]) {
      out[half].emplace();
      out[half]->node = *nodes[half];
    }
    Patch& patch = *out[half];
    if (patch.positions.size() + 3 > 0xffff) {
      tooManyVertices = true;
      continue;
    }
    for (std::uint32_t k : v) {
      auto [it, added] = local[half].try_emplace(k, std::uint16_t(patch.positions.size()));
      if (added) {
        patch.positions.push_back(positions[k]);
        patch.heights.push_back(sampleHeight(grid, positions[k]));
      }
      patch.indices.push_back(it->second);
    }
  }
  if (tooManyVertices) {
    spdlog::warn("BDAM: a patch of diamond {} kept more than 65535 vertices after simplification; triangles dropped",
                 nodes[first] ? *nodes[first] : 0);
  }
  for (auto& patch : out) {
    if (!patch) continue;
    const auto [lo, hi] = std::minmax_element(patch->heights.begin(), patch->heights.end());
    patch->minZ = *lo;
    patch->maxZ = *hi;
    patch->errorM = patchErrorM(grid, patch->positions, patch->heights, patch->indices);
  }
  return out;
}

}  // namespace

float patchErrorM(const HeightGrid& grid, const std::vector<glm::ivec2>& positions, const std::vector<float>& heights,
                  const std::vector<std::uint16_t>& indices) {
  double worst = 0.0;
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
    const glm::ivec2 a = positions[indices[i]], b = positions[indices[i + 1]], c = positions[indices[i + 2]];
    const double ha = heights[indices[i]], hb = heights[indices[i + 1]], hc = heights[indices[i + 2]];
    const long long area = orient(a, b, c);
    if (area == 0) continue;
    const glm::ivec2 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    for (int y = lo.y; y <= hi.y; ++y) {
      for (int x = lo.x; x <= hi.x; ++x) {
        const glm::ivec2 p{x, y};
        const long long wa = orient(b, c, p), wb = orient(c, a, p), wc = orient(a, b, p);
        if (area > 0 ? (wa < 0 || wb < 0 || wc < 0) : (wa > 0 || wb > 0 || wc > 0)) continue;
        const double h = (double(wa) * ha + double(wb) * hb + double(wc) * hc) / double(area);
        worst = std::max(worst, std::abs(double(sampleHeight(grid, p)) - h));
      }
    }
  }
  return float(worst);
}

Result<Hierarchy> buildHierarchy(const HeightGrid& grid, const BuildSettings& settings) {
  if (grid.width < 2 || grid.height < 2) return makeError("BDAM needs a grid of at least 2 x 2 samples");
  if (grid.width > 65537 || grid.height > 65537) {
    return makeError("BDAM patches store 16-bit coordinates: the {} x {} grid exceeds 65537 samples a side",
                     grid.width, grid.height);
  }
  if (settings.leafLog2 < 4 || settings.leafLog2 > 16) {
    return makeError("BDAM leaf patches of 2^{} half-cells: the exponent must be in [4, 16]", settings.leafLog2);
  }
  if (settings.patchTriangles < 16 || settings.patchTriangles > 16384) {
    return makeError("BDAM patches of {} triangles: must be in [16, 16384]", settings.patchTriangles);
  }
  Hierarchy h;
  h.gridWidth = grid.width;
  h.gridHeight = grid.height;
  h.spacingXM = grid.spacingXM;
  h.spacingYM = grid.spacingYM;
  while ((1 << h.domainLog2) < std::max(grid.width, grid.height) - 1) ++h.domainLog2;
  const int fullLevel = 2 * h.domainLog2;
  const int leafLog2 = std::min(settings.leafLog2, fullLevel);
  h.leafLevel = fullLevel - leafLog2;

  std::unordered_map<NodeId, std::size_t> built;  // node -> index in h.patches
  Progress progress("bdam patches", std::uint64_t(h.leafLevel) + 1);
  for (int level = h.leafLevel; level >= 0; --level) {
    // The diamonds of this level: nodes grouped by their hypotenuse's midpoint.
    std::map<std::uint64_t, std::array<std::optional<NodeId>, 2>> diamonds;
    for (NodeId node = NodeId(2) << level; node < (NodeId(4) << level); ++node) {
      const Triangle t = nodeTriangle(node, h.domainLog2);
      if (!touchesGrid(t, grid.width, grid.height)) continue;
      auto& pair = diamonds[positionKey(t.hypotenuseMidpoint())];
      (pair[0] ? pair[1] : pair[0]) = node;
    }
    std::vector<std::array<std::optional<NodeId>, 2>> list;
    for (auto& [key, pair] : diamonds) list.push_back(pair);
    std::vector<std::array<std::optional<Patch>, 2>> results(list.size());
    tbb::parallel_for(std::size_t(0), list.size(), [&](std::size_t i) {
      std::array<Triangles, 2> content;
      for (std::size_t half = 0; half < 2; ++half) {
        if (!list[i][half]) continue;
        const NodeId node = *list[i][half];
        for (NodeId child : {2 * node, 2 * node + 1}) {
          if (level == h.leafLevel) {
            fullResolution(nodeTriangle(child, h.domainLog2), fullLevel - level - 1, grid.width, grid.height, content[half]);
          } else if (auto found = built.find(child); found != built.end()) {
            appendPatch(h.patches[found->second], content[half]);
          }
        }
      }
      results[i] = buildDiamond(grid, list[i], content, h.domainLog2, settings.patchTriangles);
    });
    for (auto& pair : results) {
      for (auto& patch : pair) {
        if (!patch) continue;
        built[patch->node] = h.patches.size();
        h.patches.push_back(std::move(*patch));
      }
    }
    progress.advance();
  }
  std::sort(h.patches.begin(), h.patches.end(), [](const Patch& a, const Patch& b) { return a.node < b.node; });
  return h;
}

}  // namespace tellus::bdam
