#include "support/globe_fixtures.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/tiles/global_store_builder.hpp"
#include "tellus/viewer/globe_camera.hpp"

namespace tellus::test {

double syntheticEarthRelief(double lat, double lon) {
  constexpr double k = 3.14159265358979323846 / 180.0;
  return 800.0 + 700.0 * std::sin(3.0 * lat * k) * std::cos(2.0 * lon * k) +
         400.0 * std::sin(300.0 * lat * k) * std::sin(250.0 * lon * k);
}

std::shared_ptr<const GlobalStore> buildSyntheticEarth(double (*relief)(double, double)) {
  const std::filesystem::path dir = freshTestDir();
  const std::filesystem::path coarse =
      writeLatLonTerrain(dir / "planet.tif", -180.0, 90.0, 0.5, 720, 361, relief);
  const std::filesystem::path fine =
      writeLatLonTerrain(dir / "area.tif", 10.0, 44.0, 0.005, 801, 801, relief);
  GlobalBuildOptions options;
  options.tileCells = 32;
  EXPECT_TRUE(buildGlobalStore({coarse, fine}, dir / "earth.tstore", options));
  Result<std::shared_ptr<GlobalStore>> store = GlobalStore::open(dir / "earth.tstore");
  EXPECT_TRUE(store) << store.error().message;
  return store ? store.value() : nullptr;
}

std::shared_ptr<const GlobalStore> syntheticEarth() {
  static const std::shared_ptr<const GlobalStore> store = buildSyntheticEarth(syntheticEarthRelief);
  return store;
}

int groundHoles(const RenderedFrame& frame, const ViewSetup& view, double reachM) {
  const auto onEarth = [&](int x, int y) {
    return ellipsoidUnderPixel(view, {x + 0.5, y + 0.5}).has_value();
  };
  int count = 0;
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const std::uint8_t* p = &frame.colour.pixels[(std::size_t(y) * view.width + x) * 3];
      if (p[0] != kSentinel[0] || p[1] != kSentinel[1] || p[2] != kSentinel[2]) continue;
      const std::optional<glm::dvec2> ground = ellipsoidUnderPixel(view, {x + 0.5, y + 0.5});
      if (!ground || !onEarth(x - 3, y) || !onEarth(x + 3, y) || !onEarth(x, y - 3) ||
          !onEarth(x, y + 3)) {
        continue;
      }
      const glm::dvec3 point =
          wgs84::geodeticToEcef({ground->x * wgs84::kDegree, ground->y * wgs84::kDegree, 0.0});
      if (glm::distance(point, view.camera.position) < reachM) ++count;
    }
  }
  return count;
}

DepthComparison compareDepths(const RenderedFrame& drawn, const RenderedFrame& truth,
                              const ViewSetup& view, int step) {
  DepthComparison result;
  for (int y = 0; y < view.height; y += step) {
    for (int x = 0; x < view.width; x += step) {
      const float a = drawn.depth.at(x, y), b = truth.depth.at(x, y);
      if (a <= 0.0f) {
        ++result.holes;
        continue;
      }
      if (b <= 0.0f) continue;
      const glm::dvec3 p = view.unprojectPixel({x + 0.5, y + 0.5}, a);
      const glm::dvec3 q = view.unprojectPixel({x + 0.5, y + 0.5}, b);
      result.worstM = std::max(result.worstM, glm::distance(p, q));
      ++result.compared;
    }
  }
  return result;
}

}  // namespace tellus::test
