#pragma once
// The report of `tellus bench`: per algorithm a summary and the per-frame rows, as JSON and CSV,
// and a table readable on its own.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "tellus/eval/path_benchmark.hpp"

namespace tellus {

struct BenchContext {
  std::string cpu;
  unsigned hardwareThreads = 0;
  std::string glVendor, glRenderer, glVersion;
  std::vector<std::string> inputs;
  std::string path;
  int frames = 0, warmup = 0, width = 0, height = 0;
  bool quality = false;
};

// Summary fields: frame_ms_{median,min,max,p95,p99}, cpu_lod_ms_median, cpu_submit_ms_median,
// gpu_ms_median, triangles_median, mtris_per_s; with quality sse_px_{mean,p95,p99,max},
// crack_pixels_total, crack_frames, pop_px_{mean,p99,max} (over all pixels of all frames) and
// pop_px_p99_frame_max (the worst frame's p99).
nlohmann::json summariseRun(const PathRun& run, bool quality);
nlohmann::json benchReportJson(const BenchContext& context, const std::vector<PathRun>& runs,
                               const std::vector<nlohmann::json>& keptFrameFiles);
std::string benchReportCsv(const std::vector<PathRun>& runs, bool quality);
std::string benchReportTable(const BenchContext& context, const std::vector<PathRun>& runs);

}  // namespace tellus
