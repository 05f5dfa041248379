#include "tellus/dem/terrain_generator.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include <tbb/parallel_for.h>

#include "tellus/core/progress.hpp"
#include "tellus/dem/gradient_noise.hpp"

namespace tellus {
namespace {

// Rotates each octave's domain by ~37 degrees so lattice artefacts do not line up.
glm::dvec2 rotateOctave(glm::dvec2 p) {
  return {0.8 * p.x - 0.6 * p.y, 0.6 * p.x + 0.8 * p.y};
}

double fbm(const GradientNoise& noise, glm::dvec2 p, int octaves) {
  double sum = 0.0, amplitude = 0.5;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * noise.sample(p).x;
    p = rotateOctave(p) * 2.0 + glm::dvec2(17.3, -9.1);
    amplitude *= 0.5;
  }
  return sum;
}

// The height field before erosion, at world position p (metres).
class TerrainShape {
 public:
  explicit TerrainShape(const TerrainParams& params)
      : params_(params),
        warp_(params.seed * 4 + 0),
        relief_(params.seed * 4 + 1),
        ridges_(params.seed * 4 + 2),
        detail_(params.seed * 4 + 3) {
    // Octaves down to a wavelength of about two samples.
    ridgeOctaves_ =
        std::clamp(int(std::log2(kRidgeWavelengthM / (2.0 * params.spacingM))) + 1, 1, 14);
  }

  double heightAt(glm::dvec2 pMetres) const {
    const glm::dvec2 p = pMetres / 1000.0;  // kilometres
    // Domain warp bends ridges and valleys so they do not follow the noise lattice.
    const glm::dvec2 warp(fbm(warp_, p / 25.0, 4), fbm(warp_, p / 25.0 + glm::dvec2(5.2, 1.3), 4));
    const glm::dvec2 q = p + warp * 6.0;
    // Large-scale relief: where mountain ranges rise from lowland plains.
    const double mask = glm::smoothstep(-0.22, 0.28, fbm(relief_, q / 45.0, 3));
    const double mountains = erodedRidges(q / (kRidgeWavelengthM / 1000.0));
    const double hills = 0.5 + fbm(detail_, q / 6.0, 4);
    return params_.reliefM * (mask * std::pow(mountains, 1.2) + 0.03 * hills + 0.02);
  }

 private:
  static constexpr double kRidgeWavelengthM = 14000.0;

  // Ridged multifractal whose finer octaves are damped where the accumulated slope is steep
  // (the derivative trick that imitates erosion: smooth flanks, detailed crests and valleys).
  double erodedRidges(glm::dvec2 p) const {
    double sum = 0.0, amplitude = 0.5, weight = 1.0;
    glm::dvec2 slope(0.0);  // accumulated gradient of the raw noise: continuous everywhere
    for (int i = 0; i < ridgeOctaves_; ++i) {
      const glm::dvec3 n = ridges_.sample(p);
      slope += glm::dvec2(n.y, n.z) * amplitude;
      const double ridge = std::max(0.0, 1.0 - std::abs(n.x) * 1.4);
      const double value = ridge * ridge;
      sum += amplitude * value * weight / (1.0 + 0.75 * glm::dot(slope, slope));
      weight = std::clamp(value * 1.6, 0.0, 1.0);  // detail concentrates on crests
      p = rotateOctave(p) * 2.0 + glm::dvec2(3.7, 1.9);
      amplitude *= 0.5;
    }
    return std::clamp(sum, 0.0, 1.5);
  }

