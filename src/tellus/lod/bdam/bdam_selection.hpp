#pragma once
// BDAM's run-time traversal (seed 004 section 2.2): the patch bintree descended from its roots
// until each patch's screen-space error is under the target, with frustum culling. The error
// test is made on diamonds (the patch and its mate across the hypotenuse share one bounding
// box and one error, the seed's shared bounding volumes), saturated so that a diamond's error
// and box contain its child diamonds'. The test is then monotonic down the tree: a diamond that
// refines has both parent diamonds refined, so the mates are always refined together and the
// cut is conforming (no T-junction; with BDAM's locked borders, no crack).
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "tellus/formats/bdam/bdam_file.hpp"
#include "tellus/core/aabb.hpp"
#include "tellus/core/result.hpp"
#include "tellus/lod/lod_view.hpp"

namespace tellus::bdam {

struct SelectionSettings {
  float targetPx = 4.0f;  // screen-space error target, pixels: of the vertical error seen from the
                          // nearest point of the box, a bound far above what the view shows
                          // (4 px measures 0.9 px at p99 on the Korea flyover)
  bool culling = true;    // leave out patches outside the frustum
  // A leaf whose diamond's error is still over the target is drawn exact, at the grid's full
  // resolution (bdam_exact_leaf.hpp); off: the seed's finest patches are the finest drawn.
  bool exactLeaves = true;
};

// A leaf drawn exact is drawn as its descendants this many levels down (8 pieces of about a
// stored patch's triangles each at the default leaf size), each culled on its own: a walker's
// view takes in a fraction of the leaves around it.
constexpr int kExactPieceLevels = 3;

// A piece of a leaf drawn exact: the leaf's table entry and the piece's bintree node.
struct ExactPiece {
  std::uint32_t leafEntry = 0;
  NodeId node = 0;
};

// One frame's cut: patch table entries drawn as stored, and pieces of leaves drawn exact.
struct Selection {
  std::vector<std::uint32_t> patches;
  std::vector<ExactPiece> exactPieces;
  void clear() {
    patches.clear();
    exactPieces.clear();
  }
};

class PatchTree {
 public:
  // From the patch file's table. Errors: a table whose nodes are not a tree (a patch without
  // its parent).
  static Result<PatchTree> create(const std::vector<PatchEntry>& entries, int domainLog2, int leafLevel,
                                  double spacingXM, double spacingYM);

  // Entries (indices into the table) of the cut for this view, into `out` (cleared first).
  // A leaf is drawn exact when its diamond's error is over the target (settings.exactLeaves),
  // as its pieces kExactPieceLevels down; each is culled against its triangle's box with the
  // leaf's heights grown by the leaf's error, which bounds how far the grid lies from its patch.
  void select(const LodView& view, const SelectionSettings& settings, Selection& out) const;

  // A node's box, nested (contains its children's), world metres, heights not exaggerated.
  const Aabb& box(std::uint32_t entry) const { return box_[entry]; }
  // The saturated error of the entry's diamond, metres.
  float diamondErrorM(std::uint32_t entry) const { return diamondError_[diamondOf_[entry]]; }
  std::uint32_t diamondOf(std::uint32_t entry) const { return diamondOf_[entry]; }
  std::size_t diamondCount() const { return diamondError_.size(); }
  // The entry of `node`, or -1 when the node has no patch (outside the grid).
  long long find(NodeId node) const {
    const auto it = index_.find(node);
    return it == index_.end() ? -1 : static_cast<long long>(it->second);
  }
  int leafLevel() const { return leafLevel_; }

 private:
  void visit(NodeId node, const LodView& view, const SelectionSettings& settings, Selection& out) const;
  // The pieces of exact leaf `leaf` (table entry) under `node` that `view` may show.
  void addExactPieces(std::uint32_t leaf, NodeId node, int levelsLeft, const LodView& view,
                      const SelectionSettings& settings, Selection& out) const;

  int leafLevel_ = 0;
  int domainLog2_ = 0;
  double spacingXM_ = 1.0, spacingYM_ = 1.0;
  std::unordered_map<NodeId, std::uint32_t> index_;
  std::vector<NodeId> node_;
  std::vector<Aabb> box_;
  std::vector<std::uint32_t> diamondOf_;
  std::vector<float> diamondError_;
  std::vector<Aabb> diamondBox_;
};

}  // namespace tellus::bdam
