#include "tellus/viewer/viewer_panel.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <imgui.h>

#include "tellus/eval/renderer_registry.hpp"

namespace tellus {
namespace {

// Text from fmt, without ImGui's printf-style formatting.
template <typename... Args>
void text(fmt::format_string<Args...> format, Args&&... args) {
  const std::string line = fmt::format(format, std::forward<Args>(args)...);
  ImGui::TextUnformatted(line.c_str());
}

std::string countText(std::uint64_t n) {
  if (n >= 10'000'000) return fmt::format("{:.1f} M", double(n) / 1e6);
  if (n >= 10'000) return fmt::format("{:.1f} k", double(n) / 1e3);
  return fmt::format("{}", n);
}

// RAG's parameters. True when the renderer must be made again (sliders: when released).
// Sliders whose new value takes effect on release (the caller remakes the renderer): true on
// the frame the user lets go after a change.
bool intSliderOnRelease(const char* label, int* value, int low, int high,
                        const char* format = "%d") {
  ImGui::SliderInt(label, value, low, high, format);
  return ImGui::IsItemDeactivatedAfterEdit();
}
bool doubleSliderOnRelease(const char* label, double& value, float low, float high,
                           const char* format) {
  float shown = float(value);
  ImGui::SliderFloat(label, &shown, low, high, format);
  value = shown;
  return ImGui::IsItemDeactivatedAfterEdit();
}

// ROAM's parameters: the target and budgets take effect in the next frame (the bintree adapts
// to them incrementally); the block size remakes the renderer.
bool roamSection(ViewerState& state) {
  roam::RoamSettings& s = state.roam.settings;
  bool recreate = false;
  ImGui::SliderFloat("error target (px)", &s.targetPx, 0.1f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  int budget = int(s.triangleBudget);
  ImGui::SliderInt("triangle budget", &budget, 1000, 4'000'000, "%d", ImGuiSliderFlags_Logarithmic);
  s.triangleBudget = std::uint32_t(budget);
  float timeMs = float(s.timeBudgetMs);
  ImGui::SliderFloat("time budget (ms, 0: none)", &timeMs, 0.0f, 50.0f, "%.1f");
  s.timeBudgetMs = timeMs;
  recreate |= intSliderOnRelease("block (2^N cells)", &s.blockLog2, 4, 9);
  if (state.roamFrame) {
    const roam::RoamFrameReport& r = *state.roamFrame;
    text("leaves {}, diamonds {}", countText(r.leaves), countText(r.diamonds));
    text("splits {}, merges {}, re-prioritised {}", r.splits, r.merges, countText(r.reprioritised));
    text("priorities {:.2f} ms, splits/merges {:.2f} ms", r.priorityMs, r.queueMs);
    text("top of split queue {:.2f} px{}{}", r.maxSplitPriorityPx, r.budgetReached ? ", budget reached" : "",
         r.timeReached ? ", time reached" : "");
    text("error bounds {:.1f} MB", double(state.roamBoundsBytes) / 1e6);
  }
  return recreate;
}

// GAMeR's parameters: the target applies from the next frame; the pattern depth and culling
// remake the renderer (its pool and coarse mesh).
bool gamerSection(ViewerState& state) {
  gamer::GamerSettings& s = state.gamer.settings;
  bool recreate = false;
  ImGui::SliderFloat("error target (px)", &s.targetPx, 0.1f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  recreate |= intSliderOnRelease("pattern depth (2^N segments)", &s.maxDepth, 2, gamer::kMaxPatternDepth);
  recreate |= ImGui::Checkbox("frustum culling", &s.culling);
  if (state.gamerFrame) {
    const gamer::Selection& f = *state.gamerFrame;
    std::size_t used = 0;
    for (std::uint32_t n : f.instanceCount) used += n > 0 ? 1 : 0;
    text("coarse triangles {}, patterns in use {} of {}", countText(f.coarseTriangles), used, f.instanceCount.size());
    text("refined triangles {}", countText(f.triangles));
    text("pattern pool {:.1f} KiB", double(state.gamerPoolBytes) / 1024.0);
  }
  return recreate;
}

// BDAM's parameters: the target applies from the next frame; culling and the cache size remake
// the renderer (the patches stay in the file).
bool bdamSection(ViewerState& state) {
  BdamOptions& b = state.bdam;
  bool recreate = false;
  ImGui::SliderFloat("error target (px)", &b.selection.targetPx, 0.1f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  recreate |= ImGui::Checkbox("frustum culling", &b.selection.culling);
  recreate |= intSliderOnRelease("cache slots", &b.cacheSlots, 256, 65536);
  if (state.bdamFrame) {
    const BdamFrameInfo& f = *state.bdamFrame;
    text("patches drawn {}, read this frame {} ({:.2f} ms)", f.patches, f.loaded, f.loadMs);
    text("cache {} of {} slots", f.resident, f.slots);
  }
  return recreate;
}

// Geometry image warping's parameters: the slope weight applies from the next frame; the image
// size and the uniform share remake the renderer.
bool giwSection(ViewerState& state) {
  giw::GiwSettings& s = state.giw.settings;
  bool recreate = false;
  ImGui::SliderFloat("slope weight", &s.slopeWeight, 0.0f, 32.0f, "%.1f");
  recreate |= intSliderOnRelease("geometry image size", &s.size, 33, 1025);
  float share = s.uniformShare;
  ImGui::SliderFloat("uniform share", &share, 0.0f, 1.0f, "%.2f");
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    s.uniformShare = share;
    recreate = true;
  }
  if (state.giwFrame) {
    const auto& ms = *state.giwFrame;
    text("importance {:.2f} ms, warp {:.2f} ms, resample {:.2f} ms", ms[0], ms[1], ms[2]);
  }
  return recreate;
}

// The clipmaps' parameters; changes remake the renderer (its textures and footprints).
bool clipmapSection(ViewerState& state) {
  ClipmapOptions& c = state.clipmaps;
  bool recreate = false;
  int k = 0;
  while ((1 << (k + 1)) - 1 <= c.n) ++k;
  if (intSliderOnRelease("level size 2^k - 1", &k, 5, 10, "k = %d")) {
    c.n = (1 << k) - 1;
    recreate = true;
  }
  recreate |= intSliderOnRelease("levels (0: auto)", &c.levels, 0, 16);
  float width = c.transitionWidth;
  ImGui::SliderFloat("transition (0: n/5)", &width, 0.0f, float((c.n + 1) / 4) - 3.5f, "%.1f");
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    c.transitionWidth = width >= 1.0f ? width : 0.0f;
    recreate = true;
  }
  recreate |= ImGui::Checkbox("frustum culling", &c.culling);
  text("{} levels of {} x {} vertices", state.clipmapLevels, c.n, c.n);
  if (state.clipmapUploadSamples) {
    text("texture update: {} samples, {:.2f} ms", countText(*state.clipmapUploadSamples),
         std::max(0.0, state.stats.textureUpdateMs));
  }
  return recreate;
}

bool ragSection(ViewerState& state) {
  RagOptions& rag = state.rag;
  bool recreate = false;
  recreate |= intSliderOnRelease("coarse vertices", &rag.coarseVertices, 5, 160);
  recreate |= intSliderOnRelease(rag.adaptivePasses ? "most passes" : "passes", &rag.passes, 0,
                                 kRagMaxPasses);
  recreate |= ImGui::Checkbox("adaptive passes", &rag.adaptivePasses);
  recreate |= ImGui::Checkbox("align to samples", &rag.alignCoarseMesh);
  if (state.algo == "rag") {
    ImGui::SliderFloat("split at (px)", &rag.refinement.pixelEdge, 0.25f, 40.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
  } else {
    ImGui::SliderFloat("height difference (m)", &rag.refinement.heightDifferenceM, 0.0f, 500.0f,
                       "%.1f", ImGuiSliderFlags_Logarithmic);
    recreate |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SliderFloat("depth detail", &rag.refinement.depthDetail, 0.0f, 1.0f);
  }
  recreate |= ImGui::IsItemDeactivatedAfterEdit();
  recreate |= ImGui::Checkbox("early clipping", &rag.refinement.earlyClip);
  if (state.ragMapLevel > 0) {
    text("height map: level {} (beyond the texture limit), error {:.1f} m", state.ragMapLevel,
         state.ragMapErrorM);
  }
  if (state.ragFrame) {
    const RagPassCounts& counts = *state.ragFrame;
    for (int p = 0; p < counts.passes; ++p) {
      text("pass {}: {} triangles", p + 1, countText(counts.written[std::size_t(p)]));
    }
  }
  return recreate;
}

// Renderer choice and the parameters of the rings and RAG renderers. True when the renderer
// must be made again.
bool rendererSection(ViewerState& state) {
  bool recreate = false;
  if (ImGui::BeginCombo("renderer", state.algo.c_str())) {
    for (std::string_view name : rendererNames()) {
      const bool globe = rendererDrawsGlobe(name);
      const bool available = (!rendererNeedsStore(name) || state.hasStore) &&
                             (!rendererNeedsGlobalStore(name) || state.hasGlobalStore) &&
                             rendererNeedsStacks(name) == state.hasStacks && globe == state.globe;
      ImGui::BeginDisabled(!available);
      const std::string label(name);
      if (ImGui::Selectable(label.c_str(), name == state.algo) && name != state.algo) {
        state.algo = label;
        recreate = true;
      }
      ImGui::EndDisabled();
      if (!available && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
        ImGui::SetTooltip(globe != state.globe
                              ? (globe ? "draws on the globe: view a global store or a lat/lon "
                                         "DEM with --algo globe-reference"
                                       : "draws on the flat world: view a DEM or flat store")
                            : rendererNeedsStacks(name) != state.hasStacks
                                ? (state.hasStacks ? "draws heightfields: open a DEM or store"
                                                   : "draws material stacks: open a .tstack")
                            : rendererNeedsGlobalStore(name)
                                ? "streams from a global store: open one (build --global)"
                                : "streams from a tile store: open a .tstore");
      }
    }
    ImGui::EndCombo();
  }
  if (state.globe) {
    // What the globe is drawn with, when the session was given it.
    ImGui::BeginDisabled(!state.hasGeoid);
    recreate |= ImGui::Checkbox("geoid (heights above the ellipsoid)", &state.useGeoid);
    ImGui::EndDisabled();
    ImGui::BeginDisabled(!state.hasDrape);
    recreate |= ImGui::Checkbox("drape (colour map)", &state.useDrape);
    ImGui::EndDisabled();
    if (!state.hasGeoid) text("(--geoid FILE enables the geoid)");
    if (!state.hasDrape) text("(--drape FILE enables a colour map)");
  }
  if (state.algo == "rag" || state.algo == "rag-right") return recreate | ragSection(state);
  if (state.algo == "roam") return recreate | roamSection(state);
  if (state.algo == "clipmaps") return recreate | clipmapSection(state);
  if (state.algo == "gamer") return recreate | gamerSection(state);
  if (state.algo == "bdam") return recreate | bdamSection(state);
  if (state.algo == "giw") return recreate | giwSection(state);
  if (rendererNeedsStacks(state.algo)) {
    // The quadrangulation pipeline's parameters (seed 003, section 3.2); remade on release.
    QuadParams& q = state.stacks.quad;
    recreate |= intSliderOnRelease("node cells", &q.nodeCells, 5, 33);
    int filter = q.filter == SmoothingFilter::Box ? 1 : 0;
    if (ImGui::Combo("smoothing", &filter, "gauss\0box\0")) {
      q.filter = filter == 1 ? SmoothingFilter::Box : SmoothingFilter::Gauss;
      recreate = true;
    }
    recreate |= intSliderOnRelease("smoothing radius", &q.filterRadius, 0, 4);
    if (state.algo == "stacks") {
      // The octree needs an odd node size of at least 9 (nodes overlap by one cell).
      q.nodeCells = std::max(9, q.nodeCells | 1);
      recreate |= doubleSliderOnRelease("tau (px a cell)", state.stacks.tauPx, 1.0f, 40.0f, "%.1f");
      recreate |= doubleSliderOnRelease("error tau (px, 0: off)", state.stacks.errorTauPx, 0.0f,
                                        40.0f, "%.1f");
      recreate |=
          intSliderOnRelease("updates / frame (0: all)", &state.stacks.updatesPerFrame, 0, 200);
      recreate |= intSliderOnRelease("mesh pool MiB", &state.stacks.poolMiB, 16, 4096);
      recreate |= intSliderOnRelease("geomorph frames (0: off)", &state.stacks.morphFrames, 0, 30);
      if (state.stacksFrame) {
        const StacksLodFrame& f = *state.stacksFrame;
        text("{} nodes selected (levels {}..{}), {} drawn", f.selected, f.finestLevel,
             f.coarsestLevel, f.drawnNodes);
        text("{} quadrangulated this frame ({} forced), {:.1f} ms", f.quadrangulations, f.forced,
             f.quadMs);
        text("next selection: {} meshes missing, drawn one {} frames old", f.pendingMissing,
             f.framesBehind);
        text("{} nodes sliding between levels (geomorph)", f.morphing);
      }
      ImGui::Combo("brush material", &state.brushMaterial, "air\0rock\0soil\0grass\0");
      state.brushMaterial = std::max(state.brushMaterial, 1);
      ImGui::SliderFloat("brush radius (m)", &state.brushRadiusM, 1.0f, 100.0f, "%.1f");
      text("Ctrl + left click adds, Ctrl + right click carves");
      if (state.stackEdits > 0) {
        text("{} strokes; the last updated the stacks in {:.0f} ms, {} meshes remade",
             state.stackEdits, state.lastEditMs, state.lastEditMeshes);
      }
      return recreate;
    }
    text("{} nodes, {} quads, built in {:.2f} s", state.stackNodes, state.stackQuads,
         state.stackBuildS);
    return recreate;
  }
  if (state.algo == "ringo") {
    // RINGO's matrix and its streaming; remade on release.
    recreate |= intSliderOnRelease("rings", &state.ringo.rings, 0, 8);
    recreate |= doubleSliderOnRelease("blocks to horizon", state.ringo.blocksToHorizon, 1.0f,
                                      20.0f, "%.1f");
    recreate |= intSliderOnRelease("upload KiB / frame", &state.ringo.uploadKiBPerFrame, 64, 16384);
    recreate |= intSliderOnRelease("threads (0: all)", &state.ringo.threads, 0, 16);

    return recreate;
  }
  if (state.algo == "spiral") {
    // The seed's spiral parameters and modes; remade on release.
    SpiralOptions& s = state.spiral;
    static const int kSpinSteps[] = {1, 2, 3, 4, 5, 6, 8, 9, 10, 12, 15, 18, 20, 24, 30};
    if (ImGui::BeginCombo("spin step (deg)", fmt::format("{:g}", s.spinStepDeg).c_str())) {
      for (int step : kSpinSteps) {
        if (ImGui::Selectable(fmt::format("{}", step).c_str(), step == int(s.spinStepDeg))) {
          s.spinStepDeg = step;
          recreate = true;
        }
      }
      ImGui::EndCombo();
    }
    recreate |= doubleSliderOnRelease("spin to double", s.spinToDouble, 0.25f, 8.0f, "%.2f");
    static const char* const kProjections[] = {"globe", "flat", "hyperbolic", "dome"};
    int projection = int(s.projection);
    recreate |= ImGui::Combo("projection", &projection, kProjections, 4);
    s.projection = SpiralProjection(projection);
    int radii = s.radiusMode == SpiralRadiusMode::Feedback ? 0 : 1;
    static const char* const kRadii[] = {"occlusion feedback", "analytic"};
    recreate |= ImGui::Combo("radii", &radii, kRadii, 2);
    s.radiusMode = radii == 0 ? SpiralRadiusMode::Feedback : SpiralRadiusMode::Analytic;
    recreate |= ImGui::Checkbox("radius correction (sqrt)", &s.correctRadius);
    float fan = float(s.fanPixels);
    ImGui::SliderFloat("fan pixels", &fan, 16.0f, 4096.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
    s.fanPixels = fan;
    recreate |= ImGui::IsItemDeactivatedAfterEdit();
    if (!s.imagery.empty()) {
      // The texture quadtree of the draped imagery (--spiral-imagery).
      recreate |= ImGui::Checkbox("imagery: tint by texel size", &s.imageryOptions.showLevels);
      recreate |= intSliderOnRelease("imagery: transfers a frame (0: no cap)",
                       &s.imageryOptions.quadtree.maxTransfersPerUpdate, 0, 16);
    }
    return recreate;
  }
  if (!rendererNeedsStore(state.algo)) return recreate;

  RingsOptions& rings = state.rings;
  static const int kPatchCells[] = {0, 256, 128, 64, 32};
  const std::string patchLabel =
      rings.patchCells == 0 ? "tile size" : fmt::format("{}", rings.patchCells);
  if (ImGui::BeginCombo("patch cells", patchLabel.c_str())) {
    for (int cells : kPatchCells) {
      const std::string label = cells == 0 ? "tile size" : fmt::format("{}", cells);
      if (ImGui::Selectable(label.c_str(), cells == rings.patchCells) &&
          cells != rings.patchCells) {
        rings.patchCells = cells;
        recreate = true;
      }
    }
    ImGui::EndCombo();
  }
  // Sliders remake the renderer when released, not on every step of a drag.
  recreate |= intSliderOnRelease("rings", &rings.rings, 0, 32, rings.rings == 0 ? "all" : "%d");
  recreate |= intSliderOnRelease("GPU cache slots", &rings.gpuSlots, 8, 512);
  recreate |= intSliderOnRelease("uploads / frame", &rings.maxUploadsPerFrame, 1, 64);
  return recreate;
}

void shadingSection(ViewerState& state) {
  RenderSettings& settings = state.settings;
  int mode = int(settings.mode);
  ImGui::RadioButton("lit", &mode, int(ShadingMode::Lit));
  ImGui::SameLine();
  ImGui::RadioButton("LOD", &mode, int(ShadingMode::LevelOfDetail));
  ImGui::SameLine();
  ImGui::RadioButton("screen-space error", &mode, int(ShadingMode::ScreenSpaceError));
  settings.mode = ShadingMode(mode);
  if (settings.mode == ShadingMode::ScreenSpaceError) {
    ImGui::SliderFloat("red at (px)", &settings.sseRedPx, 0.25f, 20.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
  }
  ImGui::Checkbox("wireframe", &settings.wireframe);
  auto azimuth = float(settings.shading.sunAzimuthDeg);
  auto elevation = float(settings.shading.sunElevationDeg);
  if (ImGui::SliderFloat("sun azimuth", &azimuth, 0.0f, 360.0f, "%.0f deg")) {
    settings.shading.sunAzimuthDeg = azimuth;
  }
  if (ImGui::SliderFloat("sun elevation", &elevation, 1.0f, 90.0f, "%.0f deg")) {
    settings.shading.sunElevationDeg = elevation;
  }
  ImGui::SliderFloat("exaggeration", &settings.verticalExaggeration, 0.1f, 10.0f, "%.2fx",
                     ImGuiSliderFlags_Logarithmic);
}

void cameraSection(ViewerState& state, PanelRequests& requests) {
  if (state.globe) {
    const GeoCamera& g = state.geoCamera;
    text("{:.5f} N  {:.5f} E  {:.0f} m", g.latDeg, g.lonDeg, g.altitudeM);
    text("heading {:.1f}  pitch {:.1f}  above ground {:.0f} m", g.headingDeg, g.pitchDeg,
         g.altitudeM - state.groundM);
    requests.walk = ImGui::Button("walk (G)");
    ImGui::SameLine();
    requests.frameAll = ImGui::Button("whole globe (F)");
    ImGui::SameLine();
    text("{:.0f} m/s", state.speedMps);
    return;
  }
  const Camera& c = state.camera;
  text("position {:.0f} E  {:.0f} N  {:.0f} m", c.position.x, c.position.y, c.position.z);
  text("heading {:.1f}  pitch {:.1f}  above ground {:.0f} m", c.yawDeg, c.pitchDeg,
       c.position.z - state.groundM);
  auto fov = float(state.camera.fovYDeg);
  if (ImGui::SliderFloat("field of view", &fov, 10.0f, 100.0f, "%.0f deg")) {
    state.camera.fovYDeg = fov;
  }
  auto speed = float(state.speedFactor);
  if (ImGui::SliderFloat("speed factor", &speed, 0.01f, 100.0f, "%.2fx",
                         ImGuiSliderFlags_Logarithmic)) {
    state.speedFactor = speed;
  }
  requests.walk = ImGui::Button("walk (G)");
  ImGui::SameLine();
  requests.frameAll = ImGui::Button("frame all (F)");
  ImGui::SameLine();
  text("{:.0f} m/s", state.speedMps);
}

// CPU and GPU milliseconds of the last frames as two lines in one box, on one scale.
void frameTimeGraph(const FrameHistory& history) {
  const std::vector<float> cpu = history.cpuSeries();
  std::vector<float> gpu = history.gpuSeries();
  // GPU times arrive a few frames late: a frame not measured yet repeats the one before.
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    if (gpu[i] < 0.0f) gpu[i] = i > 0 ? gpu[i - 1] : 0.0f;
  }
  float top = 1.0f;
  for (float v : cpu) top = std::max(top, v);
  for (float v : gpu) top = std::max(top, v);
  const ImVec2 size(ImGui::CalcItemWidth(), 56.0f);
  const ImVec2 origin = ImGui::GetCursorPos();
  const std::string legend = fmt::format("0-{:.0f} ms  CPU orange, GPU blue", top);
  ImGui::PushStyleColor(ImGuiCol_PlotLines, ImVec4(1.0f, 0.6f, 0.2f, 1.0f));
  ImGui::PlotLines("##cpu", cpu.data(), int(cpu.size()), 0, legend.c_str(), 0.0f, top, size);
  ImGui::PopStyleColor();
  ImGui::SetCursorPos(origin);
  ImGui::PushStyleColor(ImGuiCol_FrameBg, ImVec4(0, 0, 0, 0));
  ImGui::PushStyleColor(ImGuiCol_PlotLines, ImVec4(0.3f, 0.75f, 1.0f, 1.0f));
  ImGui::PlotLines("frame times", gpu.data(), int(gpu.size()), 0, nullptr, 0.0f, top, size);
  ImGui::PopStyleColor(2);
}

void statisticsSection(const ViewerState& state) {
  const double cpu = state.history.medianCpuMs(), gpu = state.history.medianGpuMs();
  const double interval = state.history.medianIntervalMs();
  text("{:.1f} FPS  CPU {:.2f} ms  GPU {} ms", interval > 0 ? 1000.0 / interval : 0.0, cpu,
       gpu < 0 ? "-" : fmt::format("{:.2f}", gpu));
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "medians over the last %zu frames: frames per second of the window (wall clock), CPU "
        "time of LOD selection and submission, GPU time of the terrain (timer queries)",
        state.history.size());
  }
  frameTimeGraph(state.history);
  const FrameStats& s = state.stats;
  text("triangles {}  vertices {}  draws {}", countText(s.triangles), countText(s.vertices),
       s.drawCalls);
  if (s.tilesWanted > 0) {
    text("tiles: wanted {}  hits {}  misses {}", s.tilesWanted, s.tilesWanted - s.cacheMisses,
         s.cacheMisses);
    text("       loaded {}  resident {}", s.tilesLoaded, s.tilesResident);
  }
  if (state.ringsFrame) {
    const RingsFrameInfo& r = *state.ringsFrame;
    text("patches: {} of {} drawn, {} from coarser data", r.visiblePatches, r.windowPatches,
         r.fallbackPatches);
    if (r.fractalIterations > 0) text("fractal iterations {}", r.fractalIterations);
  }
  if (state.spiralFrame) {
    const SpiralFrameInfo& sf = *state.spiralFrame;
    text("focus {:.4f}, {:.4f}; depth {}, {} windows ({} moved)", sf.focusLatDeg, sf.focusLonDeg,
         sf.finestDepth, sf.windowsResident, sf.windowMoves);
    text("radii {:.3g} .. {:.3g} rad (analytic {:.3g} .. {:.3g})", sf.radii.minRad, sf.radii.maxRad,
         sf.analytic.minRad, sf.analytic.maxRad);
    text("fan {} px, last revolution {} px", sf.fanPixels, sf.outerPixels);
    if (sf.imagery.nodes > 0) {
      const ImageryFrameInfo& i = sf.imagery;
      text("imagery: {} nodes, finest texel {:.1f} m, {:.1f} MiB, update {:.2f} ms", i.nodes,
           i.finestTexelM, double(i.residentBytes) / double(1 << 20), i.updateMs);
      text("  {} transfers, {} held back, {} splits, {} merges", i.uploads, i.deferred, i.splits,
           i.merges);
    }
  }
  if (state.ringoFrame) {
    const RingoFrameInfo& r = *state.ringoFrame;
    text("blocks: depth {}, {} drawn, {} resident", r.depth, r.blocksDrawn, r.blocksResident);
    text("uploads: {} blocks, {} KiB{}", r.uploads, r.uploadBytes / 1024,
         r.reorganising ? "  (reorganising)" : "");
    text("reorganised: {} loaded, {} derived, worker CPU {:.2f} s", r.reorganiser.loaded,
         r.reorganiser.derived, r.reorganiser.workerCpuSeconds);
  }
}

void keysSection() {
  static const char* const kKeys[][2] = {{"W A S D", "forward, left, back, right"},
                                         {"Q E", "down, up"},
                                         {"Shift", "4x faster"},
                                         {"drag", "look around"},
                                         {"wheel", "speed -/+ 25%"},
                                         {"G", "drop to walking height"},
                                         {"F", "frame the whole terrain"},
                                         {"M", "next shading mode"},
                                         {"X", "wireframe"},
                                         {"R", "start/stop recording"},
                                         {"F12", "screenshot"},
                                         {"Tab", "hide/show this panel"},
                                         {"Esc", "quit"}};
  for (const auto& [key, action] : kKeys) {
    ImGui::TextUnformatted(key);
    ImGui::SameLine(ImGui::GetFontSize() * 5.0f);
    ImGui::TextDisabled("%s", action);
  }
}

}  // namespace

PanelRequests drawViewerPanel(ViewerState& state) {
  PanelRequests requests;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowSize(ImVec2(380, std::max(200.0f, display.y - 20.0f)),
                           ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("Tellus");
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 8.5f);  // room for the labels on the right
  text("{}", state.terrainName);
  ImGui::TextDisabled("%d x %d samples, %.1f x %.1f m", state.gridWidth, state.gridHeight,
                      state.spacingXM, state.spacingYM);
  if (ImGui::CollapsingHeader("Renderer", ImGuiTreeNodeFlags_DefaultOpen)) {
    requests.recreateRenderer = rendererSection(state);
  }
  if (ImGui::CollapsingHeader("Shading", ImGuiTreeNodeFlags_DefaultOpen)) shadingSection(state);
  if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
    cameraSection(state, requests);
  }
  if (ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) {
    statisticsSection(state);
  }
  if (ImGui::CollapsingHeader("Record", ImGuiTreeNodeFlags_DefaultOpen)) {
    requests.toggleRecording =
        ImGui::Button(state.recording ? "stop recording (R)" : "record path (R)");
    ImGui::SameLine();
    requests.screenshot = ImGui::Button("screenshot (F12)");
    if (state.stacksUnsaved) {
      ImGui::SameLine();
      requests.saveStacks = ImGui::Button("save edited stacks");
    }
    if (state.recording) text("recording: {} keyframes", state.recordedKeyframes);
    if (state.replaying) {
      text("replaying {:.1f} / {:.1f} s", state.replayTimeS, state.replayDurationS);
      ImGui::SameLine();
      requests.stopReplay = ImGui::Button("stop");
    }
    if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  }
  if (ImGui::CollapsingHeader("Keys")) keysSection();
  ImGui::PopItemWidth();
  ImGui::End();
  return requests;
}

}  // namespace tellus
