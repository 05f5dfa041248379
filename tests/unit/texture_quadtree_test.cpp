// The texture quadtree (lod/spiral/texture_quadtree.hpp) against a model of the screen: a window
// of the image is seen, each level-0 texel inside it covering `density` pixels, nothing outside.
// Detail goes where the camera looks and comes back where it no longer does; what is drawn is
// always resident and never freed; memory stays within the budget; transfers within their cap;
// a steady view settles without oscillating.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "tellus/lod/spiral/texture_quadtree.hpp"

namespace tellus {
namespace {

constexpr ImageryLayout kLayout{3000, 2500, 64, 7};  // 3000, 1500, ... 47 texels: 7 levels

struct Window {
  double x0, y0, x1, y1;  // level-0 texels seen
  double density;         // pixels a level-0 texel
};

// The pixels a drawn node covers in the model.
std::uint64_t pixelsOf(const QuadDrawnNode& node, const Window& w) {
  const QuadTextureRect r = quadTextureRect(kLayout, {node.id, node.mip});
  const double s = double(1 << node.mip);
  const double x0 = std::max(w.x0, r.x0 * s), x1 = std::min(w.x1, std::min(r.x1 * s, double(kLayout.width)));
  const double y0 = std::max(w.y0, r.y0 * s), y1 = std::min(w.y1, std::min(r.y1 * s, double(kLayout.height)));
  if (x1 <= x0 || y1 <= y0) return 0;
  return std::uint64_t((x1 - x0) * (y1 - y0) * w.density);
}

// One frame: count what is drawn, update. Checks the invariants every frame.
QuadtreeUpdate frame(TextureQuadtree& tree, const Window& w) {
  for (const QuadDrawnNode& node : tree.drawn()) tree.reportPixels(node.id, node.mip, pixelsOf(node, w));
  const QuadtreeUpdate update = tree.update();
  for (const QuadDrawnNode& node : tree.drawn()) {
    EXPECT_TRUE(tree.isResident({node.id, node.mip})) << "a drawn node without its texture";
    for (const QuadTextureId& evicted : update.evictions) {
      EXPECT_FALSE(evicted.node == node.id && evicted.mip == node.mip) << "a drawn texture freed";
    }
  }
  EXPECT_LE(tree.residentBytes(), tree.params().memoryBudgetBytes);
  return update;
}

// The drawn node holding level-0 texel (x, y).
QuadDrawnNode nodeAt(const TextureQuadtree& tree, double x, double y) {
  for (const QuadDrawnNode& node : tree.drawn()) {
    const double side = double(kLayout.tileSize) * double(1 << node.id.level);
    if (x >= node.id.x * side && x < (node.id.x + 1) * side && y >= node.id.y * side &&
        y < (node.id.y + 1) * side) {
      return node;
    }
  }
  ADD_FAILURE() << "nothing drawn at " << x << ", " << y;
  return {};
}

// Drawn nodes cover the image once: their level-0 areas add up to the image's.
void expectTheImageCoveredOnce(const TextureQuadtree& tree) {
  double area = 0.0;
  for (const QuadDrawnNode& node : tree.drawn()) {
    const double side = double(kLayout.tileSize) * double(1 << node.id.level);
    const double x0 = node.id.x * side, y0 = node.id.y * side;
    area += (std::min(x0 + side, double(kLayout.width)) - x0) *
            (std::min(y0 + side, double(kLayout.height)) - y0);
  }
  EXPECT_DOUBLE_EQ(area, double(kLayout.width) * kLayout.height);
}

TEST(TextureQuadtree, DetailGoesWhereTheCameraLooksAndLeavesWhereItNoLongerDoes) {
  TextureQuadtree tree(kLayout, {.leafLevel = 2});
  // A window of 400 x 300 texels, each covering a sixteenth of a pixel: mip 2 is one texel a
  // pixel there.
  const Window near{200, 300, 600, 600, 1.0 / 16.0};
  for (int f = 0; f < 40; ++f) frame(tree, near);
  expectTheImageCoveredOnce(tree);
  EXPECT_EQ(nodeAt(tree, 400, 450).mip, 2);
  // Far from the window, the tree stays coarse.
  EXPECT_GE(nodeAt(tree, 2800, 2300).id.level, 5);
  // The view moves to the other corner: detail follows, the old window merges back.
  const Window moved{2300, 1900, 2900, 2400, 1.0 / 16.0};
  for (int f = 0; f < 60; ++f) frame(tree, moved);
  expectTheImageCoveredOnce(tree);
  EXPECT_EQ(nodeAt(tree, 2600, 2100).mip, 2);
  EXPECT_GE(nodeAt(tree, 400, 450).id.level, 5);
  // Zooming in: leaves page in their finer mips down to full resolution, without splitting.
  const Window close{2200, 1950, 2700, 2400, 2.0};  // holds the leaf 2304..2560 x 2048..2304
  for (int f = 0; f < 40; ++f) frame(tree, close);
  const QuadDrawnNode finest = nodeAt(tree, 2400, 2150);
  EXPECT_EQ(finest.mip, 0);
  EXPECT_EQ(finest.id.level, 2);
}

TEST(TextureQuadtree, ASteadyViewSettlesWithoutOscillating) {
  TextureQuadtree tree(kLayout, {.leafLevel = 2});
  const Window w{1000, 1000, 1700, 1500, 1.0 / 10.0};
  for (int f = 0; f < 40; ++f) frame(tree, w);
  for (int f = 0; f < 20; ++f) {
    const QuadtreeUpdate u = frame(tree, w);
    EXPECT_EQ(u.splits + u.merges + u.finerMips + u.coarserMips, 0) << "frame " << f;
    EXPECT_TRUE(u.uploads.empty());
  }
}

TEST(TextureQuadtree, ChangesOnlyOutsideTheHysteresisBand) {
  // The whole image seen evenly: the root's texel covers 64 x 64 level-0 texels.
  const auto seen = [](double pixelsPerRootTexel) {
    return Window{0, 0, 3000, 2500, pixelsPerRootTexel / 4096.0};
  };
  TextureQuadtree tree(kLayout, {.leafLevel = 2});
  for (int f = 0; f < 3; ++f) frame(tree, seen(0.9));
  ASSERT_EQ(tree.drawn().size(), 1u);
  for (int f = 0; f < 3; ++f) frame(tree, seen(1.05));  // just past one pixel a texel: split
  EXPECT_EQ(tree.drawn().size(), 4u);
  // Back down by 30 %: the children stay (merging waits for half the parent's texels).
  for (int f = 0; f < 5; ++f) {
    const QuadtreeUpdate u = frame(tree, seen(0.8));
    EXPECT_EQ(u.merges, 0);
  }
  EXPECT_EQ(tree.drawn().size(), 4u);
  for (int f = 0; f < 3; ++f) frame(tree, seen(0.45));  // below half: merge
  EXPECT_EQ(tree.drawn().size(), 1u);
}

TEST(TextureQuadtree, StaysWithinItsMemoryBudgetAndTransferCap) {
  // A budget for a few dozen tiles, one transfer per update.
  const TextureQuadtreeParams params{.leafLevel = 2, .maxTransfersPerUpdate = 1,
                                     .memoryBudgetBytes = 40 * quadTextureBytes(kLayout, {{0, 0, 0}, 0})};
  TextureQuadtree tree(kLayout, params);
  int deferred = 0;
  for (int f = 0; f < 300; ++f) {
    // A zoom in and out over a wide window: wants more than the budget holds.
    const double density = 0.01 * std::pow(2.0, 8.0 * std::sin(f * 0.05));
    const QuadtreeUpdate u = frame(tree, {0, 0, 3000, 2500, density});
    if (f > 0) {
      EXPECT_LE(u.uploads.size(), 1u) << "frame " << f;
    }
    deferred += u.deferred;
  }
  EXPECT_GT(deferred, 0);  // the caps held changes back
  expectTheImageCoveredOnce(tree);
}

TEST(TextureQuadtree, ADrawnNodeWithNoPixelsIsStillDrawnAndCanComeBack) {
  TextureQuadtree tree(kLayout, {.leafLevel = 2});
  for (int f = 0; f < 5; ++f) frame(tree, {0, 0, 0, 0, 1.0});  // nothing seen
  ASSERT_EQ(tree.drawn().size(), 1u);
  EXPECT_EQ(tree.drawn().front().id, tree.root());
  for (int f = 0; f < 30; ++f) frame(tree, {1000, 1000, 1400, 1300, 1.0 / 16.0});
  EXPECT_GT(tree.drawn().size(), 4u);
}

TEST(TextureQuadtree, StaleCountsAreIgnored) {
  TextureQuadtree tree(kLayout, {.leafLevel = 2});
  tree.update();
  const QuadNodeId root = tree.root();
  tree.reportPixels(root, root.level - 1, 1u << 30);  // counted at another mip
  tree.reportPixels({0, 0, 0}, 0, 1u << 30);          // a node not drawn
  const QuadtreeUpdate u = tree.update();
  EXPECT_EQ(u.splits, 0);
  EXPECT_EQ(tree.drawn().size(), 1u);
}

}  // namespace
}  // namespace tellus
