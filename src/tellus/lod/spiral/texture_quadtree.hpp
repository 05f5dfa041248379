#pragma once
// The texture quadtree of seed 001 ("High-Resolution Texturing Level of Detail"), GL-free: which
// pieces of a large image (an imagery pyramid, dem/imagery_pyramid.hpp) are drawn at which
// detail, decided from how many pixels each drawn piece covered (the renderer's occlusion
// queries, read a frame or more late), and which textures to transfer or free to get there.
//
// The tree: node (level, x, y) is tile (x, y) of the pyramid's level `level`; the root is the
// last level's single tile; a node's children are the (up to four) tiles of level - 1 below it.
// A node draws its region with one texture of the region at some mip level m <= level: texels
// (region size) / 2^m. Nodes above the leaf level draw at m = level (one tile's texels); leaves
// (level <= leafLevel) do not split but page in finer mips down to 0 instead (the seed's leaves
// "with multiple levels of detail").
//
// Detail follows the pixels-per-texel rule with hysteresis: a drawn node whose count P exceeds
// its texels T (times splitAbove) wants more detail (split, or a leaf's finer mip); a leaf whose
// P is below mergeBelow times the texels of its coarser mip wants that mip; four siblings whose
// summed P is below mergeBelow times their parent's texels merge. With splitAbove 1 and
// mergeBelow 0.5 a node changes detail only once its pixels have moved by a factor of two past
// the point where it changed, so steady views never oscillate.
//
// Residency: every drawn node's texture is resident (a change is applied only once all the
// textures it needs are, and the old ones stay until then: nothing drawn ever disappears);
// textures no longer drawn stay as a cache, freed least recently drawn first when a transfer
// would exceed the memory budget; drawn textures are never freed. Transfers per update can be
// capped (the seed's "one transfer per update", smoothing the spikes of Table 2).
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <vector>

namespace tellus {

// The pyramid's shape: level m is ceil(width / 2^m) x ceil(height / 2^m) texels in square
// tiles of tileSize; the last level is one tile.
struct ImageryLayout {
  int width = 0, height = 0, tileSize = 256, levels = 1;
  int levelWidth(int level) const;
  int levelHeight(int level) const;
  int tilesX(int level) const;
  int tilesY(int level) const;
};

struct QuadNodeId {
  int level = 0, x = 0, y = 0;
  auto operator<=>(const QuadNodeId&) const = default;
};

// A node's region at one mip level: what one texture holds.
struct QuadTextureId {
  QuadNodeId node;
  int mip = 0;
  auto operator<=>(const QuadTextureId&) const = default;
};

// Where a texture's texels lie: [x0, x1) x [y0, y1) texels of level `mip`; in level-0 texels
// (pixel corners) that is [x0 2^mip, x1 2^mip) x ...
struct QuadTextureRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};
QuadTextureRect quadTextureRect(const ImageryLayout& layout, const QuadTextureId& id);
// GPU bytes of the texture with its mip chain (RGBA8).
std::uint64_t quadTextureBytes(const ImageryLayout& layout, const QuadTextureId& id);

struct TextureQuadtreeParams {
  int leafLevel = 2;         // nodes of this level and finer do not split (clamped to the root)
  double splitAbove = 1.0;   // more detail when pixels > splitAbove x texels
  double mergeBelow = 0.5;   // less when pixels < mergeBelow x the coarser choice's texels
  int maxTransfersPerUpdate = 0;  // 0: no cap; 1: the seed's one transfer per update
  std::uint64_t memoryBudgetBytes = std::uint64_t(192) << 20;
};

struct QuadDrawnNode {
  QuadNodeId id;
  int mip = 0;
  std::optional<double> pixels;  // the last count at this mip over its visible fraction
};

struct QuadtreeUpdate {
  std::vector<QuadTextureId> uploads;    // transfer these now (before drawing), in order
  std::vector<QuadTextureId> evictions;  // free these
  int splits = 0, merges = 0, finerMips = 0, coarserMips = 0;
  int deferred = 0;  // changes wanted but left for later (transfer cap or memory budget)
};

class TextureQuadtree {
 public:
  TextureQuadtree(ImageryLayout layout, TextureQuadtreeParams params);

  const ImageryLayout& layout() const { return layout_; }
  const TextureQuadtreeParams& params() const { return params_; }
  QuadNodeId root() const { return {layout_.levels - 1, 0, 0}; }
  int leafLevel() const { return leafLevel_; }

  // The nodes to draw, each with a resident texture (empty before the first update). A node
  // that covered no pixels is still drawn: it must be, to be counted again.
  std::vector<QuadDrawnNode> drawn() const;
  // The count of a node drawn at `mip`, samples over the frame's pixels, and the fraction of
  // the node inside the view when it was drawn (the renderer's estimate): the node is judged by
  // pixels / visibleFraction, what it would cover were it all in view. The seed compares the
  // raw count, and names the flaw: a node half off screen counts half its pixels and loses
  // detail at the screen's edge, and a large node seen close up (a small part of it filling
  // the view) never splits. Counts for nodes no longer drawn, or drawn at another mip since,
  // are ignored.
  void reportPixels(const QuadNodeId& node, int mip, std::uint64_t pixels,
                    double visibleFraction = 1.0);
  // Decides this update's changes from the counts reported so far, and applies those whose
  // textures are (or, within the caps, become) resident. `uncapped`: no transfer cap (stills).
  QuadtreeUpdate update(bool uncapped = false);

  bool isResident(const QuadTextureId& id) const { return resident_.contains(id); }
  std::uint64_t residentBytes() const { return residentBytes_; }
  std::size_t residentCount() const { return resident_.size(); }

 private:
  struct Drawn {
    int mip = 0;
    std::optional<double> pixels;
  };
  struct Resident {
    std::uint64_t bytes = 0;
    std::uint64_t lastDrawn = 0;
  };
  std::vector<QuadNodeId> childrenOf(const QuadNodeId& node) const;
  std::uint64_t texels(const QuadTextureId& id) const;
  // Makes `id` resident if it is not: false when the transfer cap or the memory budget (after
  // freeing what is neither drawn nor in `keep`) does not allow it.
  bool makeResident(const QuadTextureId& id, const std::set<QuadTextureId>& keep,
                    int& transfersLeft, QuadtreeUpdate& out);

  ImageryLayout layout_;
  TextureQuadtreeParams params_;
  int leafLevel_ = 0;
  std::map<QuadNodeId, Drawn> drawn_;
  std::map<QuadTextureId, Resident> resident_;
  std::uint64_t residentBytes_ = 0;
  std::uint64_t updates_ = 0;
};

}  // namespace tellus
