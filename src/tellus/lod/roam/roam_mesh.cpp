#include "tellus/core/stopwatch.hpp"
#include "tellus/lod/roam/roam_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <glm/trigonometric.hpp>
#include <tbb/parallel_for.h>

namespace tellus::roam {
namespace {


}  // namespace

Result<std::unique_ptr<RoamMesh>> RoamMesh::create(const HeightGrid& grid, const RoamSettings& settings) {
  if (grid.width < 2 || grid.height < 2) return makeError("ROAM needs a grid of at least 2 x 2 samples");
  if (settings.blockLog2 < 1 || settings.blockLog2 > 10) {
    return makeError("ROAM block size 2^{} cells is outside [2, 1024]", settings.blockLog2);
  }
  if (!(settings.targetPx > 0.0f)) return makeError("ROAM error target must be > 0 px");
  auto mesh = std::unique_ptr<RoamMesh>(new RoamMesh());
  mesh->grid_ = &grid;
  mesh->settings_ = settings;
  mesh->domain_ = BintreeDomain::forGrid(grid.width, grid.height, settings.blockLog2);
  const BintreeDomain& d = mesh->domain_;
  const std::size_t blockBytes = d.storedPerRoot() * 2 * sizeof(std::uint16_t);
  const std::size_t keep = std::max<std::size_t>(1, settings.boundsBudgetBytes / blockBytes);
  mesh->blocks_.resize(std::size_t(d.blockCount()));
  tbb::parallel_for(0, d.blockCount(), [&](int k) {
    BlockBounds bounds = computeBlockBounds(grid, d, k % d.blocksX, k / d.blocksX);
    BlockState& state = mesh->blocks_[std::size_t(k)];
    state.minHeightM = bounds.minHeightM;
    state.maxHeightM = bounds.maxHeightM;
    state.rootBoundM = bounds.rootBoundM;
    if (std::size_t(k) < keep) state.bounds = std::make_unique<BlockBounds>(std::move(bounds));
  });
  for (int k = 0; k < d.blockCount(); ++k) {
    BlockState& state = mesh->blocks_[std::size_t(k)];
    if (!state.bounds) continue;
    mesh->boundsBytes_ += blockBytes;
    state.idle = mesh->idleBlocks_.insert(mesh->idleBlocks_.end(), k);
    state.inIdleList = true;
  }
  // The roots: node 2k and 2k + 1 are block k's (a pair, like every pair of children).
  mesh->nodes_.resize(std::size_t(d.blockCount()) * 2);
  mesh->deferral_.resize(mesh->nodes_.size());
  const auto rootId = [&](int bx, int by, int root) {
    if (bx < 0 || by < 0 || bx >= d.blocksX || by >= d.blocksY) return std::int32_t(-1);
    return std::int32_t(2 * (by * d.blocksX + bx) + root);
  };
  for (int by = 0; by < d.blocksY; ++by) {
    for (int bx = 0; bx < d.blocksX; ++bx) {
      for (int root = 0; root < 2; ++root) {
        const std::int32_t id = rootId(bx, by, root);
        Node& n = mesh->node(id);
        n.tri = rootTriangle(d, bx, by, root);
        n.height = {heightAt(grid, n.tri.apex), heightAt(grid, n.tri.left), heightAt(grid, n.tri.right)};
        n.block = by * d.blocksX + bx;
        n.root = std::uint8_t(root);
        n.alive = true;
        n.base = rootId(bx, by, 1 - root);
        // Root 0's legs: east and south edges; root 1's: west and north edges.
        n.left = root == 0 ? rootId(bx + 1, by, 1) : rootId(bx - 1, by, 0);
        n.right = root == 0 ? rootId(bx, by - 1, 1) : rootId(bx, by + 1, 0);
        mesh->splitQueue_.set(id, 0.0f);
        ++mesh->leaves_;
      }
    }
  }
  return mesh;
}

std::int32_t RoamMesh::allocatePair() {
  if (!freePairs_.empty()) {
    const std::int32_t first = freePairs_.back();
    freePairs_.pop_back();
    return first;
  }
  nodes_.resize(nodes_.size() + 2);
  deferral_.resize(nodes_.size());
  return std::int32_t(nodes_.size() - 2);
}

void RoamMesh::freePair(std::int32_t first) {
  node(first) = Node{};
  node(first + 1) = Node{};
  clearDeferral(first);
  clearDeferral(first + 1);
  freePairs_.push_back(first);
}

std::size_t RoamMesh::residentBoundBlocks() const {
  return std::size_t(std::count_if(blocks_.begin(), blocks_.end(),
                                   [](const BlockState& b) { return b.bounds != nullptr; }));
}

float RoamMesh::nodeBoundM(std::int32_t id) const {
  const Node& n = node(id);
  const int leafDepth = domain_.leafDepth();
  if (n.depth >= leafDepth) return 0.0f;
  if (n.depth == leafDepth - 1) return lastSplitBound(*grid_, n.tri);
  const BlockState& block = blocks_[std::size_t(n.block)];
  if (n.depth == 0) return block.rootBoundM[n.root];
  return decodeBound(block.bounds->bounds[std::size_t(n.root) * domain_.storedPerRoot() + n.heap]);
}

RoamMesh::Evaluation RoamMesh::evaluate(std::int32_t id) const {
  const Node& n = node(id);
  const BlockState& block = blocks_[std::size_t(n.block)];
  const glm::dvec2 spacing(grid_->spacingXM, grid_->spacingYM);
  const glm::dvec2 centre = glm::dvec2(n.tri.left + n.tri.right) * 0.5;
  const double half = 0.625 * glm::length(glm::dvec2(n.tri.left - n.tri.right));
  const double exaggeration = view_.exaggeration;
  Aabb box;
  box.min = glm::dvec3((centre - half) * spacing, double(block.minHeightM) * exaggeration) - view_.cameraM;
  box.max = glm::dvec3((centre + half) * spacing, double(block.maxHeightM) * exaggeration) - view_.cameraM;
  Evaluation e;
  double marginIn = std::numeric_limits<double>::max(), marginOut = 0.0;
  for (const glm::dvec4& plane : sidePlanes_) {
    const glm::dvec3 positive(plane.x >= 0.0 ? box.max.x : box.min.x, plane.y >= 0.0 ? box.max.y : box.min.y,
                              plane.z >= 0.0 ? box.max.z : box.min.z);
    const glm::dvec3 negative(plane.x >= 0.0 ? box.min.x : box.max.x, plane.y >= 0.0 ? box.min.y : box.max.y,
                              plane.z >= 0.0 ? box.min.z : box.max.z);
    const double outside = glm::dot(glm::dvec3(plane), positive) + plane.w;
    if (outside < 0.0) {
      e.visible = false;
      marginOut = std::max(marginOut, -outside);
    }
    marginIn = std::min(marginIn, std::max(0.0, glm::dot(glm::dvec3(plane), negative) + plane.w));
  }
  e.marginInM = float(marginIn);
  e.marginOutM = float(marginOut);
  e.reachM = float(glm::length(glm::max(glm::abs(box.min), glm::abs(box.max))));
  const double distance = std::max(box.distanceTo(glm::dvec3(0.0)), 1e-3);
  const double scale = exaggeration * view_.pixelsPerRadian;
  const double bound = double(nodeBoundM(id));
  e.distanceSlackM = float(distance - bound * scale / double(settings_.targetPx));
  e.priority = e.visible ? float(bound * scale / distance) : 0.0f;
  return e;
}

void RoamMesh::setDeferral(std::int32_t id, float slackM, float reachM) {
  deferral_[std::size_t(id)] = {slackM, reachM, float(travelM_), float(turnRad_)};
}

void RoamMesh::clearDeferral(std::int32_t id) {
  deferral_[std::size_t(id)].slackM = std::numeric_limits<float>::infinity();
}

float RoamMesh::priority(std::int32_t id) {
  const Evaluation e = evaluate(id);
  node(id).visible = e.visible;
  if (!e.visible) {  // stays at 0 until the box may enter the frustum
    setDeferral(id, e.marginOutM, e.reachM);
  } else if (e.priority < settings_.targetPx) {  // stays below until the camera comes closer
    setDeferral(id, e.distanceSlackM, 0.0f);  // turning away only lowers it to 0: no decision changes
  } else {
    setDeferral(id, -1.0f, 0.0f);  // above the target (left by a budget): every frame
  }
  return e.priority;
}

float RoamMesh::diamondPriority(std::int32_t id) {
  const std::int32_t base = node(id).base;
  Evaluation e = evaluate(id);
  if (base >= 0) {
    const Evaluation other = evaluate(base);
    if (other.priority > e.priority) e = other;
  }
  if (e.priority > settings_.targetPx) {
    // Stays above while neither the distance nor the frustum's sides pass the larger half.
    setDeferral(id, std::min(-e.distanceSlackM, e.marginInM), e.reachM);
  } else {
    setDeferral(id, -1.0f, 0.0f);  // below the target (left by the time budget): every frame
  }
  return e.priority;
}

bool RoamMesh::deferred(const Deferral& d) const {
  const double travel = travelM_ - double(d.travel0);
  const double turn = turnRad_ - double(d.turn0);
  return travel + turn * (double(d.reachM) + travel) < double(d.slackM);
}

void RoamMesh::beginFrame(const RoamView& view) {
  bool invalidate = !viewValid_ || view.pixelsPerRadian != view_.pixelsPerRadian ||
                    view.exaggeration != view_.exaggeration || view.aspect != view_.aspect ||
                    settings_.targetPx != lastTargetPx_;
  if (viewValid_) {
    travelM_ += glm::length(view.cameraM - view_.cameraM);
    // The angle of the rotation between the two camera frames.
    const glm::dmat3 relative = view.rotation * glm::transpose(view_.rotation);
    const double cosine = std::clamp((relative[0][0] + relative[1][1] + relative[2][2] - 1.0) * 0.5, -1.0, 1.0);
    turnRad_ += std::acos(cosine) + 1e-9;
  }
  view_ = view;
  viewValid_ = true;
  lastTargetPx_ = settings_.targetPx;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec4 plane = view.frustum.planes()[std::size_t(i)];
    sidePlanes_[std::size_t(i)] = plane / glm::length(glm::dvec3(plane));
  }
  // The totals are kept small, so that the floats of the deferrals stay precise.
  if (travelM_ > 1e5 || turnRad_ > 1e3) {
    for (Deferral& d : deferral_) {
      d.travel0 = float(double(d.travel0) - travelM_);
      d.turn0 = float(double(d.turn0) - turnRad_);
    }
    travelM_ = turnRad_ = 0.0;
  }
  if (invalidate) {
    for (Deferral& d : deferral_) d.slackM = -1.0f;
  }
}

