#include "tellus/eval/bench_report.hpp"

#include <algorithm>
#include <map>
#include <variant>

#include "tellus/eval/geo_camera_path.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace tellus {
using nlohmann::json;

namespace {

template <typename F>
Distribution distributionOver(const PathRun& run, F&& field) {
  std::vector<double> values;
  for (const FrameRecord& f : run.frames) values.push_back(double(field(f)));
  return distributionOf(std::move(values));
}

}  // namespace

json summariseRun(const PathRun& run, bool quality) {
  const Distribution frame = distributionOver(run, [](const FrameRecord& f) { return f.frameMs; });
  double triangles = 0.0, milliseconds = 0.0;
  for (const FrameRecord& f : run.frames) {
    triangles += double(f.stats.triangles);
    milliseconds += f.frameMs;
  }
  std::uint64_t misses = 0, loads = 0, truncated = 0;
  for (const FrameRecord& f : run.frames) {
    misses += f.stats.cacheMisses;
    loads += f.stats.tilesLoaded;
    truncated += f.stats.truncated ? 1 : 0;
  }
  const auto fps = [](double ms) { return ms > 0.0 ? 1000.0 / ms : 0.0; };
  json s = {
      {"frames", run.frames.size()},
      {"fps_median", fps(frame.median)},
      {"fps_min", fps(frame.max)},
      {"fps_max", fps(frame.min)},
      {"cpu_ms_median",
       distributionOver(run, [](const FrameRecord& f) { return f.cpuLodMs + f.cpuSubmitMs; })
           .median},
      {"cache_misses_total", misses},
      {"tiles_loaded_total", loads},
      {"truncated_frames", truncated},
      {"frame_ms_median", frame.median},
      {"frame_ms_min", frame.min},
      {"frame_ms_max", frame.max},
      {"frame_ms_p95", frame.p95},
      {"frame_ms_p99", frame.p99},
      {"cpu_lod_ms_median",
       distributionOver(run, [](const FrameRecord& f) { return f.cpuLodMs; }).median},
      {"cpu_lod_ms_max", distributionOver(run, [](const FrameRecord& f) { return f.cpuLodMs; }).max},
      {"cpu_lod_thread_ms_median",
       distributionOver(run, [](const FrameRecord& f) { return f.cpuLodThreadMs; }).median},
      {"cpu_lod_thread_ms_max",
       distributionOver(run, [](const FrameRecord& f) { return f.cpuLodThreadMs; }).max},
      {"cpu_thread_ms_median",
       distributionOver(run, [](const FrameRecord& f) { return f.cpuLodThreadMs + f.cpuSubmitThreadMs; })
           .median},
      {"cpu_thread_ms_p99",
       distributionOver(run, [](const FrameRecord& f) { return f.cpuLodThreadMs + f.cpuSubmitThreadMs; })
           .p99},
      {"background_cpu_ms_median",
       distributionOver(run, [](const FrameRecord& f) { return f.stats.backgroundCpuMs; }).median},
      {"background_cpu_ms_max",
       distributionOver(run, [](const FrameRecord& f) { return f.stats.backgroundCpuMs; }).max},
      {"cpu_submit_ms_median",
       distributionOver(run, [](const FrameRecord& f) { return f.cpuSubmitMs; }).median},
      {"gpu_ms_median", distributionOver(run, [](const FrameRecord& f) { return f.gpuMs; }).median},
      {"triangles_median",
       distributionOver(run, [](const FrameRecord& f) { return f.stats.triangles; }).median},
      {"draw_calls_median",
       distributionOver(run, [](const FrameRecord& f) { return f.stats.drawCalls; }).median},
      {"gpu_waits_median",
       distributionOver(run, [](const FrameRecord& f) { return f.stats.gpuWaits; }).median},
      {"gpu_waits_max",
       distributionOver(run, [](const FrameRecord& f) { return f.stats.gpuWaits; }).max},
      {"mtris_per_s", milliseconds > 0.0 ? triangles / milliseconds / 1e3 : 0.0},
  };
  // Renderers that stream textures (textureUpdateMs >= 0): the update's mean and max.
  double updateSum = 0.0, updateMax = 0.0;
  std::size_t updates = 0;
  for (const FrameRecord& f : run.frames) {
    if (f.stats.textureUpdateMs < 0.0) continue;
    updateSum += f.stats.textureUpdateMs;
    updateMax = std::max(updateMax, f.stats.textureUpdateMs);
    ++updates;
  }
  if (updates > 0) {
    s["texture_update_ms_mean"] = updateSum / double(updates);
    s["texture_update_ms_max"] = updateMax;
    s["texture_update_ms_median"] =
        distributionOver(run, [](const FrameRecord& f) { return std::max(0.0, f.stats.textureUpdateMs); })
            .median;
  }
  // Draped imagery: memory against its budget, uploads a frame, texel density on screen.
  std::vector<const FrameRecord*> draped;
  for (const FrameRecord& f : run.frames) {
    if (f.imagery) draped.push_back(&f);
  }
  if (!draped.empty()) {
    std::uint64_t residentMax = 0, uploadBytesMax = 0;
    int uploadsMax = 0, unplaceableMax = 0;
    std::vector<double> p50, p95, update;
    for (const FrameRecord* f : draped) {
      residentMax = std::max(residentMax, f->imagery->residentBytes);
      uploadBytesMax = std::max(uploadBytesMax, f->imagery->uploadBytes);
      uploadsMax = std::max(uploadsMax, f->imagery->uploads);
      unplaceableMax = std::max(unplaceableMax, f->imagery->unplaceable);
      if (f->imagery->texelPxP50 > 0.0) p50.push_back(f->imagery->texelPxP50);
      if (f->imagery->texelPxP95 > 0.0) p95.push_back(f->imagery->texelPxP95);
      update.push_back(f->imagery->updateMs);
    }
    s["imagery_budget_bytes"] = draped.back()->imagery->budgetBytes;
    s["imagery_resident_bytes_max"] = residentMax;
    s["imagery_uploads_max"] = uploadsMax;
    s["imagery_upload_bytes_max"] = uploadBytesMax;
    s["imagery_unplaceable_max"] = unplaceableMax;
    s["imagery_pending_last"] = draped.back()->imagery->pending;
    s["imagery_texel_px_p50"] = distributionOf(p50).median;
    s["imagery_texel_px_p95"] = distributionOf(p95).median;
    s["imagery_update_ms_median"] = distributionOf(update).median;
    s["imagery_update_ms_max"] = distributionOf(update).max;
  }
  // The renderer's own stages (FrameStats::stageMs): each one's median
  // and max over the frames that report it, as <stage>_ms_median and <stage>_ms_max.
  std::map<std::string, std::vector<double>> stages;
  for (const FrameRecord& f : run.frames) {
    for (const auto& [stage, ms] : f.stats.stageMs) stages[stage].push_back(ms);
  }
  for (auto& [stage, values] : stages) {
    const Distribution d = distributionOf(std::move(values));
    s[stage + "_ms_median"] = d.median;
    s[stage + "_ms_max"] = d.max;
  }
  if (quality) {
    std::uint64_t cracks = 0, silhouette = 0;
    json crackFrames = json::array();
    for (const FrameRecord& f : run.frames) {
      cracks += f.crackPixels;
      silhouette += f.silhouettePixels;
      if (f.crackPixels > 0) crackFrames.push_back(f.index);
    }
    s["sse_px_mean"] = run.errors.mean();
    s["sse_px_p95"] = run.errors.percentile(0.95);
    s["sse_px_p99"] = run.errors.percentile(0.99);
    s["sse_px_max"] = run.errors.max;
    s["pop_px_mean"] = run.popping.mean();
    s["pop_px_p99"] = run.popping.percentile(0.99);
    s["pop_px_max"] = run.popping.max;
    s["pop_px_p99_frame_max"] =
        distributionOver(run, [](const FrameRecord& f) { return f.popPxP99; }).max;
    s["crack_pixels_total"] = cracks;
    s["crack_frames"] = crackFrames;
    s["silhouette_pixels_total"] = silhouette;
  }
  return s;
}

