// ROAM's GL-free parts (seed 004 section 2.1): the bucket queues, the nested error bounds, and
// the bintree under random split/merge sequences and under view-driven updates: always a
// conforming triangulation (every shared edge matches: no crack), neighbour links and queues
// consistent, and the view-driven update meets its error target and budgets.
#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tellus/core/camera.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/lod/roam/roam_bucket_queue.hpp"
#include "tellus/lod/roam/roam_error_bounds.hpp"
#include "tellus/lod/roam/roam_mesh.hpp"
#include "tellus/lod/roam/roam_mesh_check.hpp"

namespace tellus::roam {
namespace {

HeightGrid terrain(int size, std::uint64_t seed = 3) {
  TerrainParams params;
  params.size = size;
  params.seed = seed;
  params.spacingM = 30.0;
  params.erosion = 0.0;
  return generateTerrain(params);
}

ViewSetup viewOver(const HeightGrid& grid, glm::dvec3 position, double yawDeg, double pitchDeg) {
  Camera camera;
  camera.position = position;
  camera.yawDeg = yawDeg;
  camera.pitchDeg = pitchDeg;
  camera.fovYDeg = 50.0;
  Aabb bounds;
  const HeightRange range = grid.heightRange();
  bounds.min = {0.0, 0.0, range.minM};
  bounds.max = {(grid.width - 1) * grid.spacingXM, (grid.height - 1) * grid.spacingYM, range.maxM};
  return ViewSetup::create(camera, bounds, 640, 360);
}

TEST(RoamBucketQueue, TopAndBottomFollowThePriorities) {
  BucketQueue q;
  std::mt19937 random(5);
  std::uniform_real_distribution<float> priority(0.0f, 100.0f);
  std::vector<float> values(500);
  for (int i = 0; i < 500; ++i) {
    values[std::size_t(i)] = priority(random);
    q.set(i, values[std::size_t(i)]);
  }
  for (int i = 0; i < 500; i += 3) {  // re-prioritise some, remove others
    values[std::size_t(i)] = priority(random);
    q.set(i, values[std::size_t(i)]);
  }
  for (int i = 1; i < 500; i += 7) {
    q.remove(i);
    values[std::size_t(i)] = -1.0f;
  }
  const float maxValue = *std::max_element(values.begin(), values.end());
  float minValue = 1e9f;
  for (float v : values) {
    if (v >= 0.0f) minValue = std::min(minValue, v);
  }
  EXPECT_EQ(BucketQueue::bucketOf(q.priority(q.top())), BucketQueue::bucketOf(maxValue));
  EXPECT_EQ(BucketQueue::bucketOf(q.priority(q.bottom())), BucketQueue::bucketOf(minValue));
  EXPECT_EQ(q.size(), std::size_t(std::count_if(values.begin(), values.end(), [](float v) { return v >= 0.0f; })));
  // Buckets are monotonic in the priority.
  for (float p = 0.001f; p < 1e4f; p *= 1.37f) {
    EXPECT_LE(BucketQueue::bucketOf(p), BucketQueue::bucketOf(p * 1.37f));
  }
}

TEST(RoamErrorBounds, NestAndBoundTheMidpointErrors) {
  const HeightGrid grid = terrain(129);
  const BintreeDomain domain = BintreeDomain::forGrid(grid.width, grid.height, 5);
  ASSERT_EQ(domain.blocksX, 4);
  for (int block = 0; block < domain.blockCount(); ++block) {
    const BlockBounds b = computeBlockBounds(grid, domain, block % 4, block / 4);
    for (int root = 0; root < 2; ++root) {
      const std::uint16_t* stored = b.bounds.data() + std::size_t(root) * domain.storedPerRoot();
      EXPECT_GE(b.rootBoundM[std::size_t(root)] + kBoundStepM, decodeBound(stored[1]) - kBoundStepM);
      // Walk the stored nodes with their triangles: parent >= child + own midpoint error.
      std::vector<std::pair<std::uint32_t, BintreeTriangle>> stack{{1u, rootTriangle(domain, block % 4, block / 4, root)}};
      while (!stack.empty()) {
        const auto [heap, tri] = stack.back();
        stack.pop_back();
        const float bound = decodeBound(stored[heap]);
        EXPECT_GE(bound, midpointError(grid, tri) - 1e-4f);
        const std::uint32_t left = 2 * heap;
        if (left + 1 < domain.storedPerRoot()) {
          EXPECT_GE(bound, decodeBound(stored[left]));
          EXPECT_GE(bound, decodeBound(stored[left + 1]));
          stack.push_back({left, leftChild(tri)});
          stack.push_back({left + 1, rightChild(tri)});
        } else {  // children one level above the leaves: bounds computed from their samples
          EXPECT_GE(bound + 1e-4f, midpointError(grid, leftChild(tri)));
          EXPECT_GE(bound + 1e-4f, midpointError(grid, rightChild(tri)));
        }
      }
    }
  }
}

TEST(RoamMesh, RandomSplitsAndMergesKeepAConformingBintree) {
  const HeightGrid grid = terrain(97);  // not 2^n + 1: blocks reach past the east and north edges
  RoamSettings settings;
  settings.blockLog2 = 4;
  Result<std::unique_ptr<RoamMesh>> created = RoamMesh::create(grid, settings);
  ASSERT_TRUE(created) << created.error().message;
  RoamMesh& mesh = *created.value();
  ASSERT_TRUE(checkConforming(mesh.leaves(), mesh.domain()));
  std::mt19937 random(11);
  int splits = 0, merges = 0;
  for (int step = 0; step < 4000; ++step) {
    const bool doSplit = (step / 500) % 2 == 0 ? random() % 4 != 0 : random() % 4 == 0;
    if (doSplit) {
      const std::vector<std::int32_t> leaves = mesh.leafIds();
      splits += mesh.splitLeaf(leaves[random() % leaves.size()]) ? 1 : 0;
    } else {
      const std::vector<std::int32_t> diamonds = mesh.mergeableDiamondIds();
      if (!diamonds.empty()) merges += mesh.mergeDiamond(diamonds[random() % diamonds.size()]) ? 1 : 0;
    }
    if (step % 97 == 0 || step == 3999) {
      Status structure = mesh.checkStructure();
      ASSERT_TRUE(structure) << "step " << step << ": " << structure.error().message;
      Status conforming = checkConforming(mesh.leaves(), mesh.domain());
      ASSERT_TRUE(conforming) << "step " << step << ": " << conforming.error().message;
    }
  }
  EXPECT_GT(splits, 1000);
  EXPECT_GT(merges, 300);
  // Every split node's bound is at least its children's (nesting, as the mesh uses them).
  for (const std::int32_t leaf : mesh.leafIds()) {
    for (std::int32_t child = leaf, parent = mesh.parentOf(leaf); parent >= 0;
         child = parent, parent = mesh.parentOf(parent)) {
      EXPECT_GE(mesh.nodeBoundM(parent), mesh.nodeBoundM(child));
    }
  }
}

TEST(RoamMesh, ConformingCatchesATJunction) {
  const BintreeDomain domain = BintreeDomain::forGrid(5, 5, 2);
  std::vector<BintreeTriangle> leaves = {leftChild(rootTriangle(domain, 0, 0, 0)),
                                         rightChild(rootTriangle(domain, 0, 0, 0)),
                                         rootTriangle(domain, 0, 0, 1)};
  EXPECT_FALSE(checkConforming(leaves, domain));  // root 1 unsplit against a split root 0
  leaves.pop_back();
  leaves.push_back(leftChild(rootTriangle(domain, 0, 0, 1)));
  leaves.push_back(rightChild(rootTriangle(domain, 0, 0, 1)));
  EXPECT_TRUE(checkConforming(leaves, domain));
}

TEST(RoamMesh, ViewDrivenUpdatesMeetTheTargetAndStayConforming) {
  const HeightGrid grid = terrain(257);
  RoamSettings settings;
  settings.blockLog2 = 5;
  settings.targetPx = 2.0f;
  Result<std::unique_ptr<RoamMesh>> created = RoamMesh::create(grid, settings);
  ASSERT_TRUE(created);
  RoamMesh& mesh = *created.value();
  const double side = 256 * 30.0;
  std::uint32_t previousLeaves = 0;
  for (int frame = 0; frame < 30; ++frame) {
    const double t = frame / 29.0;
    const ViewSetup view = viewOver(grid, {side * (0.1 + 0.8 * t), side * 0.2, 2500.0}, 60.0 * t * t, -25.0);
    const RoamFrameReport report = mesh.update(RoamView::fromSetup(view, 1.0f));
    ASSERT_FALSE(report.budgetReached);
    EXPECT_LE(report.maxSplitPriorityPx, settings.targetPx * 1.03f) << "frame " << frame;
    ASSERT_TRUE(mesh.checkStructure());
    ASSERT_TRUE(checkConforming(mesh.leaves(), mesh.domain())) << "frame " << frame;
    // Deferred re-prioritisation never leaves a decision wrong: computed afresh, every leaf is
    // at most the target and every mergeable diamond above it.
    for (const std::int32_t leaf : mesh.leafIds()) {
      ASSERT_LE(mesh.currentPriority(leaf), settings.targetPx * 1.0001f) << "frame " << frame;
    }
    for (const std::int32_t diamond : mesh.mergeableDiamondIds()) {
      const std::int32_t base = mesh.baseOf(diamond);
      const float p = std::max(mesh.currentPriority(diamond), base >= 0 ? mesh.currentPriority(base) : 0.0f);
      ASSERT_GE(p, settings.targetPx * 0.9999f) << "frame " << frame;
    }
    if (frame > 0) {
      // Frame coherence: a small camera step changes a fraction of the mesh.
      EXPECT_LT(report.splits + report.merges, std::max<std::uint32_t>(previousLeaves, 200)) << "frame " << frame;
    }
    previousLeaves = report.leaves;
  }
  // A tighter target needs more triangles; a budget caps them.
  const ViewSetup view = viewOver(grid, {side * 0.5, side * 0.2, 2500.0}, 0.0, -25.0);
  mesh.settings().targetPx = 0.5f;
  const std::uint32_t fine = mesh.update(RoamView::fromSetup(view, 1.0f)).leaves;
  EXPECT_GT(fine, previousLeaves);
  mesh.settings().triangleBudget = fine / 3;
  const RoamFrameReport capped = mesh.update(RoamView::fromSetup(view, 1.0f));
  EXPECT_LE(capped.leaves, fine / 3);
  EXPECT_TRUE(capped.budgetReached);
  EXPECT_TRUE(checkConforming(mesh.leaves(), mesh.domain()));
  // Emitted triangles stay on the grid and are counter-clockwise.
  std::vector<glm::vec4> vertices;
  const std::size_t triangles = mesh.emit(vertices);
  ASSERT_EQ(vertices.size(), triangles * 3);
  for (std::size_t i = 0; i < vertices.size(); i += 3) {
    const glm::vec4 a = vertices[i], b = vertices[i + 1], c = vertices[i + 2];
    EXPECT_TRUE(a.w == b.w && b.w == c.w && a.w >= 0.0f && a.w <= 5.0f);
    EXPECT_GT((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x), 0.0f);
    EXPECT_LE(std::max({a.x, b.x, c.x}), 256.0f);
  }
}

TEST(RoamMesh, BoundsBeyondTheBudgetAreDroppedAndRemade) {
  const HeightGrid grid = terrain(257);
  RoamSettings settings;
  settings.blockLog2 = 4;  // 16 x 16 blocks of 1 KiB of bounds each
  settings.boundsBudgetBytes = 40 * 1024;
  Result<std::unique_ptr<RoamMesh>> created = RoamMesh::create(grid, settings);
  ASSERT_TRUE(created);
  RoamMesh& mesh = *created.value();
  EXPECT_LE(mesh.boundsBytes(), settings.boundsBudgetBytes);
  const double side = 256 * 30.0;
  for (int frame = 0; frame < 10; ++frame) {
    const ViewSetup view = viewOver(grid, {side * (0.1 + 0.08 * frame), side * 0.5, 1500.0}, 90.0, -30.0);
    mesh.update(RoamView::fromSetup(view, 1.0f));
    ASSERT_TRUE(checkConforming(mesh.leaves(), mesh.domain()));
  }
  EXPECT_LT(mesh.residentBoundBlocks(), std::size_t(256));
}

}  // namespace
}  // namespace tellus::roam
