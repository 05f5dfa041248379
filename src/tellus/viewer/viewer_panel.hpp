#pragma once
// The viewer's Dear ImGui panel: renderer choice and parameters, shading, camera, live
// statistics with a frame-time graph, recording and screenshots. It edits a ViewerState and
// returns what the user asked for; the viewer acts on it. Call between ImGui::NewFrame() and
// ImGui::Render().
#include <optional>
#include <string>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/imagery/imagery_textures.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/viewer/frame_history.hpp"

namespace tellus {

struct ViewerState {
  // The terrain (read-only).
  std::string terrainName;
  int gridWidth = 0, gridHeight = 0;
  double spacingXM = 0.0, spacingYM = 0.0;
  bool hasStore = false;
  bool hasGlobalStore = false;  // renderers that stream from a global store can draw
  bool hasStacks = false;       // material stacks: the stack renderers, and only they, draw them
  // The stacks renderer's brush (Ctrl + left click adds, Ctrl + right click carves).
  int brushMaterial = 1;  // rock 1, soil 2, grass 3
  float brushRadiusM = 8.0f;
  std::size_t stackEdits = 0;      // strokes applied this session
  double lastEditMs = 0.0;         // the last stroke's update of stacks, levels and GPU copy
  std::size_t lastEditMeshes = 0;  // the meshes it dropped (made again in the next frame)
  bool stacksUnsaved = false;
  bool globe = false;  // a globe session: globe renderers and the geo camera
  bool hasGeoid = false, hasDrape = false;  // the globe session was given --geoid / --drape
  bool hasImagery = false;  // the flat session was given --imagery
  // Editable.
  std::string algo;
  RendererSettings renderers;  // every family's options (the panel shows the current one's)
  RenderSettings settings;
  Camera camera;
  GeoCamera geoCamera;  // the camera of a globe session
  bool useGeoid = false, useDrape = false;  // what the globe renderer uses of those
  bool useImagery = false;                  // drape the imagery (else the height tint)
  double speedFactor = 1.0;
  // Read-only, this frame.
  double groundM = 0.0;
  double speedMps = 0.0;
  FrameStats stats;
  std::optional<ImageryPagingInfo> imagery;  // the imagery's last update, when draped
  std::vector<std::string> frameReport;  // the renderer's own lines on its last frame
  FrameHistory history;
  bool recording = false;
  std::size_t recordedKeyframes = 0;
  bool replaying = false;
  double replayTimeS = 0.0, replayDurationS = 0.0;
  std::string message;  // last action's result ("wrote ...", errors)
};

struct PanelRequests {
  bool recreateRenderer = false;  // algo or a renderer option changed
  bool screenshot = false;
  bool toggleRecording = false;
  bool frameAll = false;
  bool walk = false;
  bool stopReplay = false;
  bool saveStacks = false;  // write the edited stacks back to their .tstack
};

PanelRequests drawViewerPanel(ViewerState& state);

}  // namespace tellus
