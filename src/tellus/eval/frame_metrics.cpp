#include "tellus/eval/frame_metrics.hpp"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace tellus {

namespace {

enum class TruePixel { Found, BehindCamera, NoTruth };

// Where the true surface point for the point drawn at `pixel` (depth `d`) appears on screen.
TruePixel truePixelOf(const glm::dvec2& pixel, float d, const ViewSetup& view,
                      const TrueSurfaceFn& trueSurface, glm::dvec2& truePixel) {
  const glm::dvec3 drawn = view.unprojectPixel(pixel, d);
  glm::dvec3 surface;
  if (!trueSurface(drawn, surface)) return TruePixel::NoTruth;
  return view.projectToPixel(surface, truePixel) ? TruePixel::Found : TruePixel::BehindCamera;
}

// The flat world's truth: the drawn point moved vertically onto the full-resolution mesh at
// the same ground position (x, y).
TrueSurfaceFn flatTruth(const HeightGrid& truth, double exaggeration) {
  return [&truth, exaggeration](const glm::dvec3& drawn, glm::dvec3& surface) {
    surface = {drawn.x, drawn.y, truth.meshHeightAtWorld(drawn.x, drawn.y) * exaggeration};
    return true;
  };
}

}  // namespace

ScreenSpaceError measureScreenSpaceError(const DepthImage& depth, const ViewSetup& view,
                                         const TrueSurfaceFn& trueSurface) {
  ScreenSpaceError result;
  result.errorPx.assign(depth.depth.size(), -1.0f);
  // A true point behind the camera is as wrong as can be: count it as the image diagonal.
  const double worst = std::hypot(double(depth.width), double(depth.height));
  for (int y = 0; y < depth.height; ++y) {
    for (int x = 0; x < depth.width; ++x) {
      const float d = depth.at(x, y);
      if (d <= 0.0f) continue;  // nothing drawn
      const glm::dvec2 pixel{x + 0.5, y + 0.5};
      glm::dvec2 truePixel;
      const TruePixel found = truePixelOf(pixel, d, view, trueSurface, truePixel);
      if (found == TruePixel::NoTruth) continue;
      const double error = found == TruePixel::Found ? glm::distance(truePixel, pixel) : worst;
      result.errorPx[std::size_t(y) * std::size_t(depth.width) + std::size_t(x)] = float(error);
    }
  }
  result.summary = summariseErrors(result.errorPx);
  return result;
}

ScreenSpaceError measureScreenSpaceError(const DepthImage& depth, const ViewSetup& view,
                                         const HeightGrid& truth, double exaggeration) {
  return measureScreenSpaceError(depth, view, flatTruth(truth, exaggeration));
}

ScreenSpaceError measurePopping(const DepthImage& current, const DepthImage& previousLod,
                                const ViewSetup& view, const TrueSurfaceFn& trueSurface) {
  ScreenSpaceError result;
  result.errorPx.assign(current.depth.size(), -1.0f);
  if (previousLod.width != current.width || previousLod.height != current.height) return result;
  const double worst = std::hypot(double(current.width), double(current.height));
  for (int y = 0; y < current.height; ++y) {
    for (int x = 0; x < current.width; ++x) {
      const float now = current.at(x, y);
      const float before = previousLod.at(x, y);
      if (now <= 0.0f || before <= 0.0f) continue;  // terrain in one render only
      float& pop = result.errorPx[std::size_t(y) * std::size_t(current.width) + std::size_t(x)];
      if (now == before) {  // the same surface point: it did not move
        pop = 0.0f;
        continue;
      }
      const glm::dvec2 pixel{x + 0.5, y + 0.5};
      glm::dvec2 trueNow, trueBefore;
      const TruePixel a = truePixelOf(pixel, now, view, trueSurface, trueNow);
      const TruePixel b = truePixelOf(pixel, before, view, trueSurface, trueBefore);
      if (a == TruePixel::NoTruth || b == TruePixel::NoTruth) {
        pop = -1.0f;
        continue;
      }
      const bool inFrontNow = a == TruePixel::Found, inFrontBefore = b == TruePixel::Found;
      pop = float(inFrontNow && inFrontBefore ? glm::distance(trueNow, trueBefore)
                  : inFrontNow == inFrontBefore ? 0.0
                                                : worst);
    }
  }
  result.summary = summariseErrors(result.errorPx);
  return result;
}

ScreenSpaceError measurePopping(const DepthImage& current, const DepthImage& previousLod,
                                const ViewSetup& view, const HeightGrid& truth,
                                double exaggeration) {
  return measurePopping(current, previousLod, view, flatTruth(truth, exaggeration));
}

