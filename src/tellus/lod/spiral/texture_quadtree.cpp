#include "tellus/lod/spiral/texture_quadtree.hpp"

#include <algorithm>
#include <limits>

namespace tellus {
namespace {

int halved(int size, int times) {
  return int((std::int64_t(size) + (std::int64_t(1) << times) - 1) >> times);
}

}  // namespace

int ImageryLayout::levelWidth(int level) const { return halved(width, level); }
int ImageryLayout::levelHeight(int level) const { return halved(height, level); }
int ImageryLayout::tilesX(int level) const { return (levelWidth(level) + tileSize - 1) / tileSize; }
int ImageryLayout::tilesY(int level) const { return (levelHeight(level) + tileSize - 1) / tileSize; }

QuadTextureRect quadTextureRect(const ImageryLayout& layout, const QuadTextureId& id) {
  const int side = layout.tileSize << (id.node.level - id.mip);
  QuadTextureRect r;
  r.x0 = id.node.x * side;
  r.y0 = id.node.y * side;
  r.x1 = std::min(r.x0 + side, layout.levelWidth(id.mip));
  r.y1 = std::min(r.y0 + side, layout.levelHeight(id.mip));
  return r;
}

std::uint64_t quadTextureBytes(const ImageryLayout& layout, const QuadTextureId& id) {
  const QuadTextureRect r = quadTextureRect(layout, id);
  return (std::uint64_t(r.width()) * std::uint64_t(r.height()) * 16 + 2) / 3;  // x 4/3: mips
}

TextureQuadtree::TextureQuadtree(ImageryLayout layout, TextureQuadtreeParams params)
    : layout_(layout), params_(params) {
  leafLevel_ = std::clamp(params_.leafLevel, 0, layout_.levels - 1);
}

std::vector<QuadDrawnNode> TextureQuadtree::drawn() const {
  std::vector<QuadDrawnNode> nodes;
  nodes.reserve(drawn_.size());
  for (const auto& [id, d] : drawn_) nodes.push_back({id, d.mip, d.pixels});
  return nodes;
}

void TextureQuadtree::reportPixels(const QuadNodeId& node, int mip, std::uint64_t pixels,
                                   double visibleFraction) {
  auto it = drawn_.find(node);
  if (it == drawn_.end() || it->second.mip != mip) return;
  it->second.pixels = double(pixels) / std::clamp(visibleFraction, 1e-4, 1.0);
}

std::vector<QuadNodeId> TextureQuadtree::childrenOf(const QuadNodeId& node) const {
  std::vector<QuadNodeId> children;
  if (node.level == 0) return children;
  const int level = node.level - 1;
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      const QuadNodeId child{level, 2 * node.x + dx, 2 * node.y + dy};
      if (child.x < layout_.tilesX(level) && child.y < layout_.tilesY(level)) children.push_back(child);
    }
  }
  return children;
}

std::uint64_t TextureQuadtree::texels(const QuadTextureId& id) const {
  const QuadTextureRect r = quadTextureRect(layout_, id);
  return std::uint64_t(r.width()) * std::uint64_t(r.height());
}

bool TextureQuadtree::makeResident(const QuadTextureId& id, const std::set<QuadTextureId>& keep,
                                   int& transfersLeft, QuadtreeUpdate& out) {
  if (resident_.contains(id)) return true;
  if (transfersLeft == 0) return false;
  const std::uint64_t bytes = quadTextureBytes(layout_, id);
  // Free the least recently drawn textures that are neither drawn nor wanted now.
  while (residentBytes_ + bytes > params_.memoryBudgetBytes) {
    auto victim = resident_.end();
    for (auto it = resident_.begin(); it != resident_.end(); ++it) {
      const QuadTextureId& t = it->first;
      const auto d = drawn_.find(t.node);
      const bool isDrawn = d != drawn_.end() && d->second.mip == t.mip;
      if (isDrawn || keep.contains(t)) continue;
      if (victim == resident_.end() || it->second.lastDrawn < victim->second.lastDrawn) victim = it;
    }
    if (victim == resident_.end()) return false;
    residentBytes_ -= victim->second.bytes;
    out.evictions.push_back(victim->first);
    resident_.erase(victim);
  }
  resident_[id] = {bytes, updates_};
  residentBytes_ += bytes;
  out.uploads.push_back(id);
  if (transfersLeft > 0) --transfersLeft;
  return true;
}

