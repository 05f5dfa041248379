#include "tellus/viewer/viewer.hpp"

#include "tellus/core/stopwatch.hpp"

#include "tellus/formats/stacks/stack_surface.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "tellus/eval/camera_path.hpp"
#include "tellus/eval/globe_surface.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/gl/debug_output.hpp"
#include "tellus/gl/gpu_frame_timer.hpp"
#include "tellus/render/output/named_views.hpp"
#include "tellus/render/output/offscreen_target.hpp"
#include "tellus/render/output/snapshot.hpp"
#include "tellus/render/stacks/stacks_lod_renderer.hpp"
#include "tellus/formats/stacks/stack_file.hpp"
#include "tellus/viewer/fly_camera.hpp"
#include "tellus/viewer/globe_camera.hpp"
#include "tellus/viewer/path_recorder.hpp"
#include "tellus/viewer/viewer_panel.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

namespace tellus {
namespace fs = std::filesystem;

namespace {

// The first "PREFIX-NNN.EXTENSION" in the working directory that does not exist yet.
fs::path nextFreeFile(std::string_view prefix, std::string_view extension) {
  for (int n = 1;; ++n) {
    fs::path candidate = fmt::format("{}-{:03}{}", prefix, n, extension);
    if (!fs::exists(candidate)) return candidate;
  }
}

// Dear ImGui for one GLFW window: created after the viewer's own GLFW callbacks (which it
// chains), destroyed before the GL context.
class ImGuiSession {
 public:
  explicit ImGuiSession(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
  }
  ~ImGuiSession() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;
};

// W A S D, Q E and Shift as the fly and globe inputs hold them.
template <typename Input>
void readMovementKeysOf(GLFWwindow* window, Input& input) {
  const auto held = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
  input.forward = held(GLFW_KEY_W);
  input.back = held(GLFW_KEY_S);
  input.left = held(GLFW_KEY_A);
  input.right = held(GLFW_KEY_D);
  input.down = held(GLFW_KEY_Q);
  input.up = held(GLFW_KEY_E);
  input.fast = held(GLFW_KEY_LEFT_SHIFT) || held(GLFW_KEY_RIGHT_SHIFT);
}

class Viewer {
 public:
  Viewer(gl::GlContext& context, const ViewerInputs& inputs, const ViewerOptions& options)
      : context_(context),
        window_(context.window()),
        grid_(*inputs.grid),
        inputs_(inputs),
        options_(options) {}

  Status run();

 private:
  // Setup.
  Status start();
  Status makeRendererFor(const std::string& algo);
  // Per frame.
  void handleKeys();
  void moveCamera(double dtS, double nowS);
  void act(const PanelRequests& requests);
  void drawTerrain(int width, int height, double intervalMs);
  Status takeScreenshot(const fs::path& file);
  bool recording() const;
  void startRecording();
  Status toggleRecording();
  Status saveRecording();
  double groundAt(double x, double y) const {
    return groundUpperBound(grid_, x, y) * double(state_.settings.verticalExaggeration);
  }
  // The globe session's ground: ellipsoidal metres (0 outside the grid).
  // The ground the globe camera stays above: the session's surface, and where a streaming globe
  // renderer draws finer data than that, the ground it draws (drawnGroundM).
  double globeGroundAt(double latDeg, double lonDeg) const {
    double h = surface_->ellipsoidalHeightM(latDeg, lonDeg);
    const double drawn = renderer_->drawnGroundM(latDeg, lonDeg);
    if (std::isfinite(drawn)) h = std::isfinite(h) ? std::max(h, drawn) : drawn;
    return std::isfinite(h) ? h : 0.0;
  }
  ViewSetup globeView(int width, int height) const;
  template <typename Input>
  void readMovementKeys(Input& input) const {
    readMovementKeysOf(window_, input);
  }
  void moveGlobeCamera(double dtS, double nowS);
  Aabb drawnBounds() const;

  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void onScroll(GLFWwindow* window, double dx, double dy);
  static void onMouseButton(GLFWwindow* window, int button, int action, int mods);

