// ROAM's GL-free parts (seed 004 section 2.1): the bucket queues, the nested error bounds, and
// the bintree under random split/merge sequences and under view-driven updates: always a
// conforming triangulation (every shared edge matches: no crack), neighbour links and queues
// consistent, and the view-driven update meets its error target and budgets.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
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

// The surface every reference grid draws: each cell split along its SW-NE diagonal.
double drawnSurface(const HeightGrid& grid, double u, double v) {
  const int i = std::clamp(int(std::floor(u)), 0, grid.width - 2);
  const int j = std::clamp(int(std::floor(v)), 0, grid.height - 2);
  const double fu = u - i, fv = v - j;
  const double sw = heightAt(grid, {i, j}), se = heightAt(grid, {i + 1, j});
  const double nw = heightAt(grid, {i, j + 1}), ne = heightAt(grid, {i + 1, j + 1});
  return fu >= fv ? sw + fu * (se - sw) + fv * (ne - se)   // south-east half
                  : sw + fv * (nw - sw) + fu * (ne - nw);  // north-west half
}

// Every node's bound holds the drawn surface (cells along the SW-NE diagonal, not the
// bintree's alternating ones) within that distance of the node's plane: checked at points of
// a lattice over every node of a block down to the last split.
TEST(RoamErrorBounds, BoundTheSurfaceDrawnAtTheFinestLevel) {
  const HeightGrid grid = terrain(33, 11);
  const BintreeDomain domain = BintreeDomain::forGrid(grid.width, grid.height, 5);
  const BlockBounds b = computeBlockBounds(grid, domain, 0, 0);
  int checked = 0, twisted = 0;
  for (int root = 0; root < 2; ++root) {
    const std::uint16_t* stored = b.bounds.data() + std::size_t(root) * domain.storedPerRoot();
    std::vector<std::tuple<std::uint32_t, int, BintreeTriangle>> stack{
        {1u, 0, rootTriangle(domain, 0, 0, root)}};
    while (!stack.empty()) {
      const auto [heap, depth, tri] = stack.back();
      stack.pop_back();
      if (depth == domain.leafDepth()) continue;
      const float bound = depth == 0 ? b.rootBoundM[std::size_t(root)]
                          : depth == domain.leafDepth() - 1 ? lastSplitBound(grid, tri)
                                                            : decodeBound(stored[heap]);
      if (depth == domain.leafDepth() - 1 && bound > midpointError(grid, tri) + 1e-3f) ++twisted;
      const glm::dvec3 a(tri.apex, heightAt(grid, tri.apex)), l(tri.left, heightAt(grid, tri.left)),
          r(tri.right, heightAt(grid, tri.right));
      float worst = 0.0f;
      for (int i = 0; i <= 8; ++i) {
        for (int j = 0; i + j <= 8; ++j) {
          const glm::dvec3 p = a + (l - a) * (i / 8.0) + (r - a) * (j / 8.0);
          worst = std::max(worst, float(std::abs(drawnSurface(grid, p.x, p.y) - p.z)));
        }
      }
      ASSERT_GE(bound + 1e-3f, worst) << "depth " << depth << " heap " << heap;
      ++checked;
      stack.push_back({2 * heap, depth + 1, leftChild(tri)});
      stack.push_back({2 * heap + 1, depth + 1, rightChild(tri)});
    }
  }
  EXPECT_GT(checked, 2000);
  EXPECT_GT(twisted, 100) << "the turned cells' twist is in the last split's bound";
}

