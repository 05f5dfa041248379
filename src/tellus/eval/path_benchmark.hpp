#pragma once
// Runs a renderer along a camera path and measures every frame: CPU time of LOD selection
// (prepare) and of submission (draw), GPU time (GL_TIME_ELAPSED, read back without stalling),
// what was drawn, and with `quality` the screen-space error against the full-resolution
// heights and the cracks against a reference coverage. Needs a current GL context.
//
// Frame time: a pipelined renderer is bound by the slower of CPU and GPU, so
// frame_ms = max(cpu_lod_ms + cpu_submit_ms, gpu_ms). (There is no swap chain headless.)
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/eval/frame_metrics.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/render/imagery/imagery_textures.hpp"
#include "tellus/render/registry/renderer_option.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

// A recorded frame's picture, handed to PathRunOptions::frameSink (bench --video).
struct FrameImage {
  std::string_view algo;  // the renderer's name
  int index = 0;          // frame along the path
  double timeS = 0.0;     // index * intervalS
  double intervalS = 0.0; // PathRunOptions::frameIntervalS
  const RgbImage& image;
};

struct PathRunOptions {
  int width = 1280;
  int height = 720;
  int warmupFrames = 3;  // drawn before the path, not recorded
  int samples = 1;       // MSAA samples a pixel (pictures for a video); quality runs use 1
  bool quality = false;
  // Each frame ends with glFinish and its frame time is the wall time from prepare() to the
  // GPU's end: the whole frame, serialised. For drivers whose timer queries miss work
  // (llvmpipe shades fragments on its own threads after the query has ended).
  bool finishFrames = false;
  RenderSettings settings;
  // Frames whose images are kept (for a contact sheet); the first 8 frames with cracks also
  // keep an image with the cracks marked.
  std::vector<int> keepFrames;
  // Quality runs: keep every frame's depth image in PathRun::depths (a ground-truth run whose
  // depths judge the others on 3D terrain: PathTruth::depths).
  bool recordDepths = false;
  // Called before each recorded frame is prepared, with its index (outside the frame's
  // timing): scripted changes to the scene, such as brush strokes.
  std::function<void(int)> beforeFrame;
  // Called with every recorded frame's picture, read back after the frame's timing as kept
  // frames are (a quality run's sentinel background shown as sky); an error stops the run.
  std::function<Status(const FrameImage&)> frameSink;
  // Seconds between recorded frames along the path (its duration over frames - 1), for the
  // frame times FrameImage carries.
  double frameIntervalS = 1.0 / 30.0;
};

// Per-pixel terrain coverage of the reference render of each frame (1 = terrain), needed for
// crack detection. Produced by a reference run (PathRun::coverage) or supplied.
using CoverageMasks = std::vector<std::vector<std::uint8_t>>;

struct FrameRecord {
  int index = 0;
  Camera camera;  // the frame's camera (to reproduce one frame with render --camera)
  // On the globe: the frame's geo camera (render --geo-camera), set by the caller.
  std::optional<GeoCamera> geoCamera;
  double cpuLodMs = 0.0;
  // The render thread's CPU time in prepare() (its thread clock): cpuLodMs without the time the
  // thread waited or was preempted (two cores shared with llvmpipe and the workers).
  double cpuLodThreadMs = 0.0;
  double cpuSubmitMs = 0.0;
  // The render thread's CPU time in draw() (its thread clock): on a GPU the renderer's and the
  // driver's submission work; on llvmpipe also the vertex processing it does on this thread.
  double cpuSubmitThreadMs = 0.0;
  double gpuMs = -1.0;  // -1 when the driver returned nothing
  double finishedMs = 0.0;  // with finishFrames: prepare() to glFinish's return
  double frameMs = 0.0;
  FrameStats stats;
  // With draped imagery (RenderSettings::imagery): its update before the frame (timed apart
  // from the renderer's CPU LOD) and what the last feedback said.
  std::optional<ImageryPagingInfo> imagery;
  // With quality:
  double ssePxMean = 0.0, ssePxP95 = 0.0, ssePxP99 = 0.0, ssePxMax = 0.0;
  std::uint64_t ssePixels = 0;
  std::uint64_t crackPixels = 0;
  std::uint64_t silhouettePixels = 0;  // sky where the reference has terrain, open to the sky
  // Popping (measurePopping): how far the surface jumps on screen between the previous frame's
  // level of detail and this frame's, both seen from this frame's camera. 0 with no pixels for
  // renderers whose geometry never depends on the view.
  double popPxMean = 0.0, popPxP99 = 0.0, popPxMax = 0.0;
  std::uint64_t popPixels = 0;
};

