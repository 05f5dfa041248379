// Prefiltered clipmap levels (clipmap_prefilter.hpp): the least-squares kernel keeps planes,
// lowers the error of a coarse level's surface against the finer samples on rough terrain, and
// its clamp holds the terrain's range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tellus/lod/clipmaps/clipmap_prefilter.hpp"

namespace tellus::clipmaps {
namespace {

constexpr int kR = PrefilterKernel::kRadius;
constexpr int kSide = PrefilterKernel::kSide;

float weight(int dx, int dy) { return leastSquaresKernel().weights[std::size_t((dy + kR) * kSide + dx + kR)]; }

TEST(ClipmapPrefilter, TheKernelSumsToOneAndIsSymmetricAboutItsCentre) {
  double sum = 0.0;
  for (int dy = -kR; dy <= kR; ++dy) {
    for (int dx = -kR; dx <= kR; ++dx) {
      sum += weight(dx, dy);
      // Half turn: the SW-NE triangulation maps onto itself.
      EXPECT_NEAR(weight(dx, dy), weight(-dx, -dy), 1e-6f) << dx << "," << dy;
      // Mirror across the SW-NE diagonal (x, y) -> (-y, -x): also a symmetry of the triangulation.
      EXPECT_NEAR(weight(dx, dy), weight(-dy, -dx), 1e-6f) << dx << "," << dy;
    }
  }
  EXPECT_NEAR(sum, 1.0, 1e-6);
  // The coarse sample's own position weighs most, then its six neighbours in the triangulation
  // (docs/clipmaps.md quotes these), and the weights die out towards the edge.
  EXPECT_NEAR(weight(0, 0), 0.429f, 0.002f);
  for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}, std::pair{1, -1}, std::pair{-1, 1}}) {
    EXPECT_NEAR(weight(dx, dy), 0.196f, 0.002f) << dx << "," << dy;
  }
  EXPECT_NEAR(weight(1, 1), -0.037f, 0.002f);  // across the NW-SE direction: no edge there
  for (int k = -kR; k <= kR; ++k) EXPECT_LT(std::abs(weight(k, kR)), 0.03f);
}

TEST(ClipmapPrefilter, APlaneIsKeptExactly) {
  const LevelSampler plane = [](int level, glm::ivec2 s) {
    const float x = float(s.x << level), y = float(s.y << level);
    return 120.0f + 0.75f * x - 0.5f * y;
  };
  const LevelFilter filter{true};
  for (int level = 1; level < 4; ++level) {
    for (const glm::ivec2 s : {glm::ivec2(0, 0), glm::ivec2(7, -3), glm::ivec2(40, 25)}) {
      EXPECT_NEAR(filteredHeight(plane, filter, level, s), plane(level, s), 1e-3f);
    }
  }
}