ErrorSummary summariseErrors(const std::vector<float>& values) {
  std::vector<float> valid;
  valid.reserve(values.size());
  double sum = 0.0;
  for (float v : values) {
    if (v < 0.0f) continue;
    valid.push_back(v);
    sum += v;
  }
  ErrorSummary s;
  s.pixels = valid.size();
  if (valid.empty()) return s;
  s.meanPx = sum / double(valid.size());
  const auto percentile = [&valid](double fraction) {
    const std::size_t rank =
        std::min(valid.size() - 1, std::size_t(fraction * double(valid.size())));
    std::nth_element(valid.begin(), valid.begin() + std::ptrdiff_t(rank), valid.end());
    return double(valid[rank]);
  };
  s.p95Px = percentile(0.95);
  s.p99Px = percentile(0.99);
  s.maxPx = *std::max_element(valid.begin(), valid.end());
  return s;
}

RgbImage errorImage(const ScreenSpaceError& error, int width, int height,
                    const RgbImage& background) {
  RgbImage image = background;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float e = error.errorPx[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      if (e < 0.0f) continue;
      // 0 px green, 5 px yellow, >= 10 px red.
      const float t = std::clamp(e / 10.0f, 0.0f, 1.0f);
      std::uint8_t* p = image.at(x, y);
      p[0] = std::uint8_t(std::lround(255.0f * std::min(1.0f, 2.0f * t)));
      p[1] = std::uint8_t(std::lround(255.0f * std::min(1.0f, 2.0f * (1.0f - t))));
      p[2] = 0;
    }
  }
  return image;
}

std::vector<std::uint8_t> coverageFromDepth(const DepthImage& reference) {
  std::vector<std::uint8_t> coverage(reference.depth.size());
  std::transform(reference.depth.begin(), reference.depth.end(), coverage.begin(),
                 [](float d) { return std::uint8_t(d > 0.0f ? 1 : 0); });
  return coverage;
}

CrackReport detectCracks(const RgbImage& image, const std::uint8_t sentinel[3],
                         const std::vector<std::uint8_t>& referenceCoverage) {
  CrackReport report;
  const int w = image.width, h = image.height;
  const auto index = [w](int x, int y) { return std::size_t(y) * std::size_t(w) + std::size_t(x); };
  report.mask.assign(std::size_t(w) * std::size_t(h), 0);
  // Background pixels of the image, and those connected (4-neighbours, through background) to
  // background where the reference has no terrain or to the image border: the open sky.
  std::vector<std::uint8_t> background(report.mask.size(), 0), open(report.mask.size(), 0);
  std::vector<std::pair<int, int>> stack;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (p[0] != sentinel[0] || p[1] != sentinel[1] || p[2] != sentinel[2]) continue;
      background[index(x, y)] = 1;
      const bool border = x == 0 || y == 0 || x + 1 == w || y + 1 == h;
      if (border || !referenceCoverage[index(x, y)]) {
        open[index(x, y)] = 1;
        stack.emplace_back(x, y);
      }
    }
  }
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    for (const auto& [nx, ny] : {std::pair{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}}) {
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const std::size_t n = index(nx, ny);
      if (!background[n] || open[n]) continue;
      open[n] = 1;
      stack.emplace_back(nx, ny);
    }
  }
  const auto covered = [&](int x, int y) { return referenceCoverage[index(x, y)] != 0; };
  for (int y = 1; y + 1 < h; ++y) {
    for (int x = 1; x + 1 < w; ++x) {
      if (!background[index(x, y)]) continue;
      bool interior = true;
      for (int dy = -1; dy <= 1 && interior; ++dy)
        for (int dx = -1; dx <= 1 && interior; ++dx) interior = covered(x + dx, y + dy);
      if (!interior) continue;
      if (open[index(x, y)]) {
        ++report.silhouettePixels;
        continue;
      }
      report.mask[index(x, y)] = 1;
      ++report.crackPixels;
    }
  }
  return report;
}

void excludeOpenAirGaps(CrackReport& report, const std::vector<std::uint8_t>& backFaceCoverage) {
  if (backFaceCoverage.size() != report.mask.size()) return;
  for (std::size_t i = 0; i < report.mask.size(); ++i) {
    if (!report.mask[i] || backFaceCoverage[i]) continue;
    report.mask[i] = 0;
    --report.crackPixels;
    ++report.silhouettePixels;
  }
}

RgbImage markCracks(const RgbImage& image, const CrackReport& cracks) {
  RgbImage marked = image;
  const int w = image.width, h = image.height;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!cracks.mask[std::size_t(y) * std::size_t(w) + std::size_t(x)]) continue;
      for (int dy = -3; dy <= 3; ++dy) {
        for (int dx = -3; dx <= 3; ++dx) {
          const int px = x + dx, py = y + dy;
          if (px < 0 || py < 0 || px >= w || py >= h) continue;
          const bool ring = std::max(std::abs(dx), std::abs(dy)) >= 2;
          if (ring || (dx == 0 && dy == 0)) {
            std::uint8_t* p = marked.at(px, py);
            p[0] = 255;
            p[1] = 0;
            p[2] = 255;
          }
        }
      }
    }
  }
  return marked;
}

}  // namespace tellus
