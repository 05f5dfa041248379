// The imagery virtual texture (render/imagery/imagery_textures.hpp, shaders/common/imagery.glsl):
// every pixel's lookup, frame after frame while pages arrive within the upload budget, equals
// the CPU twin's (lod/imagery/imagery_placement.hpp) over the page table of that frame: the page
// it wanted or its nearest resident ancestor, never a hole or a wrong tile; once converged every
// lookup reads the level it wanted; the budgets hold; feedback comes back without waiting.
#include <cmath>
#include <filesystem>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "support/imagery_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/render/imagery/imagery_textures.hpp"
#include "tellus/render/output/offscreen_target.hpp"

namespace tellus {
namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr float kTexelsPerPixel = 2.8f;  // the lookups' level: log2(2.8) = 1.49 (levels 1 and 2)

class ImageryTexturesTest : public test::GlTest {};

// Bilinear filtering of `level` at level texel coordinates `p` (texel centres at +0.5), texels
// beyond the level's tiles transparent: what a slot with its borders gives the GPU.
glm::dvec4 bilinear(const ImageryPyramid& pyramid, int level, glm::dvec2 p) {
  const int t = pyramid.tileSize();
  const auto texel = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= pyramid.tilesX(level) * t || y >= pyramid.tilesY(level) * t) return glm::dvec4(0.0);
    const std::span<const std::byte> tile = pyramid.tile(level, x / t, y / t);
    const std::byte* c = tile.data() + (std::size_t(y % t) * t + std::size_t(x % t)) * 4;
    return glm::dvec4(double(c[0]), double(c[1]), double(c[2]), double(c[3])) / 255.0;
  };
  const glm::dvec2 q = p - 0.5;
  const glm::ivec2 i(glm::floor(q));
  const glm::dvec2 f = q - glm::dvec2(i);
  return glm::mix(glm::mix(texel(i.x, i.y), texel(i.x + 1, i.y), f.x),
                  glm::mix(texel(i.x, i.y + 1), texel(i.x + 1, i.y + 1), f.x), f.y);
}