// Split to the finest level, ROAM draws exactly the reference's triangles: every cell split
// along its SW-NE diagonal, whichever diagonal the bintree gave it.
TEST(RoamMesh, TheFinestLevelIsDrawnAlongTheReferenceDiagonal) {
  const HeightGrid grid = terrain(33, 5);
  RoamSettings settings;
  settings.blockLog2 = 4;
  std::unique_ptr<RoamMesh> mesh = RoamMesh::create(grid, settings).value();
  for (bool split = true; split;) {
    split = false;
    for (const std::int32_t id : mesh->leafIds()) split = mesh->splitLeaf(id) || split;
  }
  std::vector<glm::vec4> vertices;
  const std::size_t triangles = mesh->emit(vertices);
  ASSERT_EQ(triangles, 2u * 32u * 32u);
  std::set<std::array<int, 6>> drawn, reference;
  const auto key = [](glm::ivec2 a, glm::ivec2 b, glm::ivec2 c) {
    std::array<glm::ivec2, 3> v{a, b, c};
    std::sort(v.begin(), v.end(), [](glm::ivec2 p, glm::ivec2 q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
    return std::array<int, 6>{v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y};
  };
  std::vector<BintreeTriangle> asLeaves;
  for (std::size_t i = 0; i < vertices.size(); i += 3) {
    const glm::ivec2 a(vertices[i]), b(vertices[i + 1]), c(vertices[i + 2]);
    drawn.insert(key(a, b, c));
    for (int k = 0; k < 3; ++k) {
      const glm::vec4 v = vertices[i + std::size_t(k)];
      ASSERT_EQ(v.z, heightAt(grid, glm::ivec2(v)));
    }
    asLeaves.push_back({a, b, c});
  }
  for (int j = 0; j < 32; ++j) {
    for (int i = 0; i < 32; ++i) {
      reference.insert(key({i, j}, {i + 1, j}, {i + 1, j + 1}));
      reference.insert(key({i, j}, {i + 1, j + 1}, {i, j + 1}));
    }
  }
  EXPECT_EQ(drawn, reference);
  EXPECT_TRUE(checkConforming(asLeaves, mesh->domain()));
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

// A view-driven update at a tight target: every visible half cell at the finest level is
// wholly drawn (either side of its median), turned or not, and the two halves of a turned cell
// are culled together (they share their box).
TEST(RoamMesh, TurnedCellsLeaveNoHole) {
  const HeightGrid grid = terrain(257);
  RoamSettings settings;
  settings.blockLog2 = 5;
  settings.targetPx = 0.1f;
  std::unique_ptr<RoamMesh> mesh = RoamMesh::create(grid, settings).value();
  const HeightRange range = grid.heightRange();
  const ViewSetup view =
      viewOver(grid, {128 * 30.0, 40 * 30.0, double(range.maxM) + 10.0}, 20.0, -60.0);
  mesh->update(RoamView::fromSetup(view, 1.0f));
  std::vector<glm::vec4> vertices;
  mesh->emit(vertices);
  std::map<std::pair<int, int>, std::vector<std::array<glm::vec2, 3>>> finestByCell;
  for (std::size_t i = 0; i < vertices.size(); i += 3) {
    if (vertices[i].w != 0.0f) continue;
    const glm::vec2 a(vertices[i]), b(vertices[i + 1]), c(vertices[i + 2]);
    const glm::vec2 centre = (a + b + c) / 3.0f;
    finestByCell[{int(std::floor(centre.x)), int(std::floor(centre.y))}].push_back({a, b, c});
  }
  const auto inside = [](glm::vec2 p, const std::array<glm::vec2, 3>& t) {
    const auto side = [](glm::vec2 a, glm::vec2 b, glm::vec2 q) {
      return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
    };
    return side(t[0], t[1], p) > 0.0f && side(t[1], t[2], p) > 0.0f && side(t[2], t[0], p) > 0.0f;
  };
  int turned = 0, halves = 0;
  const std::vector<std::int32_t> ids = mesh->leafIds();
  const std::vector<BintreeTriangle> leaves = mesh->leaves();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const BintreeTriangle& t = leaves[k];
    const glm::ivec2 d = t.right - t.left;
    if (std::abs(d.x) != 1 || std::abs(d.y) != 1 || !mesh->isVisible(ids[k])) continue;
    const std::int32_t other = mesh->baseOf(ids[k]);
    if (other >= 0 && mesh->baseOf(other) == ids[k] && d.x * d.y < 0) {  // a turned cell
      EXPECT_TRUE(mesh->isVisible(other));
      ++turned;
    }
    // Both halves of this leaf's area (either side of its apex-to-hypotenuse median) are drawn.
    const glm::vec2 a(t.apex), l(t.left), r(t.right), m = (l + r) * 0.5f;
    const glm::ivec2 cell = glm::min(t.apex, glm::min(t.left, t.right));
    const auto& candidates = finestByCell[{cell.x, cell.y}];
    for (const glm::vec2 p : {(a + l + m) / 3.0f, (a + m + r) / 3.0f}) {
      ++halves;
      EXPECT_TRUE(std::any_of(candidates.begin(), candidates.end(),
                              [&](const std::array<glm::vec2, 3>& tri) { return inside(p, tri); }))
          << "a hole in cell " << cell.x << "," << cell.y;
    }
  }
  EXPECT_GT(halves, 1000);
  EXPECT_GT(turned, 500);
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
