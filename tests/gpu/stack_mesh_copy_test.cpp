// The octree renderer's copy of node meshes from a staging into its pool (StackMeshCopy, one
// compute dispatch for all of them) against the same ranges copied on the CPU: vertices (12
// words each), indices and geomorph targets (4 words each) land where asked, nothing else in
// the pool changes, and without targets on either side none are written.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/gl_test.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/render/stacks/stack_mesh_copy.hpp"

namespace tellus {
namespace {

class StackMeshCopyTest : public test::GlTest {};

constexpr std::uint32_t kVertexWords = 12, kTargetWords = 8;

std::vector<std::uint32_t> pattern(std::size_t words, std::uint32_t seed) {
  std::vector<std::uint32_t> out(words);
  for (std::size_t i = 0; i < words; ++i) out[i] = seed * 1000003u + std::uint32_t(i) * 2654435761u;
  return out;
}

std::vector<std::uint32_t> read(const gl::Buffer& buffer) {
  std::vector<std::uint32_t> out(buffer.size() / 4);
  gl::readBuffer(buffer.id(), 0, buffer.size(), out.data());
  return out;
}

TEST_F(StackMeshCopyTest, CopiesEveryRangeLikeTheCpuAndNothingElse) {
  Result<StackMeshCopy> copier = StackMeshCopy::create();
  ASSERT_TRUE(copier) << copier.error().message;
  const std::uint32_t sourceVertices = 500, sourceIndices = 3000;
  const std::uint32_t poolVertices = 800, poolIndices = 5000;
  const std::vector<std::uint32_t> sv = pattern(sourceVertices * kVertexWords, 1),
                                   si = pattern(sourceIndices, 2),
                                   st = pattern(sourceVertices * kTargetWords, 3),
                                   pv = pattern(poolVertices * kVertexWords, 4),
                                   pi = pattern(poolIndices, 5), pt = pattern(poolVertices * kTargetWords, 6);
  const auto buffer = [](const std::vector<std::uint32_t>& words) {
    return gl::Buffer(words.size() * 4, words.data());
  };
  const gl::Buffer fromV = buffer(sv), fromI = buffer(si), fromT = buffer(st);
  for (const bool targets : {true, false}) {
    SCOPED_TRACE(targets ? "with geomorph targets" : "without");
    const gl::Buffer toV = buffer(pv), toI = buffer(pi), toT = buffer(pt);
    // Meshes of a few sizes (one of a single vertex, one larger than a work group's stride,
    // one of no index), out of order in the pool.
    const std::vector<StackMeshCopy::MeshCopy> copies = {
        {0, 700, 1, 0, 4990, 3},      {1, 10, 130, 3, 100, 700},
        {131, 400, 64, 703, 2000, 0}, {195, 200, 300, 703, 3000, 1800},
    };
    copier.value().copy(copies, {&fromV, &fromI, targets ? &fromT : nullptr},
                        {&toV, &toI, targets ? &toT : nullptr});
    std::vector<std::uint32_t> wantV = pv, wantI = pi, wantT = pt;
    for (const StackMeshCopy::MeshCopy& c : copies) {
      for (std::uint32_t w = 0; w < c.vertexCount * kVertexWords; ++w) {
        wantV[c.targetVertex * kVertexWords + w] = sv[c.sourceVertex * kVertexWords + w];
      }
      for (std::uint32_t w = 0; w < c.indexCount; ++w) wantI[c.targetIndex + w] = si[c.sourceIndex + w];
      if (!targets) continue;
      for (std::uint32_t w = 0; w < c.vertexCount * kTargetWords; ++w) {
        wantT[c.targetVertex * kTargetWords + w] = st[c.sourceVertex * kTargetWords + w];
      }
    }
    EXPECT_EQ(read(toV), wantV);
    EXPECT_EQ(read(toI), wantI);
    EXPECT_EQ(read(toT), wantT);
  }
}

}  // namespace
}  // namespace tellus