TEST_F(ImageryTexturesTest, EveryLookupMatchesTheCpuTwinWhilePagesArrive) {
  const std::filesystem::path dir = test::freshTestDir();
  test::TestImage image{.width = 700, .height = 600, .west = 120.0, .north = 40.0, .texelSize = 0.001,
                        .epsg = 4326, .texel = test::testPattern};
  test::writeTestImage(image, dir / "image.tif");
  ASSERT_TRUE(buildImageryPyramid(dir / "image.tif", dir / "image.timagery", {.tileSize = 64}));
  Result<ImageryPyramid> pyramid = ImageryPyramid::open(dir / "image.timagery");
  ASSERT_TRUE(pyramid) << pyramid.error().message;
  ASSERT_EQ(pyramid->levels(), 5);
  std::vector<ImageryLayer> layers(1);
  layers[0].pyramid = std::move(pyramid.value());
  // Frame units are level-0 texels; some pixels fall west and north of the image.
  layers[0].placement.offset = glm::dvec2(-20.0, -10.0);
  layers[0].placement.scale = glm::dvec2(1.0, 1.0);
  const std::uint64_t slotBytes = 66 * 66 * 4;
  Result<std::unique_ptr<ImageryTextures>> made =
      ImageryTextures::create(std::move(layers), ImageryBudget{.memoryBytes = 40 * slotBytes, .uploadsPerFrame = 3});
  ASSERT_TRUE(made) << made.error().message;
  ImageryTextures& imagery = *made.value();
  EXPECT_EQ(imagery.frameInfo().slots, 40);

  Result<gl::Program> probe = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "imagery/lookup_probe.vert"}, {GL_FRAGMENT_SHADER, "imagery/lookup_probe.frag"}});
  ASSERT_TRUE(probe) << probe.error().message;
  Result<OffscreenTarget> target = OffscreenTarget::create(kWidth, kHeight, 1);
  ASSERT_TRUE(target) << target.error().message;
  gl::VertexArray vertexArray = gl::VertexArray::create();
  ViewSetup view;
  view.camera.position = glm::dvec3(0.0);

  const ImageryPyramid& p = imagery.layers()[0].pyramid;
  const double lambda = std::log2(double(kTexelsPerPixel));
  const int fine = int(std::floor(lambda)), coarse = fine + 1;
  int framesWithCoarserPages = 0;
  bool converged = false;
  for (int frame = 0; frame < 40 && !converged; ++frame) {
    const std::uint64_t waitsBefore = gl::gpuWaitCount();
    imagery.beginFrame();
    EXPECT_EQ(gl::gpuWaitCount(), waitsBefore) << "frame " << frame << ": the update waited for the GPU";
    const ImageryPagingInfo info = imagery.frameInfo();
    EXPECT_LE(info.uploads, 3) << "frame " << frame;
    EXPECT_LE(info.residentBytes, info.budgetBytes);
    target->begin(glm::u8vec3(0, 0, 0));
    glDisable(GL_DEPTH_TEST);  // the target's reversed-Z clear would hide the flat triangle
    probe->use();
    imagery.apply(probe.value(), view);
    probe->set("uProbeUnitsPerPixel", kTexelsPerPixel);
    vertexArray.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    const RgbImage drawn = target->readRgb();  // a test: it waits
    imagery.endFrame();

    // The CPU twin over this frame's page table.
    const std::vector<std::uint32_t>& table = imagery.pageTable();
    const ImageryPageLayout& layout = imagery.residency().layout();
    int mismatches = 0, coarser = 0;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        // gl_FragCoord: pixel centres, y up from the bottom row; readRgb's row 0 is the top.
        const glm::dvec2 texel = glm::dvec2(-20.0, -10.0) + glm::dvec2(x + 0.5, y + 0.5) * double(kTexelsPerPixel);
        glm::dvec4 levels[2];
        for (int k = 0; k < 2; ++k) {
          const ImageryResolved r = imageryResolve(layout, table, p.tileSize(), 0, texel, k == 0 ? fine : coarse);
          if (!r.found) {
            levels[k] = glm::dvec4(0.0);
            continue;
          }
          if (k == 0 && r.level != fine) ++coarser;
          levels[k] = bilinear(p, r.level, texel / std::ldexp(1.0, r.level));
        }
        const glm::dvec4 expected = glm::mix(levels[0], levels[1], lambda - fine) * 255.0;
        const std::uint8_t* got = &drawn.pixels[(std::size_t(kHeight - 1 - y) * kWidth + x) * 3];
        for (int c = 0; c < 3; ++c) {
          if (std::abs(double(got[c]) - expected[c]) > 3.0) {
            if (mismatches++ < 5) {
              ADD_FAILURE() << "frame " << frame << " pixel (" << x << ", " << y << ") channel " << c << ": GPU "
                            << int(got[c]) << ", CPU twin " << expected[c];
            }
          }
        }
      }
    }
    EXPECT_EQ(mismatches, 0) << "frame " << frame;
    if (coarser > 0) ++framesWithCoarserPages;
    converged = frame > 0 && coarser == 0 && info.pending == 0;
  }
  EXPECT_TRUE(converged) << "pages still missing after 40 frames";
  // The budget of 3 uploads a frame made the first frames show coarser pages.
  EXPECT_GE(framesWithCoarserPages, 2);
}

TEST_F(ImageryTexturesTest, RefusesTooManyLayersAndTooSmallABudget) {
  const std::filesystem::path dir = test::freshTestDir();
  test::TestImage image{.width = 100, .height = 80, .west = 120.0, .north = 40.0, .texelSize = 0.001,
                        .epsg = 4326, .texel = test::testPattern};
  test::writeTestImage(image, dir / "image.tif");
  ASSERT_TRUE(buildImageryPyramid(dir / "image.tif", dir / "image.timagery", {.tileSize = 64}));
  const auto layersOf = [&](int n) {
    std::vector<ImageryLayer> layers(static_cast<std::size_t>(n));
    for (ImageryLayer& layer : layers) layer.pyramid = ImageryPyramid::open(dir / "image.timagery").value();
    return layers;
  };
  EXPECT_FALSE(ImageryTextures::create(layersOf(5), ImageryBudget{}));
  EXPECT_FALSE(ImageryTextures::create({}, ImageryBudget{}));
  Result<std::unique_ptr<ImageryTextures>> tiny =
      ImageryTextures::create(layersOf(2), ImageryBudget{.memoryBytes = 66 * 66 * 4, .uploadsPerFrame = 1});
  ASSERT_FALSE(tiny);
  EXPECT_NE(tiny.error().message.find("budget"), std::string::npos) << tiny.error().message;
}

}  // namespace
}  // namespace tellus
