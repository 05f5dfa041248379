// Imagery on stack terrain (render/stacks/stack_sky_texture.hpp, shaders/stacks/sky_heights.glsl):
// both stack renderers drape an orthophoto by the terrain's georeference on the tops that meet
// the sky, and leave a tunnel's floor, walls and ceiling in their materials' colours.
#include <gtest/gtest.h>

#include <memory>

#include "support/gl_test.hpp"
#include "support/imagery_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_surface.hpp"
#include "tellus/render/imagery/imagery_textures.hpp"
#include "tellus/render/output/snapshot.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/render/stacks/stacks_lod_renderer.hpp"

namespace tellus {
namespace {

constexpr int kSide = 48;           // stacks each way
constexpr double kSpacingM = 4.0;   // between stacks
constexpr double kWestM = 1000.0, kNorthM = 2000.0;  // EPSG:3857 of the north-west stack

// Solid rock up to 40 m, grass on top; rows 20 to 27 (counted from the north) hold a tunnel from
// 10 to 30 m high along x, open at both ends.
StackTerrain tunnelTerrain() {
  std::vector<std::vector<StackLayer>> columns(std::size_t(kSide) * kSide);
  for (int row = 0; row < kSide; ++row) {
    for (int x = 0; x < kSide; ++x) {
      auto& column = columns[std::size_t(row) * kSide + std::size_t(x)];
      if (row >= 20 && row <= 27) {
        column = {{0.0f, 10.0f, 1}, {30.0f, 38.0f, 1}, {38.0f, 40.0f, 3}};
      } else {
        column = {{0.0f, 38.0f, 1}, {38.0f, 40.0f, 3}};
      }
    }
  }
  Result<StackTerrain> terrain = StackTerrain::fromColumns(kSide, kSide, kSpacingM, columns);
  EXPECT_TRUE(terrain) << terrain.error().message;
  return terrain.value();
}

enum class Shade { Magenta, Cyan, Other };
Shade shadeOf(const RgbImage& image, int x, int y) {
  const std::uint8_t* p = &image.pixels[(std::size_t(y) * image.width + std::size_t(x)) * 3];
  const int r = p[0], g = p[1], b = p[2];
  if (2 * g < r && 2 * g < b) return Shade::Magenta;
  if (2 * r < g && 2 * r < b) return Shade::Cyan;
  return Shade::Other;
}

class StackImageryTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    dir_ = test::freshTestDir();
    pyramid_ = buildStackPyramid(tunnelTerrain());
    surface_ = topSurfaceGrid(pyramid_.front());
    Result<GeoReference> georef = projectedGeoReference(3857, kWestM, kNorthM, kSpacingM);
    ASSERT_TRUE(georef) << georef.error().message;
    surface_.georef = georef.value();
    // Magenta west of the terrain's middle (CRS x 1096 m: world x 96 m), cyan east of it.
    test::TestImage image{.width = 200, .height = 200, .west = 900.0, .north = 2100.0, .texelSize = 2.0,
                          .epsg = 3857, .texel = [](int x, int) {
                            return x < 98 ? std::array<std::uint8_t, 4>{255, 0, 255, 255}
                                          : std::array<std::uint8_t, 4>{0, 255, 255, 255};
                          }};
    test::writeTestImage(image, dir_ / "ortho.tif");
  }

  std::unique_ptr<ImageryTextures> imagery() {
    Result<std::vector<ImageryLayer>> layers =
        imageryLayersOnGrid({dir_ / "ortho.tif"}, surface_.georef, surface_.width, surface_.height, kSpacingM,
                            kSpacingM, dir_ / "cache");
    EXPECT_TRUE(layers) << layers.error().message;
    Result<std::unique_ptr<ImageryTextures>> made = ImageryTextures::create(std::move(layers.value()), {});
    EXPECT_TRUE(made) << made.error().message;
    return std::move(made.value());
  }

