#include "tellus/viewer/viewer_panel.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <imgui.h>

#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/viewer/option_widgets.hpp"

namespace tellus {
namespace {

// Text from fmt, without ImGui's printf-style formatting.
template <typename... Args>
void text(fmt::format_string<Args...> format, Args&&... args) {
  const std::string line = fmt::format(format, std::forward<Args>(args)...);
  ImGui::TextUnformatted(line.c_str());
}



// The stacks brush (--algo stacks: the octree renderer edits its stacks).
void stacksBrush(ViewerState& state) {
  ImGui::Combo("brush material", &state.brushMaterial, "air\0rock\0soil\0grass\0");
  state.brushMaterial = std::max(state.brushMaterial, 1);
  ImGui::SliderFloat("brush radius (m)", &state.brushRadiusM, 1.0f, 100.0f, "%.1f");
  text("Ctrl + left click adds, Ctrl + right click carves");
  if (state.stackEdits > 0) {
    text("{} strokes; the last updated the stacks in {:.0f} ms, {} meshes remade",
         state.stackEdits, state.lastEditMs, state.lastEditMeshes);
  }
}

// Renderer choice, the chosen renderer's options (from its family's schema) and what its last
// frame did. True when the renderer must be made again.
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
  const RendererEntry* entry = findRenderer(state.algo);
  if (!entry) return recreate;
  recreate |= drawOptionWidgets(familyOf(*entry).schema, state.renderers.of(familyNameOf(*entry)));
  if (state.algo == "stacks") {
    // The octree needs an odd node size of at least 9 (nodes overlap by one cell).
    int& cells = state.renderers.as<StacksRenderOptions>("stacks").quad.nodeCells;
    cells = std::max(9, cells | 1);
    stacksBrush(state);
  }
  return recreate;
}

void imageryLines(const ViewerState& state) {
  if (!state.imagery) return;
  const ImageryPagingInfo& i = *state.imagery;
  text("imagery: {} layers, {} / {} pages ({:.0f} / {:.0f} MiB)", i.layers, i.residentPages, i.slots,
       double(i.residentBytes) / (1 << 20), double(i.budgetBytes) / (1 << 20));
  text("  uploads {} ({:.1f} MiB), waiting {}", i.uploads, double(i.uploadBytes) / (1 << 20), i.pending);
  text("  a texel covers {:.2f} px (p95 {:.2f})", i.texelPxP50, i.texelPxP95);
}

void shadingSection(ViewerState& state) {
  RenderSettings& settings = state.settings;
  if (state.hasImagery) {
    ImGui::Checkbox("imagery (--imagery)", &state.useImagery);
    imageryLines(state);
  }
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
  // What the renderer says of its last frame (patches, passes, queues, caches).
  for (const std::string& line : state.frameReport) ImGui::TextUnformatted(line.c_str());
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
