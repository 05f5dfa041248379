#include "tellus/lod/stacks/stack_octree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/trigonometric.hpp>

namespace tellus {

std::uint64_t OctreeKey::packed() const {
  const auto field = [](int v) { return std::uint64_t(std::uint16_t(std::int16_t(v))); };
  return (std::uint64_t(level) << 48) | (field(x) << 32) | (field(y) << 16) | field(z);
}

StackOctree::StackOctree(const StackLevels& levels)
    : levels_(&levels), n_(levels.params().nodeCells) {
  // The top level: the first whose keys are just -1 and 0 on every axis, or the coarsest.
  topLevel_ = levels.count() - 1;
  for (int k = 0; k < levels.count(); ++k) {
    const std::array<int, 3> end = nodesEnd(k);
    if (end[0] <= 1 && end[1] <= 1 && end[2] <= 1) {
      topLevel_ = k;
      break;
    }
  }
}

std::array<int, 3> StackOctree::nodesEnd(int level) const {
  const QuantisedStacks& s = levels_->level(level).stacks;
  // Cells up to the sample past the last column (or above the highest cell) are needed.
  const auto end = [&](int size) { return (size + 1) / (n_ - 1) + 1; };
  return {end(s.width), end(s.height), end(s.cellsZ)};
}

std::array<int, 3> StackOctree::origin(const OctreeKey& key) const {
  const int stride = n_ - 1;
  return {key.x * stride, key.y * stride, key.z * stride};
}

double StackOctree::cellSizeM(int level) const {
  const QuantisedStacks& s = levels_->level(level).stacks;
  return std::max(s.spacingM, s.cellM);
}

Aabb StackOctree::cellBox(const OctreeKey& key) const {
  const QuantisedStacks& s = levels_->level(key.level).stacks;
  const std::array<int, 3> o = origin(key);
  Aabb box;
  box.min = {o[0] * s.spacingM, o[1] * s.spacingM, s.baseM + (o[2] + 0.5) * s.cellM};
  // One cell more on the high sides: a stitched node's last cells take the vertices of the
  // coarser cells they lie in, which reach one of its cells further.
  box.max = {(o[0] + n_ + 1) * s.spacingM, (o[1] + n_ + 1) * s.spacingM,
             s.baseM + (o[2] + n_ + 1.5) * s.cellM};
  return box;
}

Aabb StackOctree::surfaceBox(const OctreeKey& key) const {
  const StackLevel& level = levels_->level(key.level);
  const QuantisedStacks& s = level.stacks;
  const std::array<int, 3> o = origin(key);
  const int reach = levels_->params().filterRadius + 1;
  const int x0 = o[0] - reach, x1 = o[0] + n_ + reach;
  const int y0 = o[1] - reach, y1 = o[1] + n_ + reach;
  float low = std::numeric_limits<float>::max(), high = std::numeric_limits<float>::lowest();
  const bool touchesOutside = x0 < 0 || y0 < 0 || x1 >= s.width || y1 >= s.height;
  for (int y = std::max(y0, 0); y <= std::min(y1, s.height - 1); ++y) {
    for (int x = std::max(x0, 0); x <= std::min(x1, s.width - 1); ++x) {
      const std::size_t c = std::size_t(x) + std::size_t(s.width) * std::size_t(y);
      low = std::min(low, level.lowestBoundaryM[c]);
      high = std::max(high, level.highestTopM[c]);
    }
  }
  Aabb box = cellBox(key);
  if (high < 0.0f) {  // no column with a layer under the node
    box.min.z = 1.0;
    box.max.z = 0.0;
    return box;
  }
  // The floor at the base, and the walls at the terrain's sides, are surfaces too.
  if (touchesOutside || box.min.z <= 0.0) low = 0.0f;
  const double margin = (reach + 0.5) * s.cellM;
  box.min.z = std::max(box.min.z, double(low) - margin);
  box.max.z = std::min(box.max.z, double(high) + margin);
  return box;
}

double StackOctree::geometricErrorM(const OctreeKey& key, const Aabb& box) const {
  if (key.level == 0 || box.min.z > box.max.z) return 0.0;
  const StackLevel& level = levels_->level(key.level);
  const QuantisedStacks& s = level.stacks;
  const std::array<int, 3> o = origin(key);
  const int reach = levels_->params().filterRadius + 1;
  float worst = 0.0f;
  for (int y = std::max(o[1] - reach, 0); y <= std::min(o[1] + n_ + reach, s.height - 1); ++y) {
    for (int x = std::max(o[0] - reach, 0); x <= std::min(o[0] + n_ + reach, s.width - 1); ++x) {
      const std::size_t c = std::size_t(x) + std::size_t(s.width) * std::size_t(y);
      if (level.errorM[c] <= worst) continue;
      if (double(level.errorHighM[c]) < box.min.z || double(level.errorLowM[c]) > box.max.z) {
        continue;  // the mismatch is above or below this node
      }
      worst = level.errorM[c];
    }
  }
  return worst;
}

double SelectionView::extentPx(double sizeM, double distanceM) const {
  if (distanceM <= 0.0) return std::numeric_limits<double>::infinity();
  return sizeM * double(viewportHeightPx) / (2.0 * distanceM * std::tan(glm::radians(fovYDeg) / 2.0));
}

bool SelectionView::wantsSplit(const SelectedNode& node) const {
  return node.extentPx > tauPx || (errorTauPx > 0.0 && node.errorPx > errorTauPx);
}

namespace {

bool emptyBox(const Aabb& box) { return box.min.z > box.max.z; }

struct Leaves {
  std::unordered_map<std::uint64_t, std::size_t> index;  // packed key -> nodes index
  std::vector<SelectedNode> nodes;
  std::vector<bool> removed;
  void add(const SelectedNode& node) {
    index[node.key.packed()] = nodes.size();
    nodes.push_back(node);
    removed.push_back(false);
  }
  bool has(const OctreeKey& key) const { return index.count(key.packed()) != 0; }
};

}  // namespace

StackSelection selectStackNodes(const StackOctree& octree, const SelectionView& view) {
  StackSelection selection;
  Leaves leaves;
  const auto leafFor = [&](const OctreeKey& key, const Aabb& box) {
    SelectedNode node;
    node.key = key;
    node.box = box;
    const double distance = box.distanceTo(view.camera);
    node.extentPx = view.extentPx(octree.cellSizeM(key.level), distance);
    if (view.errorTauPx > 0.0) {
      node.errorM = octree.geometricErrorM(key, box);
      node.errorPx = view.extentPx(node.errorM, distance);
    }
    return node;
  };
  // Refinement: depth first from the roots.
  std::vector<OctreeKey> stack;
  const int top = octree.topLevel();
  const std::array<int, 3> rootEnd = octree.nodesEnd(top);
  for (int z = rootEnd[2] - 1; z >= -1; --z) {
    for (int y = rootEnd[1] - 1; y >= -1; --y) {
      for (int x = rootEnd[0] - 1; x >= -1; --x) stack.push_back({top, x, y, z});
    }
  }
  while (!stack.empty()) {
    const OctreeKey key = stack.back();
    stack.pop_back();
    const Aabb box = octree.surfaceBox(key);
    if (emptyBox(box)) continue;
    const SelectedNode node = leafFor(key, box);
    if (key.level > 0 && view.wantsSplit(node)) {
      ++selection.splits;
      for (int c = 7; c >= 0; --c) stack.push_back(key.child(c));
      continue;
    }
    leaves.add(node);
  }
  // Balance, finest level first: a leaf's 26 neighbours must not lie in a leaf two or more
  // levels coarser; such a leaf is split (its children may need splitting in turn, at their
  // level, later in this loop).
  const auto split = [&](std::size_t at) {
    const OctreeKey key = leaves.nodes[at].key;
    leaves.removed[at] = true;
    leaves.index.erase(key.packed());
    ++selection.balanceSplits;
    for (int c = 0; c < 8; ++c) {
      const OctreeKey child = key.child(c);
      const Aabb box = octree.surfaceBox(child);
      if (!emptyBox(box)) leaves.add(leafFor(child, box));
    }
  };
  for (int level = 0; level <= top - 2; ++level) {
    for (std::size_t i = 0; i < leaves.nodes.size(); ++i) {
      if (leaves.removed[i] || leaves.nodes[i].key.level != level) continue;
      const OctreeKey key = leaves.nodes[i].key;
      for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0 && dz == 0) continue;
            const OctreeKey neighbour{level, key.x + dx, key.y + dy, key.z + dz};
            for (int j = level + 2; j <= top; ++j) {
              const int shift = j - level;
              const OctreeKey ancestor{j, neighbour.x >> shift, neighbour.y >> shift,
                                       neighbour.z >> shift};
              const auto found = leaves.index.find(ancestor.packed());
              if (found == leaves.index.end()) continue;
              split(found->second);
              j = level + 1;  // look again from the finest candidate level
            }
          }
        }
      }
    }
  }
  // The survivors, finest level first, with their stitch masks.
  for (std::size_t i = 0; i < leaves.nodes.size(); ++i) {
    if (leaves.removed[i]) continue;
    SelectedNode node = leaves.nodes[i];
    const OctreeKey parent = node.key.parent();
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          if (leaves.has({parent.level, parent.x + dx, parent.y + dy, parent.z + dz})) {
            node.stitchMask |= 1u << neighbourBit(dx, dy, dz);
          }
        }
      }
    }
    selection.nodes.push_back(node);
  }
  std::sort(selection.nodes.begin(), selection.nodes.end(),
            [](const SelectedNode& a, const SelectedNode& b) {
              if (a.key.level != b.key.level) return a.key.level < b.key.level;
              if (a.key.z != b.key.z) return a.key.z < b.key.z;
              if (a.key.y != b.key.y) return a.key.y < b.key.y;
              return a.key.x < b.key.x;
            });
  if (!selection.nodes.empty()) {
    selection.finestLevel = selection.nodes.front().key.level;
    selection.coarsestLevel = selection.nodes.back().key.level;
  }
  return selection;
}

}  // namespace tellus
