// tellus render --path P --video FILE: one renderer flown along a camera path, every frame
// encoded into a video at the path's own timing (30 frames a second of path time unless
// --frames says how many). The frames are drawn by the bench's path runner (no metrics are
// printed), so a video shows exactly what `tellus bench` measures along the same path.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_support.hpp"
#include "global_store_cli.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/progress.hpp"

namespace tellus::cli {

int runRenderAlongPath(const BenchPathOptions& o, const LookOptions& look) {
  if (o.video.file.empty()) {
    return fail(makeError("render --path draws a flight: give --video FILE (.mp4, .mkv, .mov or .webm)"));
  }
  if (o.algos.find(',') != std::string::npos) {
    return fail(makeError("render --path draws one renderer; bench --video draws several"));
  }
  Result<std::pair<int, int>> size = parseImageSize(o.size);
  if (!size) return fail(size.error());
  const std::vector<std::string> algos{o.algos};
  if (Status s = checkRendererInput(o.algos, o.dem, o.renderers); !s) return fail(s.error());
  if (!rendererDrawsGlobe(o.algos) && (!o.target.empty() || !o.geoid.empty())) {
    return fail(makeError("--target and --geoid are for globe renderers (--algo globe-reference)"));
  }
  Result<std::shared_ptr<PathVideoRecorder>> video = PathVideoRecorder::create(o.video, algos, size->first, size->second);
  if (!video) return fail(video.error());
  Result<std::unique_ptr<gl::GlContext>> context = createContext("headless");
  if (!context) return fail(context.error());
  PathRunOptions options;
  options.width = size->first;
  options.height = size->second;
  options.warmupFrames = 0;
  options.samples = look.samples;
  options.settings = renderSettingsOf(look);
  options.frameSink = video.value()->sink();
  Result<std::vector<PathRun>> runs = runAlongPath(o, options, {BenchEntry{o.algos, o.algos, o.renderers}});
  if (!runs) return fail(runs.error());
  Result<std::vector<std::filesystem::path>> written = video.value()->finish();
  if (!written) return fail(written.error());
  const PathRun& run = runs->front();
  fmt::print("{}: {} frames of {} along '{}', {} x {}\n", o.video.file, run.frames.size(), run.algo,
             pathInWorld(o.path, rendererDrawsGlobe(run.algo)),
             size->first, size->second);
  return 0;
}

}  // namespace tellus::cli
