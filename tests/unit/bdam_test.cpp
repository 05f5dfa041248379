// BDAM's GL-free parts (seed 004 section 2.2): the triangle bintree, the patches simplified with
// locked borders (every shared edge has one vertex set, whatever the two patches' levels), the
// patch file round trip and its corruption errors, and the run-time selection (nested diamond
// errors and boxes, a conforming cut that meets the error target).
#include <algorithm>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "support/store_surgery.hpp"
#include "support/test_support.hpp"
#include "tellus/formats/bdam/bdam_file.hpp"
#include "tellus/formats/bdam/bdam_patches.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/lod/bdam/bdam_selection.hpp"

namespace tellus::bdam {
namespace {

HeightGrid terrain(int width, int height, std::uint64_t seed = 5) {
  TerrainParams params;
  params.size = std::max(width, height);
  params.seed = seed;
  params.spacingM = 30.0;
  params.erosion = 0.0;
  HeightGrid square = generateTerrain(params);
  HeightGrid grid(width, height);
  grid.spacingXM = grid.spacingYM = 30.0;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) grid.at(c, r) = square.at(c, r);
  }
  return grid;
}

// The patch's vertices on segment [a, b], sorted.
std::vector<std::pair<int, int>> onEdge(const Patch& p, glm::ivec2 a, glm::ivec2 b) {
  std::vector<std::pair<int, int>> out;
  for (const glm::ivec2& q : p.positions) {
    if (onSegment(q, a, b)) out.emplace_back(q.x, q.y);
  }
  std::sort(out.begin(), out.end());
  return out;
}

class BdamPatches : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    grid_ = new HeightGrid(terrain(301, 257));  // not a power of two: patches cut by the grid's edges
    BuildSettings settings;
    settings.leafLog2 = 9;
    settings.patchTriangles = 128;
    Result<Hierarchy> built = buildHierarchy(*grid_, settings);
    ASSERT_TRUE(built) << built.error().message;
    hierarchy_ = new Hierarchy(std::move(built.value()));
  }
  static void TearDownTestSuite() {
    delete grid_;
    delete hierarchy_;
  }
  static const Patch* find(NodeId node) {
    const auto it = std::lower_bound(hierarchy_->patches.begin(), hierarchy_->patches.end(), node,
                                     [](const Patch& p, NodeId n) { return p.node < n; });
    return it != hierarchy_->patches.end() && it->node == node ? &*it : nullptr;
  }
  static HeightGrid* grid_;
  static Hierarchy* hierarchy_;
};
HeightGrid* BdamPatches::grid_ = nullptr;
Hierarchy* BdamPatches::hierarchy_ = nullptr;

TEST(BdamBintree, ChildrenSplitTheHypotenuseAndTileTheParent) {
  for (NodeId node = 2; node < 64; ++node) {
    const Triangle t = nodeTriangle(node, 4);
    const Triangle a = nodeTriangle(2 * node, 4), b = nodeTriangle(2 * node + 1, 4);
    EXPECT_EQ(a.apex, t.hypotenuseMidpoint());
    EXPECT_EQ(b.apex, t.hypotenuseMidpoint());
    EXPECT_EQ(std::llabs(orient(a.apex, a.left, a.right)) + std::llabs(orient(b.apex, b.left, b.right)),
              std::llabs(orient(t.apex, t.left, t.right)));
    EXPECT_EQ(nodeLevel(2 * node), nodeLevel(node) + 1);
  }
}

TEST_F(BdamPatches, EveryLevelIsSimplifiedTowardsItsTarget) {
  ASSERT_GT(hierarchy_->leafLevel, 4);
  std::map<int, std::pair<std::size_t, std::size_t>> perLevel;  // level -> (patches, triangles)
  for (const Patch& p : hierarchy_->patches) {
    auto& [patches, triangles] = perLevel[nodeLevel(p.node)];
    ++patches;
    triangles += p.indices.size() / 3;
  }
  // A leaf covers 512 half-cells: simplified to 128 triangles (a few more where borders are locked).
  const auto& [leaves, leafTriangles] = perLevel[hierarchy_->leafLevel];
  EXPECT_LT(double(leafTriangles) / double(leaves), 200.0);
  // The root patches hold a whole-terrain approximation in about 2 x 128 triangles.
  EXPECT_LT(perLevel[0].second, 600u);
}

TEST_F(BdamPatches, SharedEdgesHaveOneVertexSetAcrossLevels) {
  std::size_t compared = 0;
  for (const Patch& p : hierarchy_->patches) {
    const Triangle t = nodeTriangle(p.node, hierarchy_->domainLog2);
    // The mate across the hypotenuse (same level) puts the same vertices on it.
    const glm::ivec2 m = t.hypotenuseMidpoint();
    for (const Patch& q : hierarchy_->patches) {
      if (&q == &p || nodeLevel(q.node) != nodeLevel(p.node)) continue;
      const Triangle u = nodeTriangle(q.node, hierarchy_->domainLog2);
      if (u.hypotenuseMidpoint() != m) continue;
      EXPECT_EQ(onEdge(p, t.left, t.right), onEdge(q, u.left, u.right)) << "mates " << p.node << " " << q.node;
      ++compared;
    }
    // Each leg is a child's hypotenuse: the finer patch puts the same vertices on it.
    for (int which = 0; which < 2; ++which) {
      const Patch* child = find(2 * p.node + NodeId(which));
      if (!child) continue;
      const Triangle c = nodeTriangle(child->node, hierarchy_->domainLog2);
      EXPECT_EQ(onEdge(p, c.left, c.right), onEdge(*child, c.left, c.right)) << "leg of " << p.node;
      ++compared;
    }
  }
  EXPECT_GT(compared, hierarchy_->patches.size());
}

