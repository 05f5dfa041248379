#pragma once
// ROAM, real-time optimally adapting meshes (Duchaineau et al. 1997; seed 004 section 2.1): a
// triangle bintree over the height grid (roam_error_bounds.hpp) refined and coarsened every frame
// by two priority queues carried over from the previous frame (frame coherence):
//   - the split queue holds every leaf triangle, by its projected error bound (pixels);
//   - the merge queue holds every mergeable diamond (a split triangle and its base neighbour,
//     all four children leaves), by the larger of the two parents' priorities.
// Splitting a triangle whose base neighbour is coarser first splits the neighbour (forced
// splits, recursively), so the mesh never has a T-junction. Each frame the priorities are
// recomputed for the new view, then the highest-priority leaves are split while above the
// error target and the lowest diamonds merged while below it, within the seed's stopping
// rules: a triangle budget (over it, diamonds are merged from the bottom whatever their error),
// the error target, and a time budget.
//
// Deferred priority recomputation (Duchaineau et al., section 6.4): each queue entry keeps how
// far the camera may move (and turn, weighted by the entry's distance) before its priority
// could cross the error target or its box the frustum's sides; until then it is not
// recomputed. So a frame re-prioritises the entries near a decision, not the whole mesh.
//
// A node's priority is its wedgie bound projected at the nearest point of a box that holds the
// node and all its descendants (xy: 0.625 of the hypotenuse around its midpoint; z: the
// block's height range), so priorities nest like the bounds: a child never outranks its
// parent, and a split is never undone by the merge rule in the same frame. Nodes whose box is
// outside the view frustum get priority 0 and are not drawn.
//
// Memory: 2 bytes of bounds per sample of a block once one of its roots is split (roam_error_
// bounds.hpp), 64 bytes per bintree node in use; blocks whose roots are leaves drop their
// bounds when the total exceeds RoamSettings::boundsBudgetBytes (recomputed when needed).
// GL-free; the renderer (render/roam/) uploads emit()'s triangles each frame.
#include <chrono>
#include <cstdint>
#include <list>
#include <memory>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "tellus/core/camera.hpp"
#include "tellus/core/frustum.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/lod/lod_view.hpp"
#include "tellus/lod/roam/roam_bucket_queue.hpp"
#include "tellus/lod/roam/roam_error_bounds.hpp"

namespace tellus::roam {

struct RoamSettings {
  float targetPx = 1.0f;                       // error target: split above, merge below, pixels
  std::uint32_t triangleBudget = 4'000'000;    // leaves at most
  double timeBudgetMs = 0.0;                   // split/merge time a frame at most (0: no limit)
  int blockLog2 = 7;                           // block side 2^blockLog2 cells
  std::size_t boundsBudgetBytes = std::size_t(512) << 20;
};

// The view ROAM refines for (shared with the other CPU selections).
using RoamView = LodView;

// What one update() did.
struct RoamFrameReport {
  std::uint32_t splits = 0;        // triangles split, forced ones included
  std::uint32_t merges = 0;        // diamonds merged
  std::uint32_t leaves = 0;        // after the update
  std::uint32_t diamonds = 0;      // mergeable diamonds after the update
  std::uint32_t reprioritised = 0;  // queue entries whose priority was recomputed
  double priorityMs = 0.0;         // re-prioritising both queues for the view
  double queueMs = 0.0;            // the split/merge loop
  float maxSplitPriorityPx = 0.0f;  // the split queue's top after the update
  bool budgetReached = false;      // the triangle budget stopped refinement
  bool timeReached = false;        // the time budget stopped the loop
};

class RoamMesh {
 public:
  // `grid` must outlive the mesh. Errors: a grid below 2 x 2, blockLog2 outside [1, 10].
  static Result<std::unique_ptr<RoamMesh>> create(const HeightGrid& grid, const RoamSettings& settings);

  RoamFrameReport update(const RoamView& view);
  // Writes the visible leaves as three (u, v, height, level) vertices each, counter-clockwise
  // from above, vertices clamped onto the grid (leaves wholly outside it are left out), to
  // `out`, which has room for 3 * leafCount() vertices (a mapped GPU buffer). A cell whose two
  // halves are leaves is drawn split along its SW-NE diagonal, as the reference grids draw it
  // (roam_error_bounds.hpp), whichever diagonal the bintree gave it. level is the
  // leaf's level of detail, (leaf depth - its depth) / 2 rounded down: 0 for half cells, one
  // more each time the triangle's size doubles. Returns the triangles written.
  std::size_t emit(glm::vec4* out) const;
  // The same appended to a vector.
  std::size_t emit(std::vector<glm::vec4>& vertices) const;

  const BintreeDomain& domain() const { return domain_; }
  RoamSettings& settings() { return settings_; }
  std::uint32_t leafCount() const { return leaves_; }
  std::size_t nodeCount() const { return nodes_.size() - freePairs_.size() * 2; }
  std::size_t boundsBytes() const { return boundsBytes_; }
  std::size_t residentBoundBlocks() const;