std::int32_t RoamMesh::diamondKey(std::int32_t id) const {
  const std::int32_t base = node(id).base;
  return base < 0 || id < base ? id : base;
}

bool RoamMesh::isMergeable(std::int32_t id) const {
  const auto childrenAreLeaves = [&](std::int32_t x) {
    const std::int32_t c = node(x).child;
    return c >= 0 && isLeaf(c) && isLeaf(c + 1);
  };
  if (!childrenAreLeaves(id)) return false;
  const std::int32_t base = node(id).base;
  return base < 0 || (node(base).base == id && childrenAreLeaves(base));
}

void RoamMesh::replaceNeighbour(std::int32_t at, std::int32_t from, std::int32_t to) {
  Node& n = node(at);
  if (n.base == from) {
    n.base = to;
  } else if (n.left == from) {
    n.left = to;
  } else if (n.right == from) {
    n.right = to;
  }
}

void RoamMesh::ensureBounds(std::int32_t blockIndex) {
  BlockState& block = blocks_[std::size_t(blockIndex)];
  if (block.inIdleList) {
    idleBlocks_.erase(block.idle);
    block.inIdleList = false;
  }
  if (block.bounds) return;
  block.bounds = std::make_unique<BlockBounds>(computeBlockBounds(
      *grid_, domain_, blockIndex % domain_.blocksX, blockIndex / domain_.blocksX));
  boundsBytes_ += block.bounds->bounds.size() * sizeof(std::uint16_t);
  trimBounds();
}

