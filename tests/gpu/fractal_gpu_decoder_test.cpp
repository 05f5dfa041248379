// The fractal decoder on the GPU reproduces the CPU reference exactly: the same working image
// after any number of iterations (from scratch or continued), the same samples with the
// residual layer, for fixed ranges and for a quadtree, with several tiles resident at once.
#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/render/fractal/fractal_gpu_decoder.hpp"
#include "tellus/tiles/fractal_encoder.hpp"

namespace tellus {
namespace {

using Tile = std::vector<std::int32_t>;

class FractalGpuDecoderTest : public test::GlTest {
 protected:
  // A 257 x 257 tile of the Japan Alps (N36E137) at (origin, origin), integer metres.
  static Tile alpsTile(const std::filesystem::path& data, int origin) {
    Result<HeightGrid> grid = loadDem({data / "srtm3-hgt-east-asia/N36E137.hgt"});
    EXPECT_TRUE(grid) << grid.error().message;
    Tile tile(257 * 257);
    for (int j = 0; j < 257; ++j) {
      for (int i = 0; i < 257; ++i) {
        tile[std::size_t(j * 257 + i)] = std::int32_t(grid->at(origin + i, origin + j));
      }
    }
    return tile;
  }

  static std::vector<float> readLayer(const gl::Texture& texture, int layer, TileShape shape) {
    std::vector<float> values(shape.sampleCount());
    glGetTextureSubImage(texture.id(), 0, 0, 0, layer, shape.width, shape.height, 1, GL_RED,
                         GL_FLOAT, GLsizei(values.size() * sizeof(float)), values.data());
    return values;
  }
};

TEST_F(FractalGpuDecoderTest, WorkingImagesEqualTheCpuReferenceAtEveryIteration) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{257, 257};
  FractalOptions tree;
  tree.rangeSize = 2;
  tree.quadtreeLevels = 3;
  tree.splitRmseSteps = 6.0;
  const auto fixed = fractal::encode(alpsTile(data, 700), shape, {}, 0);
  const auto quadtree = fractal::encode(alpsTile(data, 800), shape, tree, 0);
  ASSERT_TRUE(fixed && quadtree);
  for (const fractal::FractalCode* code : {&fixed.value(), &quadtree.value()}) {
    auto decoder = FractalGpuDecoder::create(geometryOf(*code), 3);
    ASSERT_TRUE(decoder) << decoder.error().message;
    ASSERT_TRUE(decoder->load(1, *code));
    int done = 0;
    for (int k : {1, 2, 3, 5, 9}) {  // continues from where it stopped
      decoder->iterate(1, k - done);
      done = k;
      ASSERT_EQ(decoder->iterations(1), k);
      ASSERT_EQ(decoder->readWorking(1), fractal::decodeWorking(*code, k))
          << "iteration " << k << ", smallest range " << (1 << decoder->geometry().minLog2);
    }
  }
}

// Several slots iterated in one batch, at different ping-pong phases and with different counts,
// end where iterating each alone would.
TEST_F(FractalGpuDecoderTest, BatchedIterationsEqualTheCpuReferenceForEverySlot) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{257, 257};
  std::vector<fractal::FractalCode> codes;
  for (int origin : {620, 700, 780, 860}) {
    auto code = fractal::encode(alpsTile(data, origin), shape, {}, 0);
    ASSERT_TRUE(code);
    codes.push_back(std::move(code.value()));
  }
  auto decoder = FractalGpuDecoder::create(geometryOf(codes[0]), 6);
  ASSERT_TRUE(decoder);
  const int slots[4] = {5, 0, 3, 2};
  for (std::size_t i = 0; i < codes.size(); ++i) ASSERT_TRUE(decoder->load(slots[i], codes[i]));
  decoder->iterate(slots[1], 1);  // slot 0 now reads the other working array
  decoder->iterate(slots[3], 2);  // slot 2 is back in the first one, one iteration ahead
  const FractalGpuDecoder::IterationRequest batch[] = {
      {slots[0], 3}, {slots[1], 2}, {slots[2], 1}, {slots[3], 3}};
  decoder->iterate(batch);
  const int expected[4] = {3, 3, 1, 5};
  for (std::size_t i = 0; i < codes.size(); ++i) {
    EXPECT_EQ(decoder->iterations(slots[i]), expected[i]);
    EXPECT_EQ(decoder->readWorking(slots[i]), fractal::decodeWorking(codes[i], expected[i]))
        << "slot " << slots[i];
  }
}

TEST_F(FractalGpuDecoderTest, PublishedHeightsEqualTheCpuCodecWithTheResidualLayer) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const TileShape shape{257, 257};
  FractalOptions options;
  options.residual = true;
  const Tile a = alpsTile(data, 650), b = alpsTile(data, 900);
  const auto codeA = fractal::encode(a, shape, options, 2);
  const auto codeB = fractal::encode(b, shape, options, 2);
  ASSERT_TRUE(codeA && codeB);
  auto decoder = FractalGpuDecoder::create(geometryOf(codeA.value()), 2);
  ASSERT_TRUE(decoder);
  ASSERT_TRUE(decoder->load(0, codeA.value()));
  ASSERT_TRUE(decoder->load(1, codeB.value()));
  decoder->iterate(0, codeA->iterations);
  decoder->iterate(1, 2);  // not yet converged: published without the residual
  gl::Texture heights = gl::Texture::create2DArray(GL_R32F, 257, 257, 4);
  decoder->publish(0, heights, 3, 1.0f, true);
  decoder->publish(1, heights, 0, 1.0f, true);

  const std::vector<float> gpuA = readLayer(heights, 3, shape);
  const std::vector<float> gpuB = readLayer(heights, 0, shape);
  Tile cpuA(shape.sampleCount()), cpuB(shape.sampleCount());
  fractal::workingToSamples(codeA.value(), fractal::decodeWorking(codeA.value(), codeA->iterations),
                            true, cpuA);
  fractal::workingToSamples(codeB.value(), fractal::decodeWorking(codeB.value(), 2), false, cpuB);
  std::int64_t worst = 0;
  for (std::size_t i = 0; i < cpuA.size(); ++i) {
    ASSERT_EQ(gpuA[i], float(cpuA[i])) << "sample " << i;
    ASSERT_EQ(gpuB[i], float(cpuB[i])) << "sample " << i;
    worst = std::max<std::int64_t>(worst, std::abs(cpuA[i] - a[i]));
  }
  EXPECT_LE(worst, 2);  // the residual's bound holds on the GPU too
}

TEST_F(FractalGpuDecoderTest, RefusesACodeOfAnotherLayout) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const auto big = fractal::encode(alpsTile(data, 700), {257, 257}, {}, 0);
  Tile small(65 * 65, 100);
  const auto other = fractal::encode(small, {65, 65}, {}, 0);
  ASSERT_TRUE(big && other);
  auto decoder = FractalGpuDecoder::create(geometryOf(big.value()), 1);
  ASSERT_TRUE(decoder);
  const Status s = decoder->load(0, other.value());
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("does not fit"), std::string::npos);
}

}  // namespace
}  // namespace tellus