  // For tests: the leaves (all of them, visible or not) and the bintree operations.
  std::vector<BintreeTriangle> leaves() const;
  std::vector<std::int32_t> leafIds() const;
  std::vector<std::int32_t> mergeableDiamondIds() const;  // one node of each diamond
  // Splits a leaf (forcing its neighbours as needed); false at the finest depth.
  bool splitLeaf(std::int32_t id);
  // Merges the diamond of a split node; false when it is not mergeable.
  bool mergeDiamond(std::int32_t id);
  // Neighbour links symmetric and matching edges, queue membership right; error otherwise.
  Status checkStructure() const;
  // The bound of a node, metres (tests check they nest).
  float nodeBoundM(std::int32_t id) const;
  // A node's priority for the last update's view, computed now (tests check the deferred
  // queue entries against it).
  float currentPriority(std::int32_t id) const { return evaluate(id).priority; }
  std::int32_t baseOf(std::int32_t id) const { return nodes_[std::size_t(id)].base; }
  bool isVisible(std::int32_t id) const { return nodes_[std::size_t(id)].visible; }
  std::int32_t parentOf(std::int32_t id) const { return nodes_[std::size_t(id)].parent; }

 private:
  struct Node {
    BintreeTriangle tri;
    std::array<float, 3> height{};  // of apex, left, right (clamped onto the grid), metres
    std::int32_t parent = -1, child = -1;  // child: the left child; the right one is child + 1
    std::int32_t left = -1, right = -1, base = -1;  // neighbours across the legs and hypotenuse
    std::int32_t block = 0;
    std::uint32_t heap = 1;
    std::uint8_t root = 0, depth = 0;
    bool alive = false, visible = true;
  };
  // When a queue entry's priority must be recomputed: once travel + turn * (reach + travel)
  // since (travel0, turn0) reaches slack. Kept apart from the nodes (16 bytes, not 96) so the
  // frame's scan over all entries reads little memory; +infinity for nodes in no queue.
  struct Deferral {
    float slackM = -1.0f, reachM = 0.0f;
    float travel0 = 0.0f, turn0 = 0.0f;  // the running totals, relative to totalsBase_
  };
  struct Evaluation {  // a node's priority and how far the view may move before it changes
    float priority = 0.0f;
    float distanceSlackM = 0.0f;  // distance - bound * scale / target: > 0 when below target
    float marginInM = 0.0f;       // how far the box is inside every side plane (0: straddles)
    float marginOutM = 0.0f;      // how far it is outside one (when not visible)
    float reachM = 0.0f;          // distance to the box's farthest point
    bool visible = true;
  };
  struct BlockState {
    std::unique_ptr<BlockBounds> bounds;  // null when dropped (only the roots are then leaves)
    float minHeightM = 0.0f, maxHeightM = 0.0f;
    std::array<float, 2> rootBoundM{};
    std::uint32_t splitRoots = 0;           // roots of the block that are split
    std::list<std::int32_t>::iterator idle;  // position in idleBlocks_ when no root is split
    bool inIdleList = false;
  };

  RoamMesh() = default;
  Node& node(std::int32_t id) { return nodes_[std::size_t(id)]; }
  const Node& node(std::int32_t id) const { return nodes_[std::size_t(id)]; }
  std::int32_t allocatePair();
  void freePair(std::int32_t first);
  Evaluation evaluate(std::int32_t id) const;
  // Priority of a leaf / of the diamond of a split node; both set the node's deferral.
  float priority(std::int32_t id);
  float diamondPriority(std::int32_t id);
  bool deferred(const Deferral& d) const;
  void setDeferral(std::int32_t id, float slackM, float reachM);
  void clearDeferral(std::int32_t id);
  void beginFrame(const RoamView& view);
  std::int32_t diamondKey(std::int32_t id) const;  // the node that stands for the diamond in the merge queue
  bool isLeaf(std::int32_t id) const { return node(id).child < 0; }
  bool isMergeable(std::int32_t id) const;
  void replaceNeighbour(std::int32_t at, std::int32_t from, std::int32_t to);
  void splitOne(std::int32_t id);
  void split(std::int32_t id, int guard);
  void merge(std::int32_t id);
  void refreshParentDiamond(std::int32_t id);
  void ensureBounds(std::int32_t block);
  void trimBounds();

  const HeightGrid* grid_ = nullptr;
  RoamSettings settings_;
  BintreeDomain domain_;
  std::vector<Node> nodes_;
  std::vector<Deferral> deferral_;  // by node id
  std::vector<std::int32_t> freePairs_;
  std::vector<BlockState> blocks_;
  std::list<std::int32_t> idleBlocks_;  // blocks with bounds and no split root, least recent first
  std::size_t boundsBytes_ = 0;
  BucketQueue splitQueue_, mergeQueue_;
  RoamView view_;
  std::array<glm::dvec4, 4> sidePlanes_{};  // unit normals, camera-relative
  double travelM_ = 0.0, turnRad_ = 0.0;     // cumulative camera motion since the last rebase
  bool viewValid_ = false;
  float lastTargetPx_ = 0.0f;
  std::uint32_t leaves_ = 0;
  std::uint32_t splitsThisFrame_ = 0;
};

}  // namespace tellus::roam