void RoamMesh::trimBounds() {
  while (boundsBytes_ > settings_.boundsBudgetBytes && !idleBlocks_.empty()) {
    BlockState& block = blocks_[std::size_t(idleBlocks_.front())];
    idleBlocks_.pop_front();
    block.inIdleList = false;
    boundsBytes_ -= block.bounds->bounds.size() * sizeof(std::uint16_t);
    block.bounds.reset();
  }
}

void RoamMesh::splitOne(std::int32_t id) {
  if (node(id).depth == 0) {
    ensureBounds(node(id).block);
    ++blocks_[std::size_t(node(id).block)].splitRoots;
  }
  const std::int32_t l = allocatePair(), r = l + 1;  // may move nodes_: no references above
  Node& n = node(id);
  for (const std::int32_t c : {l, r}) {
    Node& child = node(c);
    child.parent = id;
    child.depth = std::uint8_t(n.depth + 1);
    child.block = n.block;
    child.root = n.root;
    child.alive = true;
  }
  node(l).tri = leftChild(n.tri);
  node(r).tri = rightChild(n.tri);
  // The children's corners: the new midpoint's height, read once, and the parent's.
  const float centre = heightAt(*grid_, node(l).tri.apex);
  node(l).height = {centre, n.height[0], n.height[1]};
  node(r).height = {centre, n.height[2], n.height[0]};
  node(l).heap = 2 * n.heap;
  node(r).heap = 2 * n.heap + 1;
  node(l).left = r;
  node(r).right = l;
  node(l).base = n.left;
  node(r).base = n.right;
  if (n.left >= 0) replaceNeighbour(n.left, id, l);
  if (n.right >= 0) replaceNeighbour(n.right, id, r);
  n.child = l;
  splitQueue_.remove(id);
  splitQueue_.set(l, priority(l));
  splitQueue_.set(r, priority(r));
  ++leaves_;
  ++splitsThisFrame_;
  if (node(id).parent >= 0) mergeQueue_.remove(diamondKey(node(id).parent));
}