// Percentiles of a per-frame quantity.
struct Distribution {
  double median = 0.0, min = 0.0, max = 0.0, p95 = 0.0, p99 = 0.0, mean = 0.0;
};
Distribution distributionOf(std::vector<double> values);

// Screen-space errors pooled over all pixels of all frames, as a histogram (0.01 px bins up
// to 64 px, the rest in an overflow bin) so that path percentiles are exact to 0.01 px.
struct ErrorHistogram {
  static constexpr double kBinPx = 0.01;
  static constexpr int kBins = 6400;
  std::vector<std::uint64_t> counts = std::vector<std::uint64_t>(kBins + 1, 0);
  double sum = 0.0;
  double max = 0.0;
  std::uint64_t total = 0;
  void add(float errorPx);
  void merge(const ErrorHistogram& other);
  double percentile(double p) const;
  double mean() const { return total ? sum / double(total) : 0.0; }
};

struct KeptFrame {
  int index = 0;
  RgbImage image;
  RgbImage cracksMarked;  // empty unless the frame had cracks
  RgbImage errors;        // quality runs: screen-space error, green 0 px to red >= 10 px
};

struct PathRun {
  std::string algo;
  // The renderer's options as it ran, by name ("rag-coarse"): its family's schema.
  std::map<std::string, OptionValue> options;
  std::vector<FrameRecord> frames;
  ErrorHistogram errors;
  ErrorHistogram popping;  // per-pixel popping over all frames (quality runs)
  CoverageMasks coverage;  // this run's own coverage (quality runs only)
  std::vector<DepthImage> depths;  // with PathRunOptions::recordDepths
  std::vector<KeptFrame> kept;
  // Appends a run of the same renderer over the frames that follow (frame and kept indices
  // shifted by this run's frame count).
  void append(PathRun&& later);
};

// What a path is measured against: the true surface (frame_metrics.hpp: the flat world's
// full-resolution mesh, or the globe's, globe_surface.hpp) and how each frame's settings are
// fitted to its view (may be empty).
//
// 3D terrain (material stacks) has no true point at a ground position: its truth is the ground-
// truth renderer's depth image of every frame (`depths`), and the screen-space error and the
// popping are measureDepthTruthError's (depth_truth_error.hpp). A run with neither `surface` nor `depths` is the ground
// truth itself (its error is 0 by definition, measured as such).
struct PathTruth {
  TrueSurfaceFn surface;
  const std::vector<DepthImage>* depths = nullptr;
  std::function<void(const ViewSetup&, RenderSettings&)> fitSettings;
};

// Runs the renderer through ready-made views (the globe's come from geo cameras).
Result<PathRun> runViews(TerrainRenderer& renderer, const std::vector<ViewSetup>& views,
                         const PathTruth& truth, const PathRunOptions& options,
                         const CoverageMasks& referenceCoverage = {},
                         const std::function<void(int)>& onFrame = nullptr);

// The flat world: views from `cameras` over `truth`, measured against its mesh.
// `referenceCoverage` (one mask per camera) is used for crack detection; when empty and
// `quality` is set, the run uses its own coverage (a reference run judging itself).
Result<PathRun> runPath(TerrainRenderer& renderer, const std::vector<Camera>& cameras,
                        const HeightGrid& truth, const PathRunOptions& options,
                        const CoverageMasks& referenceCoverage = {},
                        const std::function<void(int)>& onFrame = nullptr);

// 3D terrain: views from `cameras` in `bounds`, measured against `truthDepths` (one per camera;
// null: this run is the ground truth), cracks against `referenceCoverage` as for runPath.
Result<PathRun> runDepthTruthPath(TerrainRenderer& renderer, const std::vector<Camera>& cameras,
                                  const Aabb& bounds, const PathRunOptions& options,
                                  const std::vector<DepthImage>* truthDepths,
                                  const CoverageMasks& referenceCoverage = {},
                                  const std::function<void(int)>& onFrame = nullptr);

}  // namespace tellus