  // The stacks brush: strokes under the cursor (Ctrl + click) and scripted ones, applied by
  // the octree renderer before the frame is drawn; saving writes the edited stacks back.
  void applyBrushStrokes(const ViewSetup& view);
  void applyStackEdit(const SphereEdit& edit);
  Status saveStackEdits();
  // The stacks the renderers are made from: the edited ones once there are edits.
  const std::vector<StackTerrain>* currentStacks() const {
    return editedStacks_ ? &*editedStacks_ : inputs_.stacks;
  }

  gl::GlContext& context_;
  GLFWwindow* window_;
  const HeightGrid& grid_;
  ViewerInputs inputs_;
  ViewerOptions options_;
  Aabb gridBounds_;  // the terrain at exaggeration 1

  ViewerState state_;
  FlyCameraController controller_;
  // A globe session: the truth surface for the ground under the camera, the orbit/fly camera
  // and the replay of a globe path.
  bool globe_ = false;
  std::optional<GlobeSurface> surface_;
  GlobeCameraController globeController_;
  std::optional<GeoCameraPath> geoPath_;
  std::vector<GeoCamera> geoPathCameras_;
  PathRecorder recorder_;        // flat sessions
  GeoPathRecorder geoRecorder_;  // globe sessions
  fs::path recordFile_;
  std::unique_ptr<TerrainRenderer> renderer_;
  std::unique_ptr<ImageryTextures> imagery_;  // --imagery, flat sessions
  const RendererFamily* rendererFamily_ = nullptr;  // renderer_'s (its live options)
  std::optional<OffscreenTarget> target_;
  std::optional<gl::GpuFrameTimer> timer_;

  // Replay of options_.path: sampled cameras (fixed frame count) or real time.
  std::optional<CameraPath> path_;
  std::vector<Camera> pathCameras_;
  double replayStartS_ = 0.0;

  // Input gathered by the GLFW callbacks between frames.
  std::vector<int> pressedKeys_;
  double scrollSteps_ = 0.0;
  glm::dvec2 lastCursor_{0.0};

  std::uint64_t frameIndex_ = 0;
  // The first corrupt data a renderer met: shown in the panel, and the viewer's exit status.
  std::optional<Error> dataError_;
  double sceneTimeS_ = 0.0;  // the recorder's clock: path time when sampling a path, else wall
  bool showPanel_ = true;
  bool screenshotRequested_ = false;