void RoamMesh::split(std::int32_t id, int guard) {
  if (node(id).child >= 0 || node(id).depth >= domain_.leafDepth() || guard > 64) return;
  std::int32_t base = node(id).base;
  if (base >= 0 && node(base).base != id) {
    split(base, guard + 1);  // a coarser base neighbour: forced split
    base = node(id).base;    // now its child across our hypotenuse
    if (base >= 0 && node(base).base != id) return;  // cannot happen in a valid bintree
  }
  splitOne(id);
  if (base >= 0) {
    splitOne(base);
    const std::int32_t tl = node(id).child, tr = tl + 1;
    const std::int32_t bl = node(base).child, br = bl + 1;
    node(tl).right = br;
    node(tr).left = bl;
    node(bl).right = tr;
    node(br).left = tl;
  }
  const std::int32_t key = diamondKey(id);
  mergeQueue_.set(key, diamondPriority(key));
}

void RoamMesh::refreshParentDiamond(std::int32_t id) {
  const std::int32_t parent = node(id).parent;
  if (parent >= 0 && isMergeable(parent)) {
    const std::int32_t key = diamondKey(parent);
    mergeQueue_.set(key, diamondPriority(key));
  }
}

void RoamMesh::merge(std::int32_t id) {
  const std::int32_t base = node(id).base;
  mergeQueue_.remove(diamondKey(id));
  for (const std::int32_t x : {id, base}) {
    if (x < 0) continue;
    const std::int32_t l = node(x).child, r = l + 1;
    Node& n = node(x);
    n.left = node(l).base;
    n.right = node(r).base;
    if (n.left >= 0) replaceNeighbour(n.left, l, x);
    if (n.right >= 0) replaceNeighbour(n.right, r, x);
    splitQueue_.remove(l);
    splitQueue_.remove(r);
    freePair(l);
    node(x).child = -1;
    splitQueue_.set(x, priority(x));
    --leaves_;
    if (node(x).depth == 0) {
      BlockState& block = blocks_[std::size_t(node(x).block)];
      if (--block.splitRoots == 0 && block.bounds) {
        block.idle = idleBlocks_.insert(idleBlocks_.end(), node(x).block);
        block.inIdleList = true;
        trimBounds();
      }
    }
  }
  for (const std::int32_t x : {id, base}) {
    if (x >= 0) refreshParentDiamond(x);
  }
}