QuadtreeUpdate TextureQuadtree::update(bool uncapped) {
  ++updates_;
  QuadtreeUpdate out;
  int transfersLeft = !uncapped && params_.maxTransfersPerUpdate > 0 ? params_.maxTransfersPerUpdate : -1;
  if (drawn_.empty()) {
    const QuadTextureId first{root(), root().level};
    transfersLeft = -1;  // the root is always allowed: without it nothing is drawn
    if (makeResident(first, {first}, transfersLeft, out)) drawn_[root()] = {root().level, {}};
    return out;
  }
  for (const auto& [id, d] : drawn_) resident_[{id, d.mip}].lastDrawn = updates_;

  // What each drawn node wants, from its last count.
  enum class Kind { Split, FinerMip, CoarserMip, Merge };
  struct Change {
    Kind kind;
    QuadNodeId node;  // the node changed (for Merge: the parent)
    double ratio;     // pixels / texels
    std::vector<QuadTextureId> needs;
  };
  std::vector<Change> coarser, finer;
  std::set<QuadNodeId> parents;
  for (const auto& [id, d] : drawn_) {
    if (id.level < root().level) parents.insert({id.level + 1, id.x / 2, id.y / 2});
    if (!d.pixels) continue;
    const double p = *d.pixels;
    const double t = double(texels({id, d.mip}));
    if (p > params_.splitAbove * t) {
      if (id.level > leafLevel_) {
        Change c{Kind::Split, id, p / t, {}};
        for (const QuadNodeId& child : childrenOf(id)) c.needs.push_back({child, child.level});
        finer.push_back(std::move(c));
      } else if (d.mip > 0) {
        finer.push_back({Kind::FinerMip, id, p / t, {{id, d.mip - 1}}});
      }
    } else if (d.mip < id.level && p < params_.mergeBelow * double(texels({id, d.mip + 1}))) {
      coarser.push_back({Kind::CoarserMip, id, p / t, {{id, d.mip + 1}}});
    }
  }
  for (const QuadNodeId& parent : parents) {
    double sum = 0.0;
    bool all = true;
    for (const QuadNodeId& child : childrenOf(parent)) {
      const auto it = drawn_.find(child);
      if (it == drawn_.end() || it->second.mip != child.level || !it->second.pixels) {
        all = false;
        break;
      }
      sum += *it->second.pixels;
    }
    const double t = double(texels({parent, parent.level}));
    if (all && sum < params_.mergeBelow * t) {
      coarser.push_back({Kind::Merge, parent, sum / t, {{parent, parent.level}}});
    }
  }
  // Less detail first (it frees memory), the most under-sampled refinements next.
  std::sort(coarser.begin(), coarser.end(), [](const Change& a, const Change& b) { return a.ratio < b.ratio; });
  std::sort(finer.begin(), finer.end(), [](const Change& a, const Change& b) { return a.ratio > b.ratio; });
  std::set<QuadNodeId> touched;  // nodes changed by this update: one change each
  const auto apply = [&](const Change& c) {
    std::vector<QuadNodeId> involved{c.node};
    if (c.kind == Kind::Merge) involved = childrenOf(c.node);
    for (const QuadNodeId& n : involved) {
      if (touched.contains(n)) return;
    }
    const std::set<QuadTextureId> keep(c.needs.begin(), c.needs.end());
    for (const QuadTextureId& t : c.needs) {
      if (!makeResident(t, keep, transfersLeft, out)) {
        ++out.deferred;
        return;
      }
    }
    touched.insert(involved.begin(), involved.end());
    switch (c.kind) {
      case Kind::Split:
        drawn_.erase(c.node);
        for (const QuadTextureId& t : c.needs) drawn_[t.node] = {t.mip, {}};
        ++out.splits;
        break;
      case Kind::Merge:
        for (const QuadNodeId& n : involved) drawn_.erase(n);
        drawn_[c.node] = {c.node.level, {}};
        ++out.merges;
        break;
      case Kind::FinerMip:
      case Kind::CoarserMip:
        drawn_[c.node] = {c.needs.front().mip, {}};
        ++(c.kind == Kind::FinerMip ? out.finerMips : out.coarserMips);
        break;
    }
    for (const QuadTextureId& t : c.needs) resident_[t].lastDrawn = updates_;
  };
  for (const Change& c : coarser) apply(c);
  for (const Change& c : finer) apply(c);
  return out;
}

}  // namespace tellus