  // The stacks brush: clicks waiting for the next frame (pixel in framebuffer pixels, and
  // whether it carves), the edited stacks once a renderer switch had to keep them, and the
  // next scripted stroke.
  struct BrushClick {
    glm::dvec2 pixel;
    bool carve = false;
  };
  std::vector<BrushClick> brushClicks_;
  std::optional<std::vector<StackTerrain>> editedStacks_;
  std::size_t nextScriptedEdit_ = 0;
};

Aabb Viewer::drawnBounds() const {
  return tellus::drawnBounds(gridBounds_, state_.settings.verticalExaggeration);
}

Status Viewer::makeRendererFor(const std::string& algo) {
  RendererInputs inputs;
  inputs.grid = &grid_;
  inputs.store = inputs_.store;
  inputs.waitForTiles = options_.waitForTiles;
  inputs.inputPath = options_.inputPath;
  inputs.geoid = state_.useGeoid ? inputs_.geoid : nullptr;
  inputs.drape = state_.useDrape ? inputs_.drape : nullptr;
  inputs.globalStore = inputs_.globalStore;
  if (inputs.globalStore && algo == "globe-reference" && options_.globeReferenceReadsStore) {
    inputs.grid = nullptr;  // the store's cut; the grid stays the ground under the camera
  }
  // Edits live in the octree renderer's own stacks: keep them before it goes.
  if (const auto* lod = dynamic_cast<const StacksLodRenderer*>(renderer_.get());
      lod && state_.stackEdits > 0) {
    editedStacks_ = lod->pyramid();
  }
  inputs.stacks = currentStacks();
  renderer_.reset();  // free the old one's GPU memory first (stack meshes are large)
  Result<std::unique_ptr<TerrainRenderer>> made = makeRenderer(algo, inputs, state_.renderers);
  if (!made) return made.error();
  renderer_ = std::move(made.value());
  rendererFamily_ = &familyOf(*findRenderer(algo));
  state_.algo = algo;
  glfwSetWindowTitle(window_, fmt::format("Tellus - {} - {}", options_.terrainName, algo).c_str());
  return {};
}

Status Viewer::start() {
  if (!window_) return makeError("tellus view needs a window (a GLFW context)");
  gridBounds_ = inputs_.stacks ? stackWorldBounds(inputs_.stacks->front()) : grid_.worldBounds();
  state_.terrainName = options_.terrainName;
  state_.gridWidth = grid_.width;
  state_.gridHeight = grid_.height;
  state_.spacingXM = grid_.spacingXM;
  state_.spacingYM = grid_.spacingYM;
  state_.hasStore = inputs_.store != nullptr;
  state_.hasGlobalStore = inputs_.globalStore != nullptr;
  state_.hasStacks = inputs_.stacks != nullptr;
  state_.renderers = options_.renderers;
  state_.settings = options_.settings;
  showPanel_ = options_.showPanel;
  globe_ = rendererDrawsGlobe(options_.algo);
  state_.globe = globe_;
  state_.hasGeoid = state_.useGeoid = inputs_.geoid != nullptr;
  state_.hasDrape = state_.useDrape = inputs_.drape != nullptr;
  if (!options_.imagery.empty()) {
    Result<std::vector<ImageryLayer>> layers =
        globe_ ? imageryLayersOnGlobe(options_.imagery, options_.imageryCache)
               : imageryLayersOnGrid(options_.imagery, grid_.georef, grid_.width, grid_.height, grid_.spacingXM,
                                     grid_.spacingYM, options_.imageryCache);
    if (!layers) return layers.error();
    Result<std::unique_ptr<ImageryTextures>> imagery = ImageryTextures::create(
        std::move(layers.value()), options_.imageryBudget, globe_ ? ImageryFrame::LonLat : ImageryFrame::FlatWorld);
    if (!imagery) return imagery.error();
    imagery_ = std::move(imagery.value());
    state_.hasImagery = state_.useImagery = true;
  }
  if (Status made = makeRendererFor(options_.algo); !made) return made;
  if (globe_) {
    surface_.emplace(grid_, inputs_.geoid);
    if (options_.geoCamera) {
      state_.geoCamera = *options_.geoCamera;
    } else {
      const auto& gt = grid_.georef.geoTransform;
      state_.geoCamera = {gt[3] + 0.5 * grid_.height * gt[5], gt[0] + 0.5 * grid_.width * gt[1],
                          20'000'000.0, 0.0, -90.0, 45.0};
    }
    globeController_.setFlyPitchDeg(state_.geoCamera.pitchDeg > -89.0 ? state_.geoCamera.pitchDeg
                                                                      : -20.0);
    if (!options_.path.empty()) {
      Result<GeoCameraPath> path = makeGeoCameraPath(
          options_.path, [this](double lat, double lon) { return globeGroundAt(lat, lon); },
          options_.geoTarget);
      if (!path) return path.error();
      geoPath_ = std::move(path.value());
      if (options_.frames > 0) geoPathCameras_ = geoPath_->sample(options_.frames);
      state_.replaying = true;
      state_.replayDurationS =
          geoPath_->keyframes().back().timeS - geoPath_->keyframes().front().timeS;
    }
  }

  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  const double aspect = double(std::max(width, 1)) / double(std::max(height, 1));
  if (options_.camera) {
    state_.camera = *options_.camera;
  } else {
    Result<Camera> oblique = namedView("oblique", grid_, aspect);
    if (!oblique) return oblique.error();
    state_.camera = oblique.value();
  }
  if (!options_.path.empty() && !globe_) {
    Result<CameraPath> path = makeCameraPath(options_.path, grid_);
    if (!path) return path.error();
    path_ = std::move(path.value());
    if (options_.frames > 0) pathCameras_ = path_->sample(options_.frames);
    state_.replaying = true;
    state_.replayDurationS = path_->durationS();
  }
  recordFile_ = options_.recordFile;
  timer_.emplace();

  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, onKey);
  glfwSetScrollCallback(window_, onScroll);
  glfwSetMouseButtonCallback(window_, onMouseButton);
  glfwGetCursorPos(window_, &lastCursor_.x, &lastCursor_.y);
  return {};
}

void Viewer::onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  auto* viewer = static_cast<Viewer*>(glfwGetWindowUserPointer(window));
  if (action == GLFW_PRESS) viewer->pressedKeys_.push_back(key);
}