json benchReportJson(const BenchContext& c, const std::vector<PathRun>& runs,
                     const std::vector<json>& keptFrameFiles) {
  json algorithms = json::array();
  for (const PathRun& run : runs) {
    json frames = json::array();
    for (const FrameRecord& f : run.frames) {
      json row = {{"index", f.index},
                  {"camera", fmt::format("{:.3f},{:.3f},{:.3f},{:.4f},{:.4f},{:.3f}",
                                         f.camera.position.x, f.camera.position.y,
                                         f.camera.position.z, f.camera.yawDeg,
                                         f.camera.pitchDeg, f.camera.fovYDeg)},
                  {"frame_ms", f.frameMs},
                  {"cpu_lod_ms", f.cpuLodMs},
                  {"cpu_lod_thread_ms", f.cpuLodThreadMs},
                  {"cpu_submit_ms", f.cpuSubmitMs},
                  {"cpu_submit_thread_ms", f.cpuSubmitThreadMs},
                  {"gpu_ms", f.gpuMs},
                  {"triangles", f.stats.triangles},
                  {"vertices", f.stats.vertices},
                  {"draw_calls", f.stats.drawCalls},
                  {"tiles_loaded", f.stats.tilesLoaded},
                  {"background_cpu_ms", f.stats.backgroundCpuMs},
                  {"upload_bytes", f.stats.uploadBytes},
                  {"cache_misses", f.stats.cacheMisses},
                  {"gpu_waits", f.stats.gpuWaits}};
      if (f.stats.textureUpdateMs >= 0.0) row["texture_update_ms"] = f.stats.textureUpdateMs;
      for (const auto& [stage, ms] : f.stats.stageMs) row[stage + "_ms"] = ms;
      if (f.imagery) {
        row["imagery_update_ms"] = f.imagery->updateMs;
        row["imagery_uploads"] = f.imagery->uploads;
        row["imagery_upload_bytes"] = f.imagery->uploadBytes;
        row["imagery_resident_bytes"] = f.imagery->residentBytes;
        row["imagery_pending"] = f.imagery->pending;
        row["imagery_texel_px_p50"] = f.imagery->texelPxP50;
        row["imagery_texel_px_p95"] = f.imagery->texelPxP95;
      }
      // Globe paths: the geo camera render --geo-camera takes (camera holds ECEF there).
      if (f.geoCamera) row["geo_camera"] = formatGeoCamera(*f.geoCamera);
      if (c.quality) {
        row["sse_px_mean"] = f.ssePxMean;
        row["sse_px_p95"] = f.ssePxP95;
        row["sse_px_p99"] = f.ssePxP99;
        row["sse_px_max"] = f.ssePxMax;
        row["crack_pixels"] = f.crackPixels;
        row["silhouette_pixels"] = f.silhouettePixels;
        row["pop_px_mean"] = f.popPxMean;
        row["pop_px_p99"] = f.popPxP99;
        row["pop_px_max"] = f.popPxMax;
        row["pop_pixels"] = f.popPixels;
      }
      frames.push_back(row);
    }
    json options = json::object();
    for (const auto& [name, value] : run.options) {
      std::visit([&](const auto& v) { options[name] = v; }, value);
    }
    json algorithm = {{"algo", run.algo},
                      {"options", options},
                      {"summary", summariseRun(run, c.quality)},
                      {"frames", frames}};
    if (c.quality) {
      json bins = json::array();
      for (std::size_t b = 0; b < run.errors.counts.size(); ++b) {
        if (run.errors.counts[b]) bins.push_back({b, run.errors.counts[b]});
      }
      algorithm["error_histogram"] = {
          {"bin_px", ErrorHistogram::kBinPx},
          {"overflow_from_px", ErrorHistogram::kBinPx * ErrorHistogram::kBins},
          {"bins", bins}};
    }
    algorithms.push_back(algorithm);
  }
  return {{"machine",
           {{"cpu", c.cpu},
            {"hardware_threads", c.hardwareThreads},
            {"gl_vendor", c.glVendor},
            {"gl_renderer", c.glRenderer},
            {"gl_version", c.glVersion}}},
          {"inputs", c.inputs},
          {"path", c.path},
          {"frames", c.frames},
          {"warmup_frames", c.warmup},
          {"size", {c.width, c.height}},
          {"quality", c.quality},
          {"frame_ms_definition", "max(cpu_lod_ms + cpu_submit_ms, gpu_ms)"},
          {"algorithms", algorithms},
          {"kept_frames", keptFrameFiles}};
}