bool RoamMesh::splitLeaf(std::int32_t id) {
  if (!node(id).alive || !isLeaf(id) || node(id).depth >= domain_.leafDepth()) return false;
  split(id, 0);
  return !isLeaf(id);
}

bool RoamMesh::mergeDiamond(std::int32_t id) {
  if (!node(id).alive || !isMergeable(id)) return false;
  merge(id);
  return true;
}

RoamFrameReport RoamMesh::update(const RoamView& view) {
  RoamFrameReport report;
  const Stopwatch sinceStart;  // the time budget's clock
  Stopwatch stage;
  beginFrame(view);
  splitsThisFrame_ = 0;
  // Re-prioritise the queue entries whose deferral ran out (all of them after a change of
  // projection, exaggeration or target), in node order.
  for (std::size_t i = 0; i < deferral_.size(); ++i) {
    if (deferred(deferral_[i])) continue;
    const auto id = std::int32_t(i);
    const Node& n = nodes_[i];
    if (n.alive && n.child < 0) {
      splitQueue_.set(id, priority(id));
      ++report.reprioritised;
    } else if (n.alive && mergeQueue_.contains(id)) {
      mergeQueue_.set(id, diamondPriority(id));
      ++report.reprioritised;
    } else {
      clearDeferral(id);  // in no queue (split, or free)
    }
  }
  report.priorityMs = stage.lapMs();
  bool budgetReached = false;
  for (std::uint64_t ops = 1;; ++ops) {
    if (settings_.timeBudgetMs > 0.0 && ops % 32 == 0 && sinceStart.elapsedMs() > settings_.timeBudgetMs) {
      report.timeReached = true;
      break;
    }
    if (leaves_ > settings_.triangleBudget) {
      // Over budget: coarsen from the bottom whatever the error, and refine no more.
      const std::int32_t lowest = mergeQueue_.bottom();
      if (lowest < 0) break;
      merge(lowest);
      budgetReached = true;
      ++report.merges;
      continue;
    }
    if (!budgetReached) {
      const std::int32_t highest = splitQueue_.top();
      if (highest >= 0 && splitQueue_.priority(highest) > settings_.targetPx) {
        split(highest, 0);
        if (isLeaf(highest)) budgetReached = true;  // could not split: stop refining
        continue;
      }
    }
    const std::int32_t lowest = mergeQueue_.bottom();
    if (lowest >= 0 && mergeQueue_.priority(lowest) < settings_.targetPx) {
      merge(lowest);
      ++report.merges;
      continue;
    }
    break;
  }
  report.queueMs = stage.lapMs();
  report.splits = splitsThisFrame_;
  report.leaves = leaves_;
  report.diamonds = std::uint32_t(mergeQueue_.size());
  const std::int32_t top = splitQueue_.top();
  report.maxSplitPriorityPx = top >= 0 ? splitQueue_.priority(top) : 0.0f;
  report.budgetReached = budgetReached;
  return report;
}

std::size_t RoamMesh::emit(glm::vec4* out) const {
  std::size_t triangles = 0;
  const int leafDepth = domain_.leafDepth();
  for (const Node& n : nodes_) {
    if (!n.alive || n.child >= 0 || !n.visible) continue;
    const glm::ivec2 a = domain_.clampToGrid(n.tri.apex);
    const glm::ivec2 l = domain_.clampToGrid(n.tri.left);
    const glm::ivec2 r = domain_.clampToGrid(n.tri.right);
    const glm::ivec2 e1 = l - a, e2 = r - a;
    if (e1.x * e2.y - e1.y * e2.x == 0) continue;  // wholly outside the grid: flattened
    const float level = float((leafDepth - n.depth) / 2);
    const bool turned = n.depth == leafDepth && !hasDrawnDiagonal(n.tri) && n.base >= 0 &&
                        a == n.tri.apex && l == n.tri.left && r == n.tri.right &&
                        node(n.base).child < 0 && node(n.base).tri.apex == l + r - a;
    if (turned) {
      // A half cell whose hypotenuse is the NW-SE diagonal and whose base neighbour is the
      // cell's other half: the cell is drawn along its SW-NE diagonal instead
      // (roam_error_bounds.hpp). This leaf draws the half of the turned cell that starts at its
      // left corner, the other half the rest. Both halves have the same box (the same
      // hypotenuse), so they are culled together; should their flags ever disagree, this leaf
      // draws the whole cell.
      const Node& other = node(n.base);
      const glm::ivec2 o = other.tri.apex;  // the corner opposite the apex
      const glm::vec4 apex(float(a.x), float(a.y), n.height[0], level);
      const glm::vec4 opposite(float(o.x), float(o.y), other.height[0], level);
      out[0] = apex;
      out[1] = glm::vec4(float(l.x), float(l.y), n.height[1], level);
      out[2] = opposite;
      out += 3;
      ++triangles;
      if (!other.visible) {
        out[0] = apex;
        out[1] = opposite;
        out[2] = glm::vec4(float(r.x), float(r.y), n.height[2], level);
        out += 3;
        ++triangles;
      }
      continue;
    }
    out[0] = glm::vec4(float(a.x), float(a.y), n.height[0], level);
    out[1] = glm::vec4(float(l.x), float(l.y), n.height[1], level);
    out[2] = glm::vec4(float(r.x), float(r.y), n.height[2], level);
    out += 3;
    ++triangles;
  }
  return triangles;
}