void Viewer::onScroll(GLFWwindow* window, double /*dx*/, double dy) {
  auto* viewer = static_cast<Viewer*>(glfwGetWindowUserPointer(window));
  viewer->scrollSteps_ += dy;
}

void Viewer::onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  auto* viewer = static_cast<Viewer*>(glfwGetWindowUserPointer(window));
  if (action != GLFW_PRESS || !(mods & GLFW_MOD_CONTROL) || !viewer->inputs_.stacks) return;
  if (button != GLFW_MOUSE_BUTTON_LEFT && button != GLFW_MOUSE_BUTTON_RIGHT) return;
  glm::dvec2 cursor;
  glfwGetCursorPos(window, &cursor.x, &cursor.y);
  int width = 0, height = 0, windowWidth = 0, windowHeight = 0;
  glfwGetFramebufferSize(window, &width, &height);
  glfwGetWindowSize(window, &windowWidth, &windowHeight);
  if (windowWidth <= 0 || windowHeight <= 0) return;
  // The cursor in framebuffer pixels (HiDPI windows scale them).
  viewer->brushClicks_.push_back({{cursor.x * width / windowWidth, cursor.y * height / windowHeight},
                                  button == GLFW_MOUSE_BUTTON_RIGHT});
}

void Viewer::applyStackEdit(const SphereEdit& edit) {
  auto* lod = dynamic_cast<StacksLodRenderer*>(renderer_.get());
  if (!lod) {
    state_.message = "the brush edits with the stacks renderer (--algo stacks)";
    return;
  }
  Result<StacksEditReport> report = lod->applyEdit(edit);
  if (!report) {
    state_.message = report.error().message;
    return;
  }
  if (report->region.empty()) {
    state_.message = "the brush changed no stack";
    return;
  }
  ++state_.stackEdits;
  state_.lastEditMs = report->editMs;
  state_.lastEditMeshes = report->meshesDropped;
  state_.stacksUnsaved = true;
  spdlog::debug("stroke {} at ({:.1f}, {:.1f}, {:.1f}) r {:.1f}: {} meshes, {:.1f} ms",
                state_.stackEdits, edit.xM, edit.yM, edit.zM, edit.radiusM,
                report->meshesDropped, report->editMs);
}

void Viewer::applyBrushStrokes(const ViewSetup& view) {
  while (nextScriptedEdit_ < options_.stackEdits.size() &&
         options_.stackEdits[nextScriptedEdit_].frame <= int(frameIndex_)) {
    applyStackEdit(options_.stackEdits[nextScriptedEdit_++].edit);
  }
  const bool mouseFree = !ImGui::GetIO().WantCaptureMouse;
  for (const BrushClick& click : brushClicks_) {
    if (!mouseFree || globe_) continue;
    const auto* lod = dynamic_cast<const StacksLodRenderer*>(renderer_.get());
    if (!lod) {
      state_.message = "the brush edits with the stacks renderer (--algo stacks)";
      continue;
    }
    // The ray under the cursor, in the stacks' frame (the drawn z is exaggerated).
    const double exaggeration = std::max(double(state_.settings.verticalExaggeration), 1e-3);
    const glm::dvec3 through = view.unprojectPixel(click.pixel, 0.5);
    glm::dvec3 origin = view.camera.position, direction = through - origin;
    origin.z /= exaggeration;
    direction.z /= exaggeration;
    direction = glm::normalize(direction);
    const std::optional<glm::dvec3> hit =
        firstSolidAlongRay(lod->pyramid().front(), origin, direction, view.clip.farM);
    if (!hit) {
      state_.message = "the brush found no ground under the cursor";
      continue;
    }
    const StackMaterial material = click.carve ? kAir : StackMaterial(state_.brushMaterial);
    applyStackEdit({hit->x, hit->y, hit->z, double(state_.brushRadiusM), material});
  }
  brushClicks_.clear();
}