  TerrainParams params_;
  GradientNoise warp_, relief_, ridges_, detail_;
  int ridgeOctaves_ = 10;
};

// Talus relaxation: material slides to lower 4-neighbours wherever the slope exceeds
// maxSlope. Jacobi update (reads the old field only), so it is parallel and deterministic.
void thermalErosion(HeightGrid& grid, int iterations, double maxSlope) {
  const int w = grid.width, h = grid.height;
  std::vector<float> next(grid.heights.size());
  const float talus = float(maxSlope * grid.spacingXM);
  for (int it = 0; it < iterations; ++it) {
    const std::vector<float>& cur = grid.heights;
    tbb::parallel_for(0, h, [&](int row) {
      for (int col = 0; col < w; ++col) {
        const float hc = cur[size_t(row) * w + col];
        float delta = 0.0f;
        constexpr int kDc[4] = {1, -1, 0, 0}, kDr[4] = {0, 0, 1, -1};
        for (int k = 0; k < 4; ++k) {
          const int c = col + kDc[k], r = row + kDr[k];
          if (c < 0 || c >= w || r < 0 || r >= h) continue;
          const float d = hc - cur[size_t(r) * w + c];  // >0: we are higher
          if (d > talus) delta -= 0.12f * (d - talus);
          if (-d > talus) delta += 0.12f * (-d - talus);
        }
        next[size_t(row) * w + col] = hc + delta;
      }
    });
    std::swap(grid.heights, next);
  }
}

// Droplet-based hydraulic erosion (after Beyer 2015): droplets run downhill, pick up sediment
// where they speed up and drop it where they slow down, carving gullies and filling valleys.
// Sequential and seeded, so deterministic. Works on heights normalised to the relief range,
// the regime the constants below are tuned for (a drop of ~0.01 per step on steep slopes).
class HydraulicErosion {
 public:
  HydraulicErosion(HeightGrid& grid, std::uint64_t seed)
      : grid_(grid), rng_(seed ^ 0x5DEECE66DULL) {
    for (int dy = -kRadius; dy <= kRadius; ++dy) {
      for (int dx = -kRadius; dx <= kRadius; ++dx) {
        const double weight = std::max(0.0, kRadius + 0.5 - std::hypot(dx, dy));
        if (weight > 0.0) brush_.push_back({dx, dy, weight});
      }
    }
    double total = 0.0;
    for (const auto& b : brush_) total += b.weight;
    for (auto& b : brush_) b.weight /= total;
  }

  void run(std::uint64_t droplets, Progress& progress) {
    const HeightRange range = grid_.heightRange();
    const float scale = 1.0f / std::max(1.0f, range.maxM - range.minM);
    for (float& v : grid_.heights) v *= scale;
    for (std::uint64_t i = 0; i < droplets; ++i) {
      simulateDroplet();
      if ((i & 4095) == 0) progress.advance(4096);
    }
    for (float& v : grid_.heights) v /= scale;
  }

 private:
  static constexpr int kRadius = 3;
  struct BrushTap {
    int dx, dy;
    double weight;
  };