  // Straight down over the whole terrain, north up: screen x is world x.
  RgbImage fromAbove(TerrainRenderer& renderer, ImageryTextures* drape) {
    Camera camera;
    camera.position = glm::dvec3(94.0, 94.0, 330.0);
    camera.pitchDeg = -90.0;
    camera.fovYDeg = 30.0;
    return still(renderer, camera, drape);
  }
  // From beyond the west edge, into the tunnel's mouth.
  RgbImage intoTheTunnel(TerrainRenderer& renderer, ImageryTextures* drape) {
    Camera camera;
    camera.position = glm::dvec3(-12.0, (kSide - 1 - 23.5) * kSpacingM, 22.0);
    camera.yawDeg = 90.0;
    camera.pitchDeg = -12.0;
    camera.fovYDeg = 40.0;
    return still(renderer, camera, drape);
  }
  RgbImage still(TerrainRenderer& renderer, const Camera& camera, ImageryTextures* drape) {
    SnapshotOptions options;
    options.width = 160;
    options.height = 120;
    options.samples = 1;
    options.settings.imagery = drape;
    Result<RgbImage> image = renderSnapshot(renderer, drawnBounds(surface_, 1.0f), camera, options);
    EXPECT_TRUE(image) << image.error().message;
    return image ? image.value() : RgbImage{};
  }

  void expectDrapedOnTheTopsOnly(TerrainRenderer& renderer) {
    std::unique_ptr<ImageryTextures> drape = imagery();
    ASSERT_TRUE(drape);
    // From above: the tops, magenta on the west half, cyan on the east half.
    const RgbImage above = fromAbove(renderer, drape.get());
    int westMagenta = 0, eastCyan = 0, pixels = 0;
    for (int y = 20; y < 100; ++y) {
      for (int x = 30; x < 130; ++x) {
        if (x >= 75 && x < 85) continue;  // the border, blended
        ++pixels;
        const Shade shade = shadeOf(above, x, y);
        if (x < 75 && shade == Shade::Magenta) ++westMagenta;
        if (x >= 85 && shade == Shade::Cyan) ++eastCyan;
      }
    }
    EXPECT_GT(westMagenta + eastCyan, pixels * 97 / 100)
        << "west magenta " << westMagenta << ", east cyan " << eastCyan << " of " << pixels;
    // Without imagery the same view has neither colour.
    const RgbImage plain = fromAbove(renderer, nullptr);
    int coloured = 0;
    for (int y = 0; y < plain.height; ++y) {
      for (int x = 0; x < plain.width; ++x) coloured += shadeOf(plain, x, y) != Shade::Other;
    }
    EXPECT_EQ(coloured, 0);
    // Into the tunnel: floor, walls, ceiling and the cliff around its mouth are below the tops
    // or do not face the sky: no imagery there.
    const RgbImage tunnel = intoTheTunnel(renderer, drape.get());
    int draped = 0, terrain = 0;
    const RgbImage tunnelPlain = intoTheTunnel(renderer, nullptr);
    for (int y = 0; y < tunnel.height; ++y) {
      for (int x = 0; x < tunnel.width; ++x) {
        draped += shadeOf(tunnel, x, y) != Shade::Other;
        const std::size_t at = (std::size_t(y) * tunnel.width + std::size_t(x)) * 3;
        terrain += tunnel.pixels[at] != tunnelPlain.pixels[at] || tunnel.pixels[at + 1] != tunnelPlain.pixels[at + 1];
      }
    }
    EXPECT_LE(draped, tunnel.width * tunnel.height / 200) << "imagery in the tunnel";
    EXPECT_LE(terrain, tunnel.width * tunnel.height / 100) << "pixels the imagery changed in the tunnel";
  }

  std::filesystem::path dir_;
  std::vector<StackTerrain> pyramid_;
  HeightGrid surface_;
};

TEST_F(StackImageryTest, StacksFullDrapesImageryOnTheTopsOnly) {
  StacksRenderOptions options;
  options.quad.nodeCells = 9;
  options.cellM = 2.0;
  Result<std::unique_ptr<StacksFullRenderer>> full = StacksFullRenderer::create(pyramid_.front(), options);
  ASSERT_TRUE(full) << full.error().message;
  expectDrapedOnTheTopsOnly(*full.value());
}

TEST_F(StackImageryTest, TheOctreeRendererDrapesImageryOnTheTopsOnly) {
  StacksRenderOptions options;
  options.quad.nodeCells = 9;
  options.cellM = 2.0;
  Result<std::unique_ptr<StacksLodRenderer>> lod = StacksLodRenderer::create(pyramid_, options, true);
  ASSERT_TRUE(lod) << lod.error().message;
  expectDrapedOnTheTopsOnly(*lod.value());
}

}  // namespace
}  // namespace tellus