std::size_t RoamMesh::emit(std::vector<glm::vec4>& vertices) const {
  const std::size_t first = vertices.size();
  vertices.resize(first + 3 * std::size_t(leaves_));
  const std::size_t triangles = emit(vertices.data() + first);
  vertices.resize(first + 3 * triangles);
  return triangles;
}

std::vector<std::int32_t> RoamMesh::leafIds() const {
  std::vector<std::int32_t> ids;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].alive && nodes_[i].child < 0) ids.push_back(std::int32_t(i));
  }
  return ids;
}

std::vector<BintreeTriangle> RoamMesh::leaves() const {
  std::vector<BintreeTriangle> out;
  for (const std::int32_t id : leafIds()) out.push_back(node(id).tri);
  return out;
}

std::vector<std::int32_t> RoamMesh::mergeableDiamondIds() const {
  std::vector<std::int32_t> ids;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const auto id = std::int32_t(i);
    if (nodes_[i].alive && isMergeable(id) && diamondKey(id) == id) ids.push_back(id);
  }
  return ids;
}

Status RoamMesh::checkStructure() const {
  std::uint32_t leaves = 0;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    const auto id = std::int32_t(i);
    if (!n.alive) continue;
    // A leaf's neighbours are leaves (a split neighbour would have forced a split here); a
    // split node's base is its diamond's other half, split too. A split node's leg links are
    // stale until it is merged again, and not checked.
    const bool leafNode = n.child < 0;
    for (const std::int32_t link : {n.left, n.right, n.base}) {
      if (link < 0 || (!leafNode && link != n.base)) continue;
      if (!node(link).alive) return makeError("node {} links to a freed node {}", id, link);
      if ((node(link).child < 0) != leafNode) {
        return makeError("node {} ({}) has a neighbour {} that is {}", id, leafNode ? "a leaf" : "split",
                         link, leafNode ? "split" : "a leaf");
      }
    }
    if (n.parent >= 0 && !node(n.parent).alive) return makeError("node {} has a freed parent", id);
    if (n.base >= 0 && node(n.base).base == id) {
      const BintreeTriangle& other = node(n.base).tri;
      if (other.left != n.tri.right || other.right != n.tri.left) {
        return makeError("node {} and its base neighbour {} do not share the hypotenuse", id, n.base);
      }
    }
    const bool leaf = n.child < 0;
    if (leaf) ++leaves;
    if (leaf != splitQueue_.contains(id)) {
      return makeError("node {} is {} but {} in the split queue", id, leaf ? "a leaf" : "split",
                       leaf ? "not" : "is");
    }
    const bool key = !leaf && isMergeable(id) && diamondKey(id) == id;
    if (key != mergeQueue_.contains(id)) {
      return makeError("diamond {} is {}mergeable but {} in the merge queue", id, key ? "" : "not ",
                       key ? "not" : "is");
    }
  }
  if (leaves != leaves_) return makeError("{} leaves counted, {} kept", leaves, leaves_);
  return {};
}

}  // namespace tellus::roam
