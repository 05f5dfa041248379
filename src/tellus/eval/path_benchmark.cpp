#include "tellus/eval/path_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "tellus/core/thread_cpu_clock.hpp"
#include "tellus/eval/depth_truth_error.hpp"
#include "tellus/eval/frame_metrics.hpp"
#include "tellus/gl/gpu_frame_timer.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/render/output/offscreen_target.hpp"

namespace tellus {
namespace {

constexpr std::uint8_t kSentinel[3] = {255, 0, 255};
constexpr int kMaxCrackImages = 8;  // marked images kept of the first frames with cracks

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The kept image of a quality frame: every background pixel back to the sky colour except the
// cracks, which stay magenta.
RgbImage withSky(const RgbImage& image, const CrackReport& cracks, const glm::u8vec3& sky) {
  RgbImage out = image;
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      std::uint8_t* p = out.at(x, y);
      const bool sentinel = p[0] == kSentinel[0] && p[1] == kSentinel[1] && p[2] == kSentinel[2];
      if (sentinel && !cracks.mask[std::size_t(y) * std::size_t(out.width) + std::size_t(x)]) {
        p[0] = sky.r;
        p[1] = sky.g;
        p[2] = sky.b;
      }
    }
  }
  return out;
}

}  // namespace

Distribution distributionOf(std::vector<double> values) {
  Distribution d;
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  const auto at = [&](double p) {
    const double rank = p * double(values.size() - 1);
    const std::size_t lo = std::size_t(std::floor(rank));
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (values[hi] - values[lo]) * (rank - double(lo));
  };
  d.median = at(0.5);
  d.min = values.front();
  d.max = values.back();
  d.p95 = at(0.95);
  d.p99 = at(0.99);
  double sum = 0.0;
  for (double v : values) sum += v;
  d.mean = sum / double(values.size());
  return d;
}

void ErrorHistogram::add(float errorPx) {
  if (errorPx < 0.0f) return;
  const auto bin = std::min<std::size_t>(std::size_t(double(errorPx) / kBinPx), kBins);
  ++counts[bin];
  sum += errorPx;
  max = std::max(max, double(errorPx));
  ++total;
}

void ErrorHistogram::merge(const ErrorHistogram& other) {
  for (std::size_t i = 0; i < counts.size(); ++i) counts[i] += other.counts[i];
  sum += other.sum;
  max = std::max(max, other.max);
  total += other.total;
}

void PathRun::append(PathRun&& later) {
  const int offset = int(frames.size());
  for (FrameRecord& f : later.frames) {
    f.index += offset;
    frames.push_back(std::move(f));
  }
  errors.merge(later.errors);
  popping.merge(later.popping);
  for (auto& mask : later.coverage) coverage.push_back(std::move(mask));
  for (auto& depth : later.depths) depths.push_back(std::move(depth));
  for (KeptFrame& k : later.kept) {
    k.index += offset;
    kept.push_back(std::move(k));
  }
}

double ErrorHistogram::percentile(double p) const {
  if (total == 0) return 0.0;
  const auto wanted = std::uint64_t(std::ceil(p * double(total)));
  std::uint64_t seen = 0;
  for (std::size_t bin = 0; bin < counts.size(); ++bin) {
    seen += counts[bin];
    // The bin's upper edge, but never beyond the largest value (all zeros: exactly 0).
    if (seen >= wanted) return bin == std::size_t(kBins) ? max : std::min(max, double(bin + 1) * kBinPx);
  }
  return max;
}

Result<PathRun> runPath(TerrainRenderer& renderer, const std::vector<Camera>& cameras,
                        const HeightGrid& truth, const PathRunOptions& options,
                        const CoverageMasks& referenceCoverage,
                        const std::function<void(int)>& onFrame) {
  const Aabb bounds = truth.worldBounds();
  std::vector<ViewSetup> views;
  views.reserve(cameras.size());
  for (const Camera& camera : cameras) {
    views.push_back(ViewSetup::create(camera, bounds, options.width, options.height));
  }
  PathTruth flat;
  flat.surface = [&truth](const glm::dvec3& drawn, glm::dvec3& surface) {
    surface = {drawn.x, drawn.y, truth.meshHeightAtWorld(drawn.x, drawn.y)};
    return true;
  };
  flat.fitSettings = [bounds](const ViewSetup& view, RenderSettings& settings) {
    settings.shading.fitHazeToView(bounds, view.camera.position, view.clip.farM);
  };
  return runViews(renderer, views, flat, options, referenceCoverage, onFrame);
}

