// tellus bench --stack-edits N on a .tstack: N brush strokes while flying the path, applied by
// the octree renderer as the viewer's brush applies them, judged against a ground truth that
// sees the same strokes (stacks-full made again from the edited stacks after each stroke).
#include <algorithm>

#include <spdlog/spdlog.h>

#include "stack_cli.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/stacks/stacks_lod_renderer.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"

namespace tellus::cli {

std::vector<ScriptedStackEdit> planBenchStrokes(std::vector<StackTerrain> pyramid,
                                                const std::vector<Camera>& cameras,
                                                const Aabb& bounds, int count) {
  std::vector<ScriptedStackEdit> strokes;
  if (count <= 0 || cameras.empty()) return strokes;
  StackTerrain& finest = pyramid.front();
  const double radiusM = 3.0 * finest.spacingM();
  for (int i = 0; i < count; ++i) {
    const int frame = int(std::int64_t(i) * std::int64_t(cameras.size()) / count);
    // Where the viewer's brush would land under a cursor that wanders over the middle of the
    // picture (a 16 x 9 view; the ray only needs the camera).
    const ViewSetup view = ViewSetup::create(cameras[std::size_t(frame)], bounds, 1600, 900);
    // (When the cursor points at the sky, the user would move it down: so do the candidates.)
    const glm::dvec3 origin = view.camera.position;
    std::optional<glm::dvec3> hit;
    for (int down = 0; down < 8 && !hit; ++down) {
      const glm::dvec2 pixel{800.0 + 400.0 * std::sin(1.3 * i),
                             std::min(880.0, 520.0 + 200.0 * std::cos(0.7 * i) + 60.0 * down)};
      const glm::dvec3 direction = glm::normalize(view.unprojectPixel(pixel, 0.5) - origin);
      hit = firstSolidAlongRay(finest, origin, direction, view.clip.farM);
    }
    if (!hit) continue;
    // Strokes alternate: carve, add rock, carve, add soil.
    const StackMaterial material = i % 2 == 0 ? kAir : (i % 4 == 1 ? kStackRock : kStackSoil);
    const SphereEdit edit{hit->x, hit->y, hit->z, radiusM, material};
    Result<StackRegion> region = applySphereEdit(finest, edit);
    if (!region || region->empty()) continue;
    strokes.push_back({frame, edit});
  }
  return strokes;
}

Result<PathRun> runEditedGroundTruth(std::vector<StackTerrain> pyramid,
                                     const std::vector<ScriptedStackEdit>& strokes,
                                     const std::vector<Camera>& cameras, const Aabb& bounds,
                                     const PathRunOptions& options,
                                     const RendererSettings& settings) {
  RendererInputs inputs;
  inputs.stacks = &pyramid;
  Progress progress("ground truth (stacks-full, edited)", cameras.size());
  std::optional<PathRun> whole;
  std::size_t next = 0;
  for (std::size_t first = 0; first < cameras.size();) {
    // The strokes due by this frame, then the frames up to the next stroke.
    while (next < strokes.size() && strokes[next].frame <= int(first)) {
      Result<StackRegion> region = applySphereEdit(pyramid.front(), strokes[next++].edit);
      if (!region) return region.error();
    }
    const std::size_t end =
        next < strokes.size() ? std::max(first + 1, std::size_t(strokes[next].frame)) : cameras.size();
    Result<std::unique_ptr<TerrainRenderer>> truth = makeRenderer("stacks-full", inputs, settings);
    if (!truth) return truth.error();
    PathRunOptions segment = options;
    segment.warmupFrames = 0;
    segment.keepFrames.clear();
    const std::vector<Camera> part(cameras.begin() + std::ptrdiff_t(first),
                                   cameras.begin() + std::ptrdiff_t(end));
    Result<PathRun> run = runDepthTruthPath(*truth.value(), part, bounds, segment, nullptr, {},
                                            [&](int) { progress.advance(); });
    if (!run) return run.error();
    if (whole) {
      whole->append(std::move(run.value()));
    } else {
      whole = std::move(run.value());
    }
    first = end;
  }
  return std::move(*whole);
}

void StrokeTimings::report(const PathRun& run) const {
  if (editMs.empty()) return;
  std::vector<double> total, edit = editMs;
  for (std::size_t i = 0; i < editMs.size(); ++i) {
    total.push_back(editMs[i] + run.frames[std::size_t(frames[i])].frameMs);
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  std::uint64_t cracks = 0;
  for (const int frame : frames) cracks += run.frames[std::size_t(frame)].crackPixels;
  spdlog::info("{}: {} brush strokes; stroke to updated mesh (the edit, then the frame that draws "
               "it) median {:.1f} ms, max {:.1f} ms; the edit alone median {:.1f} ms; {} meshes "
               "remade a stroke (median); {} crack pixels in the frames with a stroke",
               run.algo, editMs.size(), median(total), *std::max_element(total.begin(), total.end()),
               median(edit), std::size_t(median(std::vector<double>(meshes.begin(), meshes.end()))),
               cracks);
  std::vector<double> made;
  for (const int frame : frames) made.push_back(double(run.frames[std::size_t(frame)].stats.tilesLoaded));
  spdlog::info("{}: the edit's parts (medians): stacks and MipMap {:.1f} ms, levels quantised "
               "{:.1f} ms, uploaded {:.1f} ms; the frame drawing a stroke made {} meshes (median)",
               run.algo, median(stacksMs), median(levelsMs), median(uploadMs),
               std::size_t(median(made)));
}

std::function<void(int)> applyStrokesBeforeFrames(TerrainRenderer& renderer,
                                                  const std::vector<ScriptedStackEdit>& strokes,
                                                  StrokeTimings& timings) {
  return [&renderer, &strokes, &timings, next = std::size_t(0)](int frame) mutable {
    auto* lod = dynamic_cast<StacksLodRenderer*>(&renderer);
    while (next < strokes.size() && strokes[next].frame <= frame) {
      Result<StacksEditReport> report = lod->applyEdit(strokes[next++].edit);
      if (!report || report->region.empty()) continue;
      timings.editMs.push_back(report->editMs);
      timings.stacksMs.push_back(report->stacksMs);
      timings.levelsMs.push_back(report->levelsMs);
      timings.uploadMs.push_back(report->uploadMs);
      timings.meshes.push_back(double(report->meshesDropped));
      timings.frames.push_back(frame);
    }
  };
}

}  // namespace tellus::cli
