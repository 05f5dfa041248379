// The imagery virtual texture's pages (lod/imagery/imagery_pages.hpp) and placement
// (lod/imagery/imagery_placement.hpp): numbering, the residency's budgets and order, the page
// table's fallback to the nearest resident ancestor, and where a flat store's world points fall.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "tellus/lod/imagery/imagery_pages.hpp"
#include "tellus/lod/imagery/imagery_placement.hpp"

namespace tellus {
namespace {

int pageOf(const ImageryResidency& r, const ImageryPageKey& key) { return r.layout().pageIndex(key); }

// Two layers: 4 x 3 -> 2 x 2 -> 1 x 1 tiles, and a single tile.
ImageryPageLayout twoLayers() {
  ImageryPageLayout layout;
  const ImageryLevelPages a[] = {{0, 4, 3}, {0, 2, 2}, {0, 1, 1}};
  const ImageryLevelPages b[] = {{0, 1, 1}};
  EXPECT_TRUE(layout.addLayer(a));
  EXPECT_TRUE(layout.addLayer(b));
  return layout;
}

TEST(ImageryPages, NumbersLayersLevelsAndRows) {
  const ImageryPageLayout layout = twoLayers();
  EXPECT_EQ(layout.pageCount(), 12 + 4 + 1 + 1);
  for (int page = 0; page < layout.pageCount(); ++page) {
    EXPECT_EQ(layout.pageIndex(layout.keyOf(page)), page);
  }
  EXPECT_EQ(layout.pageIndex({0, 0, 3, 2}), 11);
  EXPECT_EQ(layout.pageIndex({0, 1, 0, 0}), 12);
  EXPECT_EQ(layout.pageIndex({0, 0, 4, 0}), -1);
  EXPECT_EQ(layout.parentOf(layout.pageIndex({0, 0, 3, 2})), layout.pageIndex({0, 1, 1, 1}));
  EXPECT_EQ(layout.rootOf(0), 16);
  EXPECT_EQ(layout.parentOf(16), -1);
  EXPECT_EQ(layout.rootOf(1), 17);
  ImageryPageLayout bad;
  const ImageryLevelPages notOneTile[] = {{0, 2, 1}};
  EXPECT_FALSE(bad.addLayer(notOneTile));
}

TEST(ImageryPages, RootsFirstThenCoarsestFirstWithinTheUploadBudget) {
  Result<ImageryResidency> made = ImageryResidency::create(twoLayers(), 8, 3);
  ASSERT_TRUE(made);
  ImageryResidency& r = made.value();
  ImageryPlan plan = r.plan();
  ASSERT_EQ(plan.uploads.size(), 2u);  // the two roots, before anything was asked for
  EXPECT_EQ(plan.uploads[0].page, 16);
  EXPECT_EQ(plan.uploads[1].page, 17);
  // Every page lookup finds a root at least.
  for (std::uint32_t entry : r.pageTable()) EXPECT_NE(entry, 0u);

  // A frame wants two fine pages of layer 0: their parents come first.
  const int wanted[] = {pageOf(r, {0, 0, 0, 0}), pageOf(r, {0, 0, 3, 2})};
  r.want(wanted, 5);
  plan = r.plan();
  ASSERT_EQ(plan.uploads.size(), 3u);
  EXPECT_EQ(r.layout().keyOf(plan.uploads[0].page).level, 1);
  EXPECT_EQ(r.layout().keyOf(plan.uploads[1].page).level, 1);
  EXPECT_EQ(r.layout().keyOf(plan.uploads[2].page).level, 0);
  EXPECT_EQ(plan.pending, 1);
  EXPECT_TRUE(r.anyPending());
  // The page still missing reads its resident parent at level 1.
  const std::vector<std::uint32_t> table = r.pageTable();
  const int missing = wanted[0] == plan.uploads[2].page ? wanted[1] : wanted[0];
  EXPECT_EQ(imageryEntryLevel(table[std::size_t(missing)]), 1);
  EXPECT_EQ(imageryEntrySlot(table[std::size_t(missing)]), r.slotOf(r.layout().parentOf(missing)));
  plan = r.plan();
  ASSERT_EQ(plan.uploads.size(), 1u);
  EXPECT_FALSE(r.anyPending());
  EXPECT_EQ(imageryEntryLevel(r.pageTable()[std::size_t(missing)]), 0);
}

TEST(ImageryPages, EvictsTheLeastRecentlyWantedAndNeverWhatIsWantedNow) {
  // 5 slots: 2 roots + 3 pages.
  Result<ImageryResidency> made = ImageryResidency::create(twoLayers(), 5, 10);
  ASSERT_TRUE(made);
  ImageryResidency& r = made.value();
  r.plan();
  const int first[] = {pageOf(r, {0, 0, 0, 0})};  // with its parent: 2 pages
  r.want(first, 1);
  EXPECT_EQ(r.plan().uploads.size(), 2u);
  const int second[] = {pageOf(r, {0, 0, 3, 2})};  // and its parent: 2 more, 1 free slot
  r.want(second, 2);
  const ImageryPlan plan = r.plan();
  EXPECT_EQ(plan.uploads.size(), 2u);
  EXPECT_EQ(plan.evictions, 1);
  EXPECT_EQ(plan.unplaceable, 0);
  // The evicted one was frame 1's finest page; frame 2's pages and the roots stay.
  EXPECT_EQ(r.slotOf(first[0]), -1);
  EXPECT_GE(r.slotOf(second[0]), 0);
  EXPECT_GE(r.slotOf(r.layout().rootOf(0)), 0);
  EXPECT_GE(r.slotOf(r.layout().rootOf(1)), 0);
  // A frame that wants more than the slots hold: what fits, the rest reported, roots kept.
  const int many[] = {pageOf(r, {0, 0, 0, 0}), pageOf(r, {0, 0, 1, 0}), pageOf(r, {0, 0, 2, 0}),
                      pageOf(r, {0, 0, 3, 0})};
  r.want(many, 3);
  const ImageryPlan full = r.plan();
  EXPECT_GT(full.unplaceable, 0);
  EXPECT_EQ(r.residentCount(), 5);
  EXPECT_GE(r.slotOf(r.layout().rootOf(0)), 0);
  EXPECT_GE(r.slotOf(r.layout().rootOf(1)), 0);
}

TEST(ImageryPages, RefusesBudgetsBelowOneSlotALayer) {
  EXPECT_FALSE(ImageryResidency::create(twoLayers(), 1, 4));
  EXPECT_FALSE(ImageryResidency::create(twoLayers(), 4, 0));
  EXPECT_FALSE(ImageryResidency::create(ImageryPageLayout(), 4, 4));
}

TEST(ImageryPlacement, FlatWorldPointsLandOnTheirTexels) {
  // A store of 101 x 81 samples, 0.01 degrees apart (pixel-is-area), from (120 E, 40 N); 800 m
  // and 1000 m apart on the ground. Imagery over it at 0.0025 degrees a texel from (120.5 E, 39.8 N).
  const std::array<double, 6> store{120.0, 0.01, 0.0, 40.0, 0.0, -0.01};
  const std::array<double, 6> layer{120.5, 0.0025, 0.0, 39.8, 0.0, -0.0025};
  const ImageryPlacement p = placeOnFlatStore(layer, store, 81, 800.0, 1000.0);
  // Sample (col, row) lies at world (col * 800, (80 - row) * 1000) and at the CRS point
  // (120.005 + 0.01 col, 39.995 - 0.01 row).
  for (const auto& [col, row] : {std::pair{0, 0}, std::pair{50, 20}, std::pair{100, 80}}) {
    const glm::dvec2 texel = p.texelAt({col * 800.0, (80 - row) * 1000.0});
    EXPECT_NEAR(texel.x, (120.005 + 0.01 * col - 120.5) / 0.0025, 1e-9);
    EXPECT_NEAR(texel.y, (39.8 - (39.995 - 0.01 * row)) / 0.0025, 1e-9);
  }
}

TEST(ImageryPlacement, ResolvesToTheNearestResidentAncestor) {
  Result<ImageryResidency> made = ImageryResidency::create(twoLayers(), 8, 8);
  ASSERT_TRUE(made);
  ImageryResidency& r = made.value();
  r.plan();
  const std::vector<std::uint32_t> table = r.pageTable();
  // Level-0 texel (300, 200) with 64-texel tiles: tile (4, 3) of level 0 does not exist (4 x 3).
  EXPECT_FALSE(imageryResolve(r.layout(), table, 64, 0, {300.0, 200.0}, 0).found);
  // (100, 70): level-0 tile (1, 1), only the root (level 2) resident: read at texel (25, 17.5).
  const ImageryResolved at = imageryResolve(r.layout(), table, 64, 0, {100.0, 70.0}, 0);
  ASSERT_TRUE(at.found);
  EXPECT_EQ(at.level, 2);
  EXPECT_EQ(at.slot, r.slotOf(r.layout().rootOf(0)));
  EXPECT_DOUBLE_EQ(at.local.x, 25.0);
  EXPECT_DOUBLE_EQ(at.local.y, 17.5);
  EXPECT_FALSE(imageryResolve(r.layout(), table, 64, 0, {-1.0, 5.0}, 0).found);
}

}  // namespace
}  // namespace tellus