Result<PathRun> runDepthTruthPath(TerrainRenderer& renderer, const std::vector<Camera>& cameras,
                                  const Aabb& bounds, const PathRunOptions& options,
                                  const std::vector<DepthImage>* truthDepths,
                                  const CoverageMasks& referenceCoverage,
                                  const std::function<void(int)>& onFrame) {
  if (truthDepths && truthDepths->size() != cameras.size()) {
    return makeError("ground-truth depths for {} frames, the path has {}", truthDepths->size(),
                     cameras.size());
  }
  std::vector<ViewSetup> views;
  views.reserve(cameras.size());
  for (const Camera& camera : cameras) {
    views.push_back(ViewSetup::create(camera, bounds, options.width, options.height));
  }
  PathTruth truth;
  truth.depths = truthDepths;
  truth.fitSettings = [bounds](const ViewSetup& view, RenderSettings& settings) {
    settings.shading.fitHazeToView(bounds, view.camera.position, view.clip.farM);
  };
  return runViews(renderer, views, truth, options, referenceCoverage, onFrame);
}

Result<PathRun> runViews(TerrainRenderer& renderer, const std::vector<ViewSetup>& views,
                         const PathTruth& truth, const PathRunOptions& options,
                         const CoverageMasks& referenceCoverage,
                         const std::function<void(int)>& onFrame) {
  if (views.empty()) return makeError("the camera path has no frames");
  if (truth.depths && truth.depths->size() != views.size()) {
    return makeError("ground-truth depths for {} frames, the path has {}", truth.depths->size(),
                     views.size());
  }
  if (!referenceCoverage.empty() && referenceCoverage.size() != views.size()) {
    return makeError("reference coverage for {} frames, the path has {}", referenceCoverage.size(),
                     views.size());
  }
  Result<OffscreenTarget> target = OffscreenTarget::create(options.width, options.height, options.quality ? 1 : options.samples);
  if (!target) return target.error();
  const glm::u8vec3 sky = skyColour8(options.settings.shading);
  const glm::u8vec3 clear =
      options.quality ? glm::u8vec3(kSentinel[0], kSentinel[1], kSentinel[2]) : sky;
  const auto settingsFor = [&](const ViewSetup& view) {
    RenderSettings settings = options.settings;
    if (truth.fitSettings) truth.fitSettings(view, settings);
    return settings;
  };

  PathRun run;
  run.algo = std::string(renderer.name());
  // Warm-up: shader compilation, first uploads, driver caches.
  for (int i = 0; i < options.warmupFrames; ++i) {
    const ViewSetup& view = views.front();
    target->begin(clear);
    const RenderSettings settings = settingsFor(view);
    if (settings.imagery) settings.imagery->beginFrame();
    renderer.prepare(view, settings);
    renderer.draw(view, settings);
    if (settings.imagery) settings.imagery->endFrame();
    if (std::optional<Error> corrupt = renderer.dataError()) return *corrupt;
  }
  gl::finish();

  gl::GpuFrameTimer timer;
  const auto collect = [&](const std::vector<gl::GpuFrameTimer::Sample>& samples) {
    for (const auto& s : samples) run.frames[std::size_t(s.frame)].gpuMs = s.milliseconds;
  };
  run.frames.resize(views.size());
  int crackImagesKept = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const ViewSetup& view = views[i];
    const RenderSettings settings = settingsFor(view);
    FrameRecord& record = run.frames[i];
    record.index = int(i);
    record.camera = view.camera;
    if (options.beforeFrame) options.beforeFrame(int(i));
    if (settings.imagery) {
      settings.imagery->beginFrame();
      record.imagery = settings.imagery->frameInfo();
    }
    target->begin(clear);
    // The clear is the harness's: llvmpipe bins it only at the next flush, which would otherwise
    // be the renderer's first memory barrier or fence and be charged to its LOD step (0.04 ms of
    // render-thread CPU at 1280x720).
    glFlush();
    const auto start = std::chrono::steady_clock::now();
    const double threadStart = threadCpuSeconds();
    const std::uint64_t waitsBefore = gl::gpuWaitCount();
    renderer.prepare(view, settings);
    record.cpuLodMs = millisecondsSince(start);
    record.cpuLodThreadMs = (threadCpuSeconds() - threadStart) * 1e3;
    const auto submit = std::chrono::steady_clock::now();
    const double submitThreadStart = threadCpuSeconds();
    // The GPU timer's own wait (its ring of queries wrapped onto a frame still in flight) is the
    // harness's, not the renderer's.
    const std::uint64_t waitsBeforeTimer = gl::gpuWaitCount();
    timer.beginFrame(i);
    const std::uint64_t timerWaits = gl::gpuWaitCount() - waitsBeforeTimer;
    record.stats = renderer.draw(view, settings);
    timer.endFrame();
    record.cpuSubmitThreadMs = (threadCpuSeconds() - submitThreadStart) * 1e3;
    record.stats.gpuWaits = gl::gpuWaitCount() - waitsBefore - timerWaits;
    if (std::optional<Error> corrupt = renderer.dataError()) {
      return makeError("frame {}: {}", i, corrupt->message);
    }
    glFlush();
    record.cpuSubmitMs = millisecondsSince(submit);
    if (options.finishFrames) {
      gl::finish();
      record.finishedMs = millisecondsSince(start);
    }
    renderer.finishStats(record.stats);  // after the timing: it may wait for the GPU
    collect(timer.poll());

    const bool keep = std::find(options.keepFrames.begin(), options.keepFrames.end(), int(i)) !=
                      options.keepFrames.end();
    RgbImage picture;  // for the frame sink
    if (options.quality) {
      const DepthImage depth = target->readDepth();
      const RgbImage colour = target->readRgb();
      const ScreenSpaceError error =
          truth.surface  ? measureScreenSpaceError(depth, view, truth.surface)
          : truth.depths ? measureDepthTruthError(depth, (*truth.depths)[i], view)
                         : measureDepthTruthError(depth, depth, view);  // the ground truth itself
      for (float e : error.errorPx) run.errors.add(e);
      record.ssePxMean = error.summary.meanPx;
      record.ssePxP95 = error.summary.p95Px;
      record.ssePxP99 = error.summary.p99Px;
      record.ssePxMax = error.summary.maxPx;
      record.ssePixels = error.summary.pixels;
      run.coverage.push_back(coverageFromDepth(depth));
      if (options.recordDepths) run.depths.push_back(depth);
      const std::vector<std::uint8_t>& reference =
          referenceCoverage.empty() ? run.coverage.back() : referenceCoverage[i];
      // Popping: this frame's view drawn again with the previous frame's selection.
      target->begin(clear);
      if (renderer.drawPreviousSelection(view, settings)) {
        const DepthImage previous = target->readDepth();
        const ScreenSpaceError pop = truth.surface
                                         ? measurePopping(depth, previous, view, truth.surface)
                                         : measureDepthTruthError(depth, previous, view);
        for (float e : pop.errorPx) run.popping.add(e);
        record.popPxMean = pop.summary.meanPx;
        record.popPxP99 = pop.summary.p99Px;
        record.popPxMax = pop.summary.maxPx;
        record.popPixels = pop.summary.pixels;
      }
      CrackReport cracks = detectCracks(colour, kSentinel, reference);
      if (cracks.crackPixels > 0) {
        // Closed solids: enclosed background reached through open air is no hole.
        target->begin(clear);
        if (renderer.drawLastFrameBackFaces(view, settings)) {
          excludeOpenAirGaps(cracks, coverageFromDepth(target->readDepth()));
        }
      }
      record.crackPixels = cracks.crackPixels;
      record.silhouettePixels = cracks.silhouettePixels;
      if (options.frameSink) picture = withSky(colour, cracks, sky);
      const bool firstCracks = cracks.crackPixels > 0 && crackImagesKept < kMaxCrackImages;
      if (keep || firstCracks) {
        crackImagesKept += firstCracks ? 1 : 0;
        KeptFrame kept;
        kept.index = int(i);
        kept.image = withSky(colour, cracks, sky);
        if (firstCracks) kept.cracksMarked = markCracks(kept.image, cracks);
        kept.errors = errorImage(error, options.width, options.height, kept.image);
        run.kept.push_back(std::move(kept));
      }
    } else if (keep || options.frameSink) {
      picture = target->readRgb();
      if (keep) run.kept.push_back(KeptFrame{int(i), picture, {}, {}});
    }
    if (options.frameSink) {
      const FrameImage frame{run.algo, int(i), double(i) * options.frameIntervalS, options.frameIntervalS, picture};
      if (Status sunk = options.frameSink(frame); !sunk) return sunk.error();
    }
    if (settings.imagery) settings.imagery->endFrame();
    if (onFrame) onFrame(int(i));
  }
  collect(timer.finish());
  for (FrameRecord& record : run.frames) {
    record.frameMs = options.finishFrames
                         ? record.finishedMs
                         : std::max(record.cpuLodMs + record.cpuSubmitMs, record.gpuMs);
  }
  return run;
}

}  // namespace tellus