std::string benchReportCsv(const std::vector<PathRun>& runs, bool quality) {
  std::string csv =
      "algo,frame,frame_ms,cpu_lod_ms,cpu_submit_ms,gpu_ms,triangles,vertices,draw_calls,"
      "tiles_loaded,cache_misses,background_cpu_ms,upload_bytes,cpu_lod_thread_ms,gpu_waits";
  csv += quality ? ",sse_px_mean,sse_px_p95,sse_px_p99,sse_px_max,crack_pixels,pop_px_p99\n"
                 : "\n";
  for (const PathRun& run : runs) {
    for (const FrameRecord& f : run.frames) {
      csv += fmt::format("{},{},{:.4f},{:.4f},{:.4f},{:.4f},{},{},{},{},{},{:.4f},{},{:.4f},{}",
                         run.algo, f.index, f.frameMs, f.cpuLodMs, f.cpuSubmitMs, f.gpuMs,
                         f.stats.triangles, f.stats.vertices, f.stats.drawCalls,
                         f.stats.tilesLoaded, f.stats.cacheMisses, f.stats.backgroundCpuMs,
                         f.stats.uploadBytes, f.cpuLodThreadMs, f.stats.gpuWaits);
      csv += quality ? fmt::format(",{:.4f},{:.4f},{:.4f},{:.4f},{},{:.4f}\n", f.ssePxMean,
                                   f.ssePxP95, f.ssePxP99, f.ssePxMax, f.crackPixels, f.popPxP99)
                     : "\n";
    }
  }
  return csv;
}

