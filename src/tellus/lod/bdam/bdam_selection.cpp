#include "tellus/lod/bdam/bdam_selection.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

namespace tellus::bdam {
namespace {

Aabb unite(const Aabb& a, const Aabb& b) { return Aabb{glm::min(a.min, b.min), glm::max(a.max, b.max)}; }

double distanceToBox(const glm::dvec3& p, const Aabb& box) {
  const glm::dvec3 nearest = glm::clamp(p, box.min, box.max);
  return glm::length(p - nearest);
}

}  // namespace

Result<PatchTree> PatchTree::create(const std::vector<PatchEntry>& entries, int domainLog2, int leafLevel,
                                    double spacingXM, double spacingYM) {
  PatchTree t;
  t.leafLevel_ = leafLevel;
  t.domainLog2_ = domainLog2;
  t.spacingXM_ = spacingXM;
  t.spacingYM_ = spacingYM;
  const std::size_t n = entries.size();
  t.node_.resize(n);
  t.box_.resize(n);
  t.diamondOf_.resize(n);
  std::map<std::pair<int, std::uint64_t>, std::uint32_t> diamonds;  // (level, hypotenuse midpoint)
  for (std::size_t i = 0; i < n; ++i) {
    const PatchEntry& e = entries[i];
    t.node_[i] = e.node;
    t.index_[e.node] = std::uint32_t(i);
    if (e.node > 3 && !t.index_.contains(e.node / 2)) {
      return makeError("BDAM patch table: patch {} has no parent patch", e.node);
    }
    const Triangle tri = nodeTriangle(e.node, domainLog2);
    const glm::ivec2 lo = tri.boxMin(), hi = tri.boxMax();
    t.box_[i] = Aabb{{lo.x * spacingXM, lo.y * spacingYM, double(e.minZ)}, {hi.x * spacingXM, hi.y * spacingYM, double(e.maxZ)}};
    const glm::ivec2 m = tri.hypotenuseMidpoint();
    const std::uint64_t key = (std::uint64_t(std::uint32_t(m.x)) << 32) | std::uint32_t(m.y);
    auto [it, added] = diamonds.try_emplace({nodeLevel(e.node), key}, std::uint32_t(t.diamondError_.size()));
    if (added) {
      t.diamondError_.push_back(0.0f);
      t.diamondBox_.push_back(t.box_[i]);
    }
    t.diamondOf_[i] = it->second;
  }
  // Finest first (entries are sorted by node, so by level): nest boxes and saturate diamonds.
  for (std::size_t k = n; k-- > 0;) {
    const NodeId node = t.node_[k];
    const std::uint32_t d = t.diamondOf_[k];
    t.diamondError_[d] = std::max(t.diamondError_[d], entries[k].errorM);
    for (NodeId child : {2 * node, 2 * node + 1}) {
      const auto c = t.index_.find(child);
      if (c == t.index_.end()) continue;
      t.box_[k] = unite(t.box_[k], t.box_[c->second]);
      const std::uint32_t cd = t.diamondOf_[c->second];
      t.diamondError_[d] = std::max(t.diamondError_[d], t.diamondError_[cd]);
      t.diamondBox_[d] = unite(t.diamondBox_[d], t.diamondBox_[cd]);
    }
    t.diamondBox_[d] = unite(t.diamondBox_[d], t.box_[k]);
  }
  return t;
}

void PatchTree::select(const LodView& view, const SelectionSettings& settings, Selection& out) const {
  out.clear();
  visit(2, view, settings, out);
  visit(3, view, settings, out);
}

void PatchTree::visit(NodeId node, const LodView& view, const SelectionSettings& settings,
                      Selection& out) const {
  const auto found = index_.find(node);
  if (found == index_.end()) return;
  const std::uint32_t i = found->second;
  const double exaggeration = view.exaggeration;
  const auto world = [&](const Aabb& b) {
    return Aabb{{b.min.x, b.min.y, b.min.z * exaggeration}, {b.max.x, b.max.y, b.max.z * exaggeration}};
  };
  const std::uint32_t d = diamondOf_[i];
  const double distance = std::max(view.nearM, distanceToBox(view.cameraM, world(diamondBox_[d])));
  const double errorPx = double(diamondError_[d]) * exaggeration * view.pixelsPerRadian / distance;
  const bool refine = errorPx > double(settings.targetPx);
  const bool leaf = nodeLevel(node) >= leafLevel_;
  if (leaf && refine && settings.exactLeaves) {
    addExactPieces(i, node, kExactPieceLevels, view, settings, out);
    return;
  }
  if (settings.culling) {
    const Aabb box = world(box_[i]);
    if (!view.frustum.intersects(Aabb{box.min - view.cameraM, box.max - view.cameraM})) return;
  }
  if (!leaf && refine) {
    visit(2 * node, view, settings, out);
    visit(2 * node + 1, view, settings, out);
    return;
  }
  out.patches.push_back(i);
}

void PatchTree::addExactPieces(std::uint32_t leaf, NodeId node, int levelsLeft, const LodView& view,
                               const SelectionSettings& settings, Selection& out) const {
  if (settings.culling) {
    // The grid lies within the leaf's error of its patch.
    const double exaggeration = view.exaggeration;
    const double grow = double(diamondError_[diamondOf_[leaf]]);
    const Triangle t = nodeTriangle(node, domainLog2_);
    const glm::ivec2 lo = t.boxMin(), hi = t.boxMax();
    const Aabb box{{lo.x * spacingXM_, lo.y * spacingYM_, (box_[leaf].min.z - grow) * exaggeration},
                   {hi.x * spacingXM_, hi.y * spacingYM_, (box_[leaf].max.z + grow) * exaggeration}};
    if (!view.frustum.intersects(Aabb{box.min - view.cameraM, box.max - view.cameraM})) return;
  }
  if (levelsLeft == 0) {
    out.exactPieces.push_back({leaf, node});
    return;
  }
  addExactPieces(leaf, 2 * node, levelsLeft - 1, view, settings, out);
  addExactPieces(leaf, 2 * node + 1, levelsLeft - 1, view, settings, out);
}

}  // namespace tellus::bdam