TEST_F(BdamPatches, TheFileRoundTripsEveryPatch) {
  const std::filesystem::path path = test::freshTestDir() / "round.bdam";
  Result<std::uint64_t> bytes = writePatchFile(*hierarchy_, path);
  ASSERT_TRUE(bytes) << bytes.error().message;
  Result<PatchFile> file = PatchFile::open(path);
  ASSERT_TRUE(file) << file.error().message;
  ASSERT_EQ(file->entries().size(), hierarchy_->patches.size());
  std::vector<PackedVertex> vertices;
  std::vector<std::uint16_t> indices;
  for (std::size_t i = 0; i < hierarchy_->patches.size(); ++i) {
    const Patch& p = hierarchy_->patches[i];
    ASSERT_TRUE(file->read(i, vertices, indices));
    ASSERT_EQ(vertices.size(), p.positions.size());
    EXPECT_EQ(indices, p.indices);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      EXPECT_EQ(int(file->entries()[i].origin.x + vertices[v].x), p.positions[v].x);
      EXPECT_EQ(vertices[v].heightM, p.heights[v]);
    }
  }
}

TEST_F(BdamPatches, ForgedFilesWithEveryChecksumRecomputedAreRefused) {
  const std::filesystem::path dir = test::freshTestDir();
  ASSERT_TRUE(writePatchFile(*hierarchy_, dir / "good.bdam"));
  const test::BdamParts good = test::readBdamParts(dir / "good.bdam");
  const auto put = [](std::vector<std::byte>& bytes, std::size_t at, auto value) {
    std::memcpy(bytes.data() + at, &value, sizeof(value));
  };
  struct Case {
    std::string name;
    std::function<void(test::BdamParts&)> forge;
    std::string message;
    bool atOpen;  // refused by open(), else by read() of the first patch
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Case> cases = {
      {"no patch", [&](test::BdamParts& f) { f.table.clear(); put(f.header, 24, std::uint32_t(0)); }, "holds no patch", true},
      {"negative error", [&](test::BdamParts& f) { put(f.table, 28, -1.0f); }, "impossible values", true},
      {"NaN error", [&](test::BdamParts& f) { put(f.table, 28, nan); }, "impossible values", true},
      {"min above max", [&](test::BdamParts& f) { put(f.table, 32, 5000.0f); put(f.table, 36, -5000.0f); }, "impossible values", true},
      {"origin off the grid", [&](test::BdamParts& f) { put(f.table, 40, std::uint32_t(1u << 30)); }, "impossible values", true},
      {"index out of range", [&](test::BdamParts& f) {
         std::uint32_t vertices = 0;
         std::memcpy(&vertices, f.table.data() + 20, 4);
         put(f.data, vertices * sizeof(PackedVertex), std::uint16_t(60000));
       }, "beyond its", false},
      {"NaN height", [&](test::BdamParts& f) { put(f.data, 4, nan); }, "height nan m", false},
      {"3e38 height", [&](test::BdamParts& f) { put(f.data, 4, 3e38f); }, "outside the patch's", false},
      {"vertex off the grid", [&](test::BdamParts& f) { put(f.data, 0, std::uint16_t(65000)); }, "off the", false},
  };
  for (const Case& c : cases) {
    test::BdamParts forged = good;
    c.forge(forged);
    const std::filesystem::path path = dir / "forged.bdam";
    test::writeBdamParts(forged, path);
    Result<PatchFile> file = PatchFile::open(path);
    std::string message;
    if (c.atOpen) {
      ASSERT_FALSE(file) << c.name;
      message = file.error().message;
    } else {
      ASSERT_TRUE(file) << c.name << ": " << file.error().message;
      std::vector<PackedVertex> vertices;
      std::vector<std::uint16_t> indices;
      Status read = file->read(0, vertices, indices);
      ASSERT_FALSE(read) << c.name;
      message = read.error().message;
    }
    EXPECT_NE(message.find(c.message), std::string::npos) << c.name << ": " << message;
    EXPECT_NE(message.find("forged.bdam"), std::string::npos) << c.name << ": " << message;
  }
  // A header changed without its checksum (the spacing, say) fails it; a format 1 file is
  // named as such.
  test::BdamParts changed = good;
  put(changed.header, 28, 1000.0);
  {
    std::ofstream out(dir / "header.bdam", std::ios::binary);
    for (const auto* part : {&changed.header, &changed.table, &changed.data}) {
      out.write(reinterpret_cast<const char*>(part->data()), std::streamsize(part->size()));
    }
  }
  Result<PatchFile> header = PatchFile::open(dir / "header.bdam");
  ASSERT_FALSE(header);
  EXPECT_NE(header.error().message.find("header fails its checksum"), std::string::npos);
  test::BdamParts old = good;
  old.header[6] = std::byte{'1'};
  test::writeBdamParts(old, dir / "v1.bdam");
  Result<PatchFile> v1 = PatchFile::open(dir / "v1.bdam");
  ASSERT_FALSE(v1);
  EXPECT_NE(v1.error().message.find("older Tellus"), std::string::npos) << v1.error().message;
}

}  // namespace
}  // namespace tellus::bdam