// Rough terrain: a coarse level's surface (SW-NE triangles) against the finer level's samples.
// Least squares is the mean-square optimum over the window; the test checks that it lowers the
// root mean square and the 99th percentile of the error by a margin over subsampling.
TEST(ClipmapPrefilter, LowersTheCoarseSurfacesErrorOnRoughTerrain) {
  constexpr int kFine = 257;
  std::vector<float> fine(std::size_t(kFine) * kFine);
  std::mt19937 random(3);
  std::normal_distribution<float> noise(0.0f, 30.0f);
  // A ridge and valley field with noise at every scale (a sum of octaves).
  std::vector<float> octave(fine.size());
  for (int scale = 64; scale >= 1; scale /= 2) {
    const int cells = kFine / scale + 2;
    std::vector<float> knots(std::size_t(cells) * std::size_t(cells));
    for (float& k : knots) k = noise(random) * std::sqrt(float(scale));
    for (int y = 0; y < kFine; ++y) {
      for (int x = 0; x < kFine; ++x) {
        const float fx = float(x) / float(scale), fy = float(y) / float(scale);
        const int ix = int(fx), iy = int(fy);
        const float tx = fx - float(ix), ty = fy - float(iy);
        const auto k = [&](int i, int j) { return knots[std::size_t(j) * std::size_t(cells) + std::size_t(i)]; };
        fine[std::size_t(y) * kFine + std::size_t(x)] +=
            (1 - ty) * ((1 - tx) * k(ix, iy) + tx * k(ix + 1, iy)) + ty * ((1 - tx) * k(ix, iy + 1) + tx * k(ix + 1, iy + 1));
      }
    }
  }
  const auto at = [&](glm::ivec2 s) {
    return fine[std::size_t(std::clamp(s.y, 0, kFine - 1)) * kFine + std::size_t(std::clamp(s.x, 0, kFine - 1))];
  };
  // The stored pyramid subsamples level 0.
  const LevelSampler stored = [&](int level, glm::ivec2 s) { return at(s * (1 << level)); };
  const auto errors = [&](const LevelSampler& levels) {
    std::vector<double> out;
    // Inside the margin, away from the clamped edge.
    for (int y = 16; y < kFine - 17; ++y) {
      for (int x = 16; x < kFine - 17; ++x) {
        const int i = x / 2, j = y / 2;
        const bool oddX = (x & 1) != 0, oddY = (y & 1) != 0;
        float surface = levels(1, {i, j});
        if (oddX && !oddY) surface = 0.5f * (levels(1, {i, j}) + levels(1, {i + 1, j}));
        if (!oddX && oddY) surface = 0.5f * (levels(1, {i, j}) + levels(1, {i, j + 1}));
        if (oddX && oddY) surface = 0.5f * (levels(1, {i, j + 1}) + levels(1, {i + 1, j}));
        out.push_back(std::abs(double(surface - at({x, y}))));
      }
    }
    std::sort(out.begin(), out.end());
    double squares = 0.0;
    for (double e : out) squares += e * e;
    return std::pair{std::sqrt(squares / double(out.size())), out[out.size() * 99 / 100]};
  };
  const auto [subsampledRms, subsampledP99] = errors(stored);
  const auto [filteredRms, filteredP99] = errors(filteredSampler(stored, LevelFilter{true}));
  EXPECT_LT(filteredRms, 0.9 * subsampledRms) << subsampledRms << " -> " << filteredRms;
  EXPECT_LT(filteredP99, 0.9 * subsampledP99) << subsampledP99 << " -> " << filteredP99;
}

TEST(ClipmapPrefilter, SamplesWhoseWindowCrossesTheTerrainsEdgeKeepTheStoredHeight) {
  const LevelSampler stored = [](int level, glm::ivec2 s) {
    const long long x = static_cast<long long>(s.x) << level, y = static_cast<long long>(s.y) << level;
    return float((x * 7919 + y * 104729) % 1000);
  };
  // 101 x 81 samples: level 1's samples 0..50 x 0..40; its window reaches 4 level-0 samples.
  const LevelFilter filter{true, -1e9f, 1e9f, glm::ivec2(101, 81)};
  for (const glm::ivec2 s : {glm::ivec2(0, 20), glm::ivec2(1, 20), glm::ivec2(49, 20), glm::ivec2(50, 20), glm::ivec2(20, 39)}) {
    EXPECT_EQ(filteredHeight(stored, filter, 1, s), stored(1, s)) << s.x << "," << s.y;
  }
  // Inside, the fit (here not the stored value).
  EXPECT_NE(filteredHeight(stored, filter, 1, {20, 20}), stored(1, {20, 20}));
  EXPECT_NE(filteredHeight(stored, filter, 1, {2, 2}), stored(1, {2, 2}));
  // Level 2 reads level 1 (0..50): its windows fit from sample 2 to 23.
  EXPECT_EQ(filteredHeight(stored, filter, 2, {24, 10}), stored(2, {24, 10}));
  EXPECT_NE(filteredHeight(stored, filter, 2, {23, 10}), stored(2, {23, 10}));
}

TEST(ClipmapPrefilter, TheStoredLevelsAreKeptWhenNotPrefilteringAndTheClampHolds) {
  const LevelSampler spiky = [](int level, glm::ivec2 s) {
    const long long x = static_cast<long long>(s.x) << level, y = static_cast<long long>(s.y) << level;
    return ((x + y) % 2 == 0) ? 1000.0f : 0.0f;
  };
  for (int level = 0; level < 3; ++level) {
    EXPECT_EQ(filteredHeight(spiky, LevelFilter{false}, level, {5, 9}), spiky(level, {5, 9}));
  }
  // Level 0 is never filtered.
  EXPECT_EQ(filteredHeight(spiky, LevelFilter{true}, 0, {5, 8}), spiky(0, {5, 8}));
  const LevelFilter clamped{true, 100.0f, 600.0f};
  for (int x = -4; x < 4; ++x) {
    const float h = filteredHeight(spiky, clamped, 1, {x, 3});
    EXPECT_GE(h, 100.0f);
    EXPECT_LE(h, 600.0f);
  }
}

}  // namespace
}  // namespace tellus::clipmaps