Status Viewer::saveStackEdits() {
  const auto* lod = dynamic_cast<const StacksLodRenderer*>(renderer_.get());
  const std::vector<StackTerrain>* stacks = lod ? &lod->pyramid() : currentStacks();
  if (options_.stackFile.empty() || !stacks) return makeError("no .tstack to save the edits to");
  const Stopwatch start;
  if (Status written = writeStackFile(options_.stackFile, *stacks, grid_.georef); !written) return written;
  state_.stacksUnsaved = false;
  state_.message = fmt::format(
      "wrote {} ({} strokes) in {:.2f} s", options_.stackFile.string(), state_.stackEdits,
      start.elapsedS());
  spdlog::info("{}", state_.message);
  return {};
}

void Viewer::handleKeys() {
  const bool keyboardFree = !ImGui::GetIO().WantCaptureKeyboard;
  for (const int key : pressedKeys_) {
    if (!keyboardFree && key != GLFW_KEY_F12) continue;
    switch (key) {
      case GLFW_KEY_ESCAPE:
        glfwSetWindowShouldClose(window_, GLFW_TRUE);
        break;
      case GLFW_KEY_TAB:
        showPanel_ = !showPanel_;
        break;
      case GLFW_KEY_F12:
        screenshotRequested_ = true;
        break;
      case GLFW_KEY_R:
        if (Status s = toggleRecording(); !s) state_.message = s.error().message;
        break;
      case GLFW_KEY_M:
        state_.settings.mode = ShadingMode((int(state_.settings.mode) + 1) % 3);
        break;
      case GLFW_KEY_X:
        state_.settings.wireframe = !state_.settings.wireframe;
        break;
      default: {
        PanelRequests requests;
        requests.walk = key == GLFW_KEY_G;
        requests.frameAll = key == GLFW_KEY_F;
        act(requests);
      }
    }
  }
  pressedKeys_.clear();
}

ViewSetup Viewer::globeView(int width, int height) const {
  const GeoCamera& c = state_.geoCamera;
  return geoViewSetup(c, chooseGeoClipRange(c, globeGroundAt(c.latDeg, c.lonDeg), surface_->highestM()),
                      width, height);
}

void Viewer::moveGlobeCamera(double dtS, double nowS) {
  if (state_.replaying && geoPath_) {
    if (!geoPathCameras_.empty()) {
      const std::size_t i = std::min<std::size_t>(frameIndex_, geoPathCameras_.size() - 1);
      state_.geoCamera = geoPathCameras_[i];
      const double fraction =
          geoPathCameras_.size() > 1 ? double(i) / double(geoPathCameras_.size() - 1) : 0.0;
      state_.replayTimeS = fraction * state_.replayDurationS;
    } else {
      if (frameIndex_ == 0) replayStartS_ = nowS;
      state_.replayTimeS = std::min(nowS - replayStartS_, state_.replayDurationS);
      state_.geoCamera = geoPath_->at(geoPath_->keyframes().front().timeS + state_.replayTimeS);
      if (nowS - replayStartS_ >= state_.replayDurationS) state_.replaying = false;
    }
    globeController_.setFlyPitchDeg(state_.geoCamera.pitchDeg);
  }
  sceneTimeS_ = !geoPathCameras_.empty() ? state_.replayTimeS : nowS;
  glm::dvec2 cursor;
  glfwGetCursorPos(window_, &cursor.x, &cursor.y);
  const ImGuiIO& io = ImGui::GetIO();
  GlobeInput input;
  const bool dragging = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS ||
                        glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  if (dragging && !io.WantCaptureMouse) input.dragPx = cursor - lastCursor_;
  lastCursor_ = cursor;
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  int windowWidth = 0, windowHeight = 0;
  glfwGetWindowSize(window_, &windowWidth, &windowHeight);
  if (!io.WantCaptureMouse) {
    input.scrollSteps = scrollSteps_;
    if (scrollSteps_ != 0.0 && width > 0 && height > 0 && windowWidth > 0) {
      // The cursor in framebuffer pixels (HiDPI windows scale them).
      const glm::dvec2 pixel{cursor.x * width / windowWidth, cursor.y * height / windowHeight};
      input.cursorLatLon = ellipsoidUnderPixel(globeView(width, height), pixel);
    }
  }
  scrollSteps_ = 0.0;
  if (!io.WantCaptureKeyboard) readMovementKeys(input);
  const auto ground = [this](double lat, double lon) { return globeGroundAt(lat, lon); };
  if (!state_.replaying) globeController_.update(state_.geoCamera, input, dtS, height, ground);
  state_.groundM = ground(state_.geoCamera.latDeg, state_.geoCamera.lonDeg);
  state_.speedMps = GlobeCameraController::speedMps(state_.geoCamera.altitudeM - state_.groundM);
}