  double random01() {
    rng_ += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = rng_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return double((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
  }

  // Height and gradient at (x, y) in sample units, bilinear.
  glm::dvec3 heightAndGradient(double x, double y) const {
    const int c = int(x), r = int(y);
    const double u = x - c, v = y - r;
    const double h00 = grid_.at(c, r), h10 = grid_.at(c + 1, r);
    const double h01 = grid_.at(c, r + 1), h11 = grid_.at(c + 1, r + 1);
    const double gx = (h10 - h00) * (1 - v) + (h11 - h01) * v;
    const double gy = (h01 - h00) * (1 - u) + (h11 - h10) * u;
    const double hh = h00 * (1 - u) * (1 - v) + h10 * u * (1 - v) + h01 * (1 - u) * v + h11 * u * v;
    return {hh, gx, gy};
  }

  void deposit(double x, double y, double amount) {
    const int c = int(x), r = int(y);
    const double u = x - c, v = y - r;
    grid_.at(c, r) += float(amount * (1 - u) * (1 - v));
    grid_.at(c + 1, r) += float(amount * u * (1 - v));
    grid_.at(c, r + 1) += float(amount * (1 - u) * v);
    grid_.at(c + 1, r + 1) += float(amount * u * v);
  }

  double erode(double x, double y, double amount) {
    const int c = int(x), r = int(y);
    double removed = 0.0;
    for (const BrushTap& tap : brush_) {
      const int cc = c + tap.dx, rr = r + tap.dy;
      if (cc < 0 || rr < 0 || cc >= grid_.width || rr >= grid_.height) continue;
      float& cell = grid_.at(cc, rr);
      const double take = amount * tap.weight;
      cell -= float(take);
      removed += take;
    }
    return removed;
  }

  void simulateDroplet() {
    const double maxX = grid_.width - 1.001, maxY = grid_.height - 1.001;
    double x = random01() * maxX, y = random01() * maxY;
    double dirX = 0.0, dirY = 0.0, speed = 1.0, water = 1.0, sediment = 0.0;
    constexpr double kInertia = 0.05, kCapacity = 4.0, kMinCapacity = 0.001, kDepositRate = 0.3,
                     kErodeRate = 0.3, kEvaporation = 0.015, kGravity = 4.0;
    for (int step = 0; step < 48; ++step) {
      const glm::dvec3 here = heightAndGradient(x, y);
      dirX = dirX * kInertia - here.y * (1 - kInertia);
      dirY = dirY * kInertia - here.z * (1 - kInertia);
      const double len = std::hypot(dirX, dirY);
      if (len < 1e-9) break;
      dirX /= len;
      dirY /= len;
      const double nx = x + dirX, ny = y + dirY;
      if (nx < 0 || ny < 0 || nx >= maxX || ny >= maxY) break;
      const double dh = heightAndGradient(nx, ny).x - here.x;
      const double capacity = std::max(-dh * speed * water * kCapacity, kMinCapacity);
      if (sediment > capacity || dh > 0) {
        const double amount =
            dh > 0 ? std::min(dh, sediment) : (sediment - capacity) * kDepositRate;
        sediment -= amount;
        deposit(x, y, amount);
      } else {
        sediment += erode(x, y, std::min((capacity - sediment) * kErodeRate, -dh));
      }
      speed = std::sqrt(std::max(0.0, speed * speed - dh * kGravity));
      water *= 1.0 - kEvaporation;
      x = nx;
      y = ny;
    }
  }

  HeightGrid& grid_;
  std::uint64_t rng_;
  std::vector<BrushTap> brush_;
};

}  // namespace

Status checkTerrainParams(const TerrainParams& params) {
  const auto within = [](double v, double lo, double hi) { return v >= lo && v <= hi; };
  if (!within(params.size, kMinTerrainSize, kMaxTerrainSize)) {
    return makeError("terrain size {} is outside {} to {}", params.size, kMinTerrainSize,
                     kMaxTerrainSize);
  }
  if (!within(params.spacingM, kMinTerrainSpacingM, kMaxTerrainSpacingM)) {
    return makeError("terrain spacing {} m is outside {} to {} m", params.spacingM,
                     kMinTerrainSpacingM, kMaxTerrainSpacingM);
  }
  if (!within(params.reliefM, kMinReliefM, kMaxReliefM)) {
    return makeError("terrain relief {} m is outside {} to {} m", params.reliefM, kMinReliefM,
                     kMaxReliefM);
  }
  if (!within(params.erosion, 0.0, kMaxErosion)) {
    return makeError("erosion {} is outside 0 to {}", params.erosion, kMaxErosion);
  }
  return {};
}

HeightGrid generateTerrain(const TerrainParams& params) {
  HeightGrid grid(params.size, params.size);
  grid.spacingXM = grid.spacingYM = params.spacingM;
  const std::uint64_t samples = std::uint64_t(params.size) * std::uint64_t(params.size);
  const std::uint64_t droplets =
      params.erosion > 0.0
          ? std::uint64_t(double(std::min<std::uint64_t>(samples, 4'000'000)) * params.erosion)
          : 0;
  Progress progress("generate", std::uint64_t(params.size) + droplets);

  const TerrainShape shape(params);
  tbb::parallel_for(0, params.size, [&](int row) {
    const double y = double(params.size - 1 - row) * params.spacingM;
    for (int col = 0; col < params.size; ++col) {
      grid.at(col, row) = float(shape.heightAt({double(col) * params.spacingM, y}));
    }
    progress.advance();
  });
  if (params.erosion > 0.0 && params.size >= 8) {
    thermalErosion(grid, 4, 1.2);
    HydraulicErosion(grid, params.seed).run(droplets, progress);
    thermalErosion(grid, 2, 1.0);
  }
  return grid;
}

}  // namespace tellus