std::string benchReportTable(const BenchContext& c, const std::vector<PathRun>& runs) {
  std::string out = fmt::format(
      "path {} ({} frames after {} warm-up), {}x{}, {} on {}\n"
      "frame ms = max(CPU LOD + submit, GPU) (with --finish: prepare to glFinish's return);\n"
      "FPS = 1000 / frame ms; CPU all = LOD + submit;\n"
      "LOD max = the render thread's slowest prepare; CPU bg = background threads' CPU a frame\n"
      "(loads, reorganisation); misses = tiles wanted but not resident, summed over the frames;\n"
      "waits = calls that made the render thread wait for the GPU a frame, median/max (0 is right)\n"
      "medians unless said\n\n",
      c.path, c.frames, c.warmup, c.width, c.height, c.glRenderer, c.cpu);
  out += fmt::format(
      "{:<22} {:>9} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>6} {:>10} {:>8} {:>7} {:>7}",
      "algo", "frame ms", "FPS min", "FPS med", "FPS max", "CPU LOD", "LOD max", "CPU all",
      "CPU bg", "GPU ms", "draws", "triangles", "Mtris/s", "misses", "waits");
  if (c.quality)
    out += fmt::format(" {:>9} {:>9} {:>9} {:>9} {:>8} {:>8}", "SSE mean", "SSE p95", "SSE p99",
                       "SSE max", "cracks", "pop p99");
  out += "\n";
  for (const PathRun& run : runs) {
    const json s = summariseRun(run, c.quality);
    out += fmt::format(
        "{:<22} {:>9.2f} {:>8.1f} {:>8.1f} {:>8.1f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>9.2f} "
        "{:>6.0f} {:>10.0f} {:>8.1f} {:>7} {:>7}",
        run.algo, s["frame_ms_median"].get<double>(), s["fps_min"].get<double>(),
        s["fps_median"].get<double>(), s["fps_max"].get<double>(),
        s["cpu_lod_ms_median"].get<double>(), s["cpu_lod_ms_max"].get<double>(),
        s["cpu_ms_median"].get<double>(), s["background_cpu_ms_median"].get<double>(),
        s["gpu_ms_median"].get<double>(), s["draw_calls_median"].get<double>(),
        s["triangles_median"].get<double>(), s["mtris_per_s"].get<double>(),
        s["cache_misses_total"].get<std::uint64_t>(),
        fmt::format("{:.0f}/{:.0f}", s["gpu_waits_median"].get<double>(),
                    s["gpu_waits_max"].get<double>()));
    if (c.quality) {
      out += fmt::format(" {:>9.3f} {:>9.3f} {:>9.3f} {:>9.2f} {:>8} {:>8.3f}",
                         s["sse_px_mean"].get<double>(), s["sse_px_p95"].get<double>(),
                         s["sse_px_p99"].get<double>(), s["sse_px_max"].get<double>(),
                         s["crack_pixels_total"].get<std::uint64_t>(),
                         s["pop_px_p99"].get<double>());
    }
    out += "\n";
  }
  return out;
}

}  // namespace tellus