void Viewer::moveCamera(double dtS, double nowS) {
  if (globe_) return moveGlobeCamera(dtS, nowS);
  const bool sampled = !pathCameras_.empty();
  if (state_.replaying && path_) {
    if (sampled) {
      const std::size_t i = std::min<std::size_t>(frameIndex_, pathCameras_.size() - 1);
      state_.camera = pathCameras_[i];
      const double fraction =
          pathCameras_.size() > 1 ? double(i) / double(pathCameras_.size() - 1) : 0.0;
      state_.replayTimeS = fraction * path_->durationS();
    } else {
      if (frameIndex_ == 0) replayStartS_ = nowS;
      state_.replayTimeS = std::min(nowS - replayStartS_, path_->durationS());
      state_.camera = path_->at(path_->keyframes().front().timeS + state_.replayTimeS);
      if (nowS - replayStartS_ >= path_->durationS()) state_.replaying = false;
    }
  }
  sceneTimeS_ = sampled ? state_.replayTimeS : nowS;

  // Fly input, unless a replay drives the camera or the panel has the input.
  glm::dvec2 cursor;
  glfwGetCursorPos(window_, &cursor.x, &cursor.y);
  const ImGuiIO& io = ImGui::GetIO();
  FlyInput input;
  const bool brushing = glfwGetKey(window_, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                        glfwGetKey(window_, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
  const bool dragging = !brushing &&
                        (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS ||
                         glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS);
  if (dragging && !io.WantCaptureMouse) input.mouseDeltaPx = cursor - lastCursor_;
  lastCursor_ = cursor;
  if (!io.WantCaptureMouse) input.scrollSteps = scrollSteps_;
  scrollSteps_ = 0.0;
  if (!io.WantCaptureKeyboard) readMovementKeys(input);
  controller_.setSpeedFactor(state_.speedFactor);
  if (!state_.replaying) {
    controller_.update(state_.camera, input, dtS,
                       [this](double x, double y) { return groundAt(x, y); });
  }
  state_.speedFactor = controller_.speedFactor();
  state_.groundM = groundAt(state_.camera.position.x, state_.camera.position.y);
  state_.speedMps = controller_.speedMps(state_.camera.position.z - state_.groundM);
}

void Viewer::act(const PanelRequests& requests) {
  if (requests.stopReplay) state_.replaying = false;
  if (globe_ && (requests.walk || requests.frameAll)) {
    state_.replaying = false;
    if (requests.walk) {
      globeController_.dropToWalkingHeight(
          state_.geoCamera, [this](double lat, double lon) { return globeGroundAt(lat, lon); });
    } else {
      globeController_.frameGlobe(state_.geoCamera);
    }
  } else if (requests.walk) {
    state_.replaying = false;
    FlyCameraController::dropToWalkingHeight(
        state_.camera, groundAt(state_.camera.position.x, state_.camera.position.y));
  }
  if (requests.frameAll && !globe_) {
    state_.replaying = false;
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    state_.camera =
        FlyCameraController::frameAll(drawnBounds(), double(width) / double(std::max(height, 1)),
                                      state_.camera.fovYDeg, state_.camera.yawDeg);
  }
  if (requests.toggleRecording) {
    if (Status s = toggleRecording(); !s) state_.message = s.error().message;
  }
  if (requests.screenshot) screenshotRequested_ = true;
  if (requests.saveStacks) {
    if (Status saved = saveStackEdits(); !saved) state_.message = saved.error().message;
  }
  if (requests.recreateRenderer) {
    const std::string previous = renderer_ ? std::string(renderer_->name()) : "";
    if (Status made = makeRendererFor(state_.algo); !made) {
      state_.message = made.error().message;
      state_.algo = previous;
    } else {
      state_.message.clear();
      // The ground under the camera follows the geoid switch (it moves by up to 100 m).
      if (globe_) surface_.emplace(grid_, state_.useGeoid ? inputs_.geoid : nullptr);
    }
  }
}

bool Viewer::recording() const {
  return globe_ ? geoRecorder_.recording() : recorder_.recording();
}

void Viewer::startRecording() {
  if (globe_)
    geoRecorder_.start(sceneTimeS_);
  else
    recorder_.start(sceneTimeS_);
}

Status Viewer::toggleRecording() {
  if (recording()) return saveRecording();
  startRecording();
  state_.message = "recording the path";
  return {};
}

Status Viewer::saveRecording() {
  const fs::path file = recordFile_.empty() ? nextFreeFile("tellus-path", ".json") : recordFile_;
  std::size_t keyframes = 0;
  double durationS = 0.0;
  if (globe_) {
    // Lat/lon keyframes: tellus bench and tellus view replay them on any global store.
    Result<GeoCameraPath> path = geoRecorder_.finish();
    if (!path) return path.error();
    if (Status saved = saveGeoCameraPath(path.value(), file); !saved) return saved;
    keyframes = path->keyframes().size();
    durationS = path->keyframes().back().timeS - path->keyframes().front().timeS;
  } else {
    Result<CameraPath> path = recorder_.finish();
    if (!path) return path.error();
    if (Status saved = saveCameraPath(path.value(), file); !saved) return saved;
    keyframes = path->keyframes().size();
    durationS = path->durationS();
  }
  state_.message = fmt::format(
      "wrote {} ({} keyframes, {:.1f} s): replay it with tellus bench --algo {} --path {}",
      file.string(), keyframes, durationS, state_.algo, file.string());
  spdlog::info("{}", state_.message);
  return {};
}

Status Viewer::takeScreenshot(const fs::path& file) {
  const RgbImage image = target_->readResolvedRgb();
  if (Status written = writePng(image, file); !written) return written;
  state_.message = fmt::format("wrote {} ({}x{})", file.string(), image.width, image.height);
  spdlog::info("{}", state_.message);
  return {};
}

void Viewer::drawTerrain(int width, int height, double intervalMs) {
  const Aabb bounds = drawnBounds();
  RenderSettings settings = state_.settings;
  ViewSetup view;
  if (globe_) {
    view = globeView(width, height);
    settings.sky = true;  // the atmosphere behind the globe, haze by the air crossed
  } else {
    view = ViewSetup::create(state_.camera, bounds, width, height);
    settings.shading.fitHazeToView(bounds, view.camera.position, view.clip.farM);
  }
  applyBrushStrokes(view);
  target_->begin(skyColour8(settings.shading));
  // The panel's live options (error targets, budgets) reach the running renderer: no remake.
  if (rendererFamily_ && rendererFamily_->applyLive)
    rendererFamily_->applyLive(*renderer_, state_.renderers.of(rendererFamily_->schema.family));
  const Stopwatch cpuStart;
  state_.imagery.reset();
  if (imagery_ && state_.useImagery) {
    imagery_->beginFrame();
    settings.imagery = imagery_.get();
  }
  renderer_->prepare(view, settings);
  timer_->beginFrame(frameIndex_);
  state_.stats = renderer_->draw(view, settings);
  timer_->endFrame();
  if (settings.imagery) {
    imagery_->endFrame();
    state_.imagery = imagery_->frameInfo();
  }
  const double cpuMs = cpuStart.elapsedMs();
  state_.history.add(cpuMs, -1.0, intervalMs);
  for (const gl::GpuFrameTimer::Sample& sample : timer_->poll()) {
    state_.history.setGpuMs(std::size_t(frameIndex_ - sample.frame), sample.milliseconds);
  }
  state_.frameReport = renderer_->frameReport();
}

Status Viewer::run() {
  if (Status started = start(); !started) return started;
  const ImGuiSession imgui(window_);
  double lastS = glfwGetTime();
  while (!glfwWindowShouldClose(window_)) {
    if (options_.frames > 0 && frameIndex_ >= std::uint64_t(options_.frames)) break;
    glfwPollEvents();
    const double nowS = glfwGetTime();
    const double intervalMs = frameIndex_ > 0 ? 1000.0 * (nowS - lastS) : -1.0;
    const double dtS = std::clamp(nowS - lastS, 0.0, 0.25);  // no leap after a stall
    lastS = nowS;
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    if (width == 0 || height == 0) {  // minimised
      glfwWaitEventsTimeout(0.1);
      continue;
    }
    if (!target_ || target_->width() != width || target_->height() != height) {
      target_.reset();
      Result<OffscreenTarget> target = OffscreenTarget::create(width, height, options_.samples);
      if (!target) return target.error();
      target_ = std::move(target.value());
    }

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handleKeys();
    moveCamera(dtS, nowS);
    if (frameIndex_ == 0 && options_.recordFromStart) startRecording();
    if (showPanel_) {
      state_.recording = recording();
      state_.recordedKeyframes =
          globe_ ? geoRecorder_.keyframeCount() : recorder_.keyframeCount();
      act(drawViewerPanel(state_));
    }
    ImGui::Render();

    drawTerrain(width, height, intervalMs);
    if (std::optional<Error> corrupt = renderer_->dataError(); corrupt && !dataError_) {
      dataError_ = corrupt;
      state_.message = corrupt->message;
      spdlog::error("{}", corrupt->message);
    }
    target_->resolve();
    target_->bindResolved();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (globe_)
      geoRecorder_.add(sceneTimeS_, state_.geoCamera);
    else
      recorder_.add(sceneTimeS_, state_.camera);
    const bool lastFrame = options_.frames > 0 && frameIndex_ + 1 == std::uint64_t(options_.frames);
    if (lastFrame && !options_.screenshot.empty()) {
      if (Status s = takeScreenshot(options_.screenshot); !s) return s;
    }
    if (screenshotRequested_) {
      screenshotRequested_ = false;
      if (Status s = takeScreenshot(nextFreeFile("tellus-screenshot", ".png")); !s) {
        state_.message = s.error().message;
      }
    }
    target_->presentTo(0, width, height);
    gl::checkGlErrors("tellus view frame");
    context_.swapBuffers();
    ++frameIndex_;
  }
  const double interval = state_.history.medianIntervalMs();
  spdlog::info("view: {} frames; medians of the last {}: {:.1f} FPS, CPU {:.2f} ms, GPU {:.2f} ms",
               frameIndex_, state_.history.size(), interval > 0 ? 1000.0 / interval : 0.0,
               state_.history.medianCpuMs(), state_.history.medianGpuMs());
  if (recording()) {
    if (Status saved = saveRecording(); !saved) return saved;
  }
  if (options_.saveStackEdits && state_.stacksUnsaved) {
    if (Status saved = saveStackEdits(); !saved) return saved;
  } else if (state_.stacksUnsaved) {
    spdlog::warn("{} brush strokes not saved (the panel's save button writes them to {})",
                 state_.stackEdits, options_.stackFile.string());
  }
  if (dataError_) return *dataError_;  // drawn without the corrupt pieces: not a clean run
  return {};
}

}  // namespace

Status runViewer(gl::GlContext& context, const ViewerInputs& inputs, const ViewerOptions& options) {
  if (!inputs.grid) return makeError("tellus view: no terrain given");
  Viewer viewer(context, inputs, options);
  return viewer.run();
}

}  // namespace tellus
