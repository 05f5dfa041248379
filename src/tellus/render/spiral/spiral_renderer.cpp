#include "tellus/render/spiral/spiral_renderer.hpp"

#include "tellus/core/cache_folder.hpp"

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>
#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/geodesy.hpp"
#include "tellus/dem/globe_texture_set.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {
namespace {

constexpr double kPi = 3.14159265358979323846;

// (height, undulation) pairs, as the RG32F textures hold them.
std::vector<float> interleaveHeights(const SpiralHeightWindow& window) {
  std::vector<float> rg(2 * window.heights.size());
  for (std::size_t k = 0; k < window.heights.size(); ++k) {
    rg[2 * k] = window.heights[k];
    rg[2 * k + 1] = window.geoidM.empty() ? 0.0f : window.geoidM[k];
  }
  return rg;
}

// Samples a side of the height windows for a spiral of n steps a revolution: a vertex takes the
// depth whose sample spacing is at most its spacing (radius * 2 pi / n) and more than half of
// it, so it lies within n / pi samples of the focal point (twice that east-west at 60 degrees
// of latitude); the window keeps that much beyond the eighth it may stray.
int windowSamplesFor(int n) {
  const double needed = 8.0 * (double(n) / kPi + 1.0);
  int samples = 128;
  while (samples < needed) samples *= 2;
  return samples + 1;
}

}  // namespace

std::optional<SpiralRadiusMode> parseSpiralRadiusMode(std::string_view name) {
  if (name == "feedback") return SpiralRadiusMode::Feedback;
  if (name == "analytic") return SpiralRadiusMode::Analytic;
  return std::nullopt;
}

std::string_view spiralRadiusModeName(SpiralRadiusMode mode) {
  return mode == SpiralRadiusMode::Feedback ? "feedback" : "analytic";
}

Result<std::unique_ptr<SpiralRenderer>> SpiralRenderer::create(
    std::shared_ptr<const GlobalStore> store, SpiralOptions options) {
  if (!store) return makeError("the spiral renderer draws a global store (tellus build --global)");
  if (!(options.fanPixels >= 1.0 && options.fanPixels <= 1e6)) {
    return makeError("spiral: the fan's target must be 1 to 1e6 pixels, got {}", options.fanPixels);
  }
  Result<SpiralMesh> mesh = buildSpiralMesh({.spinToDouble = options.spinToDouble,
                                             .baseRadius = options.baseRadiusRad,
                                             .spinStepDeg = options.spinStepDeg,
                                             .outerRadius = kPi});
  if (!mesh) return mesh.error();
  std::unique_ptr<SpiralRenderer> r(new SpiralRenderer());
  r->store_ = std::move(store);
  r->options_ = options;
  r->mesh_ = std::move(mesh.value());
  const int n = r->mesh_.perRevolution;

  // The static spiral, its centre (radius 0: the focal point) last.
  std::vector<SpiralVertex> vertices = r->mesh_.vertices;
  r->centreIndex_ = std::uint32_t(vertices.size());
  vertices.push_back({0.0f, 0.0f, 0.0f});
  r->vertices_ = gl::Buffer(std::span<const SpiralVertex>(vertices));
  r->strip_ = gl::Buffer(std::span<const std::uint32_t>(r->mesh_.strip));
  // Two fans (this frame's and the one before's), rewritten as the range moves.
  r->fanIndices_ = gl::Buffer(2 * 3 * (std::size_t(n) + 1) * sizeof(std::uint32_t), nullptr,
                              GL_DYNAMIC_STORAGE_BIT);
  r->vertexArray_ = gl::VertexArray::create();
  const GLuint vao = r->vertexArray_.id();
  glVertexArrayVertexBuffer(vao, 0, r->vertices_.id(), 0, sizeof(SpiralVertex));
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);

  // Heights: the whole Earth at the base depth, once; windows of finer depths as needed.
  const int cells = r->store_->tileCells();
  r->base_ = spiralWholeWorld(spiralBaseDepth(cells), cells);
  if (Status s = readSpiralHeightWindow(*r->store_, options.geoid, r->base_); !s) {
    return makeError("spiral: reading the base heights: {}", s.error().message);
  }
  r->baseTexture_ = gl::Texture::create2D(GL_RG32F, r->base_.columns, r->base_.rows);
  const std::vector<float> baseRg = interleaveHeights(r->base_);
  r->baseTexture_.upload2D(0, 0, 0, r->base_.columns, r->base_.rows, GL_RG, GL_FLOAT,
                           baseRg.data());
  r->windowSamples_ = windowSamplesFor(n);
  const int levels =
      std::clamp(r->store_->metadata().deepestDepth - r->base_.depth, 1, kMaxLevels);
  r->levelTextures_ = gl::Texture::create2DArray(GL_RG32F, r->windowSamples_, r->windowSamples_,
                                                 levels * kSlots);

  // The Blue Marble cube maps, converted once and cached beside the store.
  const bool textured = !options.texturesDir.empty();
  if (textured) {
    Result<GlobeTextureSet> set = loadGlobeTextureSet(
        options.texturesDir, derivedCacheFolder(r->store_->path().string(), ".spiral-textures", "spiral-textures"),
        {.faceSize = options.cubeFaceSize});
    if (!set) return set.error();
    const auto upload = [](const CubeMap& cube, GLenum internalFormat, GLenum format) {
      const int mipLevels = 1 + int(std::floor(std::log2(double(cube.size))));
      gl::Texture texture = gl::Texture::createCubeMap(internalFormat, cube.size, mipLevels);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      for (int face = 0; face < 6; ++face) {
        texture.uploadLayer(0, face, cube.size, cube.size, format, GL_UNSIGNED_BYTE,
                            cube.faces[std::size_t(face)].data());
      }
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      glGenerateTextureMipmap(texture.id());
      texture.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
      return texture;
    };
    r->surfaceCube_ = upload(set->surface, GL_SRGB8_ALPHA8, GL_RGBA);
    r->reliefCube_ = upload(set->relief, GL_RGBA8, GL_RGBA);
    r->skyCube_ = upload(set->sky, GL_RG8, GL_RG);
  }
  // The fill program also captures eye-relative positions (tests: captureDrawnPositions).
  const std::string defines =
      fmt::format("#define SPIRAL_FEATURES {}\n{}", options.features & kSpiralAllFeatures,
                  options.whiteShader ? "#define SPIRAL_WHITE 1\n" : "");
  Result<gl::Program> fill = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "spiral/spiral.vert"},
       {GL_FRAGMENT_SHADER, textured ? "spiral/spiral.frag" : "globe/globe.frag", defines}},
      {"vRelativePosition"});
  if (!fill) return fill.error();
  r->fill_ = std::move(fill.value());
  Result<gl::Program> wire = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "spiral/spiral.vert"}, {GL_FRAGMENT_SHADER, "terrain/wire.frag"}});
  if (!wire) return wire.error();
  r->wire_ = std::move(wire.value());
  Result<GlobeSky> sky = GlobeSky::create();
  if (!sky) return sky.error();
  r->sky_ = std::move(sky.value());
  if (!options.imagery.empty()) {
    std::vector<ImageryPyramid> images;
    for (const std::filesystem::path& path : options.imagery) {
      Result<ImageryPyramid> image = openCachedImageryPyramid(
          path, derivedCacheFolder(r->store_->path().string(), ".spiral-textures", "spiral-textures"));
      if (!image) return image.error();
      images.push_back(std::move(image.value()));
    }
    Result<std::unique_ptr<ImageryOverlay>> overlay =
        ImageryOverlay::create(std::move(images), options.imageryOptions);
    if (!overlay) return overlay.error();
    r->imagery_ = std::move(overlay.value());
  }
  for (CountQueries& q : r->queries_) {
    q.fan = gl::Query::create(GL_SAMPLES_PASSED);
    q.outer = gl::Query::create(GL_SAMPLES_PASSED);
  }
  return r;
}

SpiralRenderer::~SpiralRenderer() {
  reads_->wait();  // the workers write into windows this renderer owns
}

int SpiralRenderer::finestStoredAround(double latDeg, double lonDeg) const {
  const int deepest = store_->metadata().deepestDepth;
  const GeoTileKey centre = GlobalTiling::tileAt(deepest, latDeg, lonDeg);
  const int columns = GlobalTiling::tilesX(deepest), rows = GlobalTiling::tilesY(deepest);
  int finest = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    const int y = centre.y + dy;
    if (y < 0 || y >= rows) continue;
    for (int dx = -1; dx <= 1; ++dx) {
      const GeoTileKey key{deepest, ((centre.x + dx) % columns + columns) % columns, y};
      finest = std::max(finest, store_->deepestStored(key).depth);
    }
  }
  return finest;
}

double SpiralRenderer::groundM(double latDeg, double lonDeg) const {
  for (int i = kMaxLevels - 1; i >= 0; --i) {
    const SpiralHeightWindow* window = levels_[std::size_t(i)].window.get();
    if (!window) continue;
    const glm::dvec2 at = window->samplePosition(latDeg, lonDeg);
    if (spiralWindowHolds(*window, float(at.x), float(at.y))) {
      return spiralWindowHeight(*window, float(at.x), float(at.y));
    }
  }
  const glm::dvec2 at = base_.samplePosition(latDeg, lonDeg);
  return spiralWindowHeight(base_, float(at.x), float(at.y));
}

void SpiralRenderer::updateLevels(double latDeg, double lonDeg, int finestDepth, bool wait) {
  const int cells = store_->tileCells();
  const auto install = [&](int i) {
    Level& level = levels_[std::size_t(i)];
    if (!level.pending || !level.pending->done.load(std::memory_order_acquire)) return;
    std::shared_ptr<Level::Pending> done = std::move(level.pending);
    if (!done->status) {
      spdlog::warn("spiral: height window at depth {}: {}", done->window.depth,
                   done->status.error().message);
      return;
    }
    level.slot = (level.slot + 1) % kSlots;
    const std::vector<float> rg = interleaveHeights(done->window);
    levelTextures_.uploadLayer(0, i * kSlots + level.slot, done->window.columns,
                               done->window.rows, GL_RG, GL_FLOAT, rg.data());
    level.window = std::make_shared<const SpiralHeightWindow>(std::move(done->window));
    ++info_.windowMoves;
  };
  const int levelCount = std::min(finestDepth - base_.depth, kMaxLevels);
  for (int i = 0; i < levelCount; ++i) {
    install(i);
    Level& level = levels_[std::size_t(i)];
    if (level.pending) continue;
    if (level.window && !spiralWindowNeedsMove(*level.window, latDeg, lonDeg)) continue;
    auto pending = std::make_shared<Level::Pending>();
    pending->window =
        spiralWindowAround(base_.depth + 1 + i, cells, windowSamples_, latDeg, lonDeg);
    level.pending = pending;
    reads_->run([pending, store = store_, geoid = options_.geoid] {
      pending->status = readSpiralHeightWindow(*store, geoid, pending->window);
      pending->done.store(true, std::memory_order_release);
    });
  }
  if (wait) {
    reads_->wait();
    for (int i = 0; i < levelCount; ++i) install(i);
  }
}

void SpiralRenderer::readQueries() {
  info_.countsRead = false;
  GLint samples = 1;
  glGetIntegerv(GL_SAMPLES, &samples);
  const std::uint64_t perPixel = std::uint64_t(std::max(samples, 1));
  // Oldest first: each frame's counts move the radii once, in order, and never stall.
  for (std::uint64_t age = queries_.size() - 1; age >= 1; --age) {
    if (frame_ < age) continue;
    CountQueries& q = queries_[std::size_t((frame_ - age) % queries_.size())];
    if (!q.issued || !q.fan.available() || !q.outer.available()) continue;
    q.issued = false;
    info_.fanPixels = q.fan.result() / perPixel;
    info_.outerPixels = q.outer.result() / perPixel;
    info_.countsRead = true;
    if (options_.radiusMode == SpiralRadiusMode::Feedback && feedback_) {
      feedback_->update(info_.fanPixels, info_.outerPixels, 4.0 * options_.baseRadiusRad, kPi);
    }
  }
}

SpiralRenderer::DrawState SpiralRenderer::makeState(double latDeg, double lonDeg, int levelCount) {
  DrawState state;
  state.valid = true;
  state.focus = makeSpiralFocus(latDeg * wgs84::kDegree, lonDeg * wgs84::kDegree);
  state.focusEcef = wgs84::geodeticToEcef({latDeg * wgs84::kDegree, lonDeg * wgs84::kDegree, 0.0});
  state.baseFocal = glm::vec2(base_.samplePosition(latDeg, lonDeg));
  state.levelCount = levelCount;
  for (int i = 0; i < levelCount; ++i) {
    const Level& level = levels_[std::size_t(i)];
    state.layer[std::size_t(i)] = level.window ? i * kSlots + level.slot : -1;
    if (level.window) {
      state.levelFocal[std::size_t(i)] = glm::vec2(level.window->samplePosition(latDeg, lonDeg));
      state.levelStepRad[std::size_t(i)] = float(level.window->stepRad());
    }
  }
  return state;
}

void SpiralRenderer::prepare(const ViewSetup& view, const RenderSettings&) {
  const wgs84::Geodetic eye = wgs84::ecefToGeodetic(view.camera.position);
  const double latDeg = eye.latRad / wgs84::kDegree, lonDeg = eye.lonRad / wgs84::kDegree;
  info_.windowMoves = 0;
  // The radii: the analytic choice for this camera, and the feedback of the last counts.
  const SpiralFocus under = makeSpiralFocus(eye.latRad, eye.lonRad);
  const double radiusM = std::sqrt(double(under.meridianM) * double(under.primeVerticalM));
  if (!current_.valid) {
    // The first frame has no windows yet: read them round the eye down to the finest data, so
    // the clearance (and the radii) come from the ground under the camera, not the base's.
    updateLevels(latDeg, lonDeg, finestStoredAround(latDeg, lonDeg), true);
  }
  const double clearance = eye.heightM - groundM(latDeg, lonDeg);
  const double focalPx = view.height / (2.0 * std::tan(glm::radians(view.camera.fovYDeg) * 0.5));
  SpiralRadii analytic =
      spiralAnalyticRadii(clearance, eye.heightM, radiusM, focalPx, options_.fanPixels);
  // Only the globe has a horizon: hyperbolic and dome show the whole world, flat (plate
  // carree) as far as the nearer pole: beyond it the opposite meridian, where longitudes
  // jump by 360 degrees, is the map's seam.
  const double toPole = 0.5 * kPi - std::abs(eye.latRad) - 1e-3;
  const double highest = options_.projection == SpiralProjection::Flat ? toPole : kPi;
  if (options_.projection != SpiralProjection::Globe) analytic.maxRad = highest;
  analytic.maxRad = std::clamp(analytic.maxRad, 8.0 * options_.baseRadiusRad, highest);
  analytic.minRad = std::clamp(analytic.minRad, 4.0 * options_.baseRadiusRad, 0.5 * analytic.maxRad);
  info_.analytic = analytic;
  if (!feedback_) feedback_.emplace(analytic, SpiralFeedbackParams{.fanPixels = options_.fanPixels});
  readQueries();
  SpiralRadii radii =
      options_.radiusMode == SpiralRadiusMode::Feedback ? feedback_->radii() : analytic;
  radii.maxRad = std::min(radii.maxRad, highest);
  radii.minRad = std::min(radii.minRad, 0.5 * radii.maxRad);
  // The finest depth the innermost revolution resolves, within what the store holds here.
  const int n = mesh_.perRevolution;
  const int finestNeeded = spiralLevelDepthFor(float(radii.minRad * 2.0 * kPi / n),
                                               store_->tileCells(), base_.depth,
                                               finestStoredAround(latDeg, lonDeg));
  const int levelCount = std::min(finestNeeded - base_.depth, kMaxLevels);
  // The focal point on that depth's samples: the mesh stands still until the eye crosses one.
  const double step = GlobalTiling::tileSizeDeg(finestNeeded) / store_->tileCells();
  const double focusLat = std::clamp(90.0 - std::round((90.0 - latDeg) / step) * step, -90.0, 90.0);
  const double focusLon = -180.0 + std::round((lonDeg + 180.0) / step) * step;
  const bool firstFrame = !current_.valid;
  updateLevels(focusLat, focusLon, base_.depth + levelCount,
               options_.waitForHeights || firstFrame);
  DrawState state = makeState(focusLat, focusLon, levelCount);
  state.radii = radii;
  state.range = spiralRange(mesh_, radii.minRad, radii.maxRad);
  const std::vector<std::uint32_t> fan = spiralFan(mesh_, state.range, centreIndex_);
  state.fanOffset = std::size_t(frame_ % 2) * fanIndices_.size() / 2;
  fanIndices_.upload(state.fanOffset, fan.size() * sizeof(std::uint32_t), fan.data());
  previous_ = current_;
  current_ = state;
  if (imagery_) {
    imagery_->update(state.focus.latRad, state.focus.lonRad, view, options_.waitForHeights);
    info_.imagery = imagery_->frameInfo();
  }
  spdlog::debug("spiral: clearance {:.1f} m, radii {:.3g}..{:.3g} rad (analytic {:.3g}..{:.3g}), "
                "depths {}..{}, range {}+{} steps, fan {} px, last revolution {} px{}",
                clearance, radii.minRad, radii.maxRad, analytic.minRad, analytic.maxRad,
                base_.depth, base_.depth + levelCount, state.range.first, state.range.count,
                info_.fanPixels, info_.outerPixels, info_.countsRead ? " (read)" : "");
  info_.focusLatDeg = focusLat;
  info_.focusLonDeg = focusLon;
  info_.radii = radii;
  info_.range = state.range;
  info_.finestDepth = base_.depth + levelCount;
  info_.windowsResident = 0;
  for (const Level& level : levels_) info_.windowsResident += level.window ? 1 : 0;
}

void SpiralRenderer::setUniforms(const gl::Program& program, const DrawState& state,
                                 const ViewSetup& view) const {
  const SpiralFocus& f = state.focus;
  program.set("uViewProjection", glm::mat4(view.relativeViewProjection()));
  program.set("uFocusMinusEye", glm::vec3(state.focusEcef - view.camera.position));
  program.set("uFocusEcef", glm::vec3(state.focusEcef));
  program.set("uFocusEast", f.east);
  program.set("uFocusNorth", f.north);
  program.set("uFocusUp", f.up);
  program.set("uFocusSinLat", f.sinLat);
  program.set("uFocusCosLat", f.cosLat);
  program.set("uFocusPrimeVerticalM", f.primeVerticalM);
  program.set("uFocusMeridianM", f.meridianM);
  program.set("uProjection", int(options_.projection));
  program.set("uMinRadius", float(state.radii.minRad));
  program.set("uMaxRadius", float(state.radii.maxRad));
  program.set("uCorrectRadius", int(options_.correctRadius));
  program.set("uStepsPerRevolution", float(mesh_.perRevolution));
  program.set("uBlendDepths", int(options_.blendDepths));
  program.set("uBaseHeights", 0);
  program.set("uLevelHeights", 1);
  program.set("uBaseFocal", state.baseFocal);
  program.set("uBaseStepRad", float(base_.stepRad()));
  program.set("uBaseDepth", base_.depth);
  program.set("uTileCells", store_->tileCells());
  program.set("uLevelCount", state.levelCount);
  if (state.levelCount > 0) {
    program.setArray("uLevelLayer", state.layer.data(), state.levelCount);
    program.setArray("uLevelFocal", state.levelFocal.data(), state.levelCount);
    program.setArray("uLevelStepRad", state.levelStepRad.data(), state.levelCount);
  }
}

FrameStats SpiralRenderer::drawState(const DrawState& state, const ViewSetup& view,
                                     const RenderSettings& settings, bool count,
                                     bool withImagery) {
  const glm::vec3 sun = globeSunEcef(view, settings);
  if (settings.sky) sky_->draw(view, sun);
  setGlobeFillUniforms(fill_, view, settings, sun);
  fill_.set("uDrapeEnabled", 0);
  setUniforms(fill_, state, view);
  if (settings.wireframe) {
    setUniforms(wire_, state, view);
    wire_.set("uSpacing", glm::vec2(1e9f));  // the spiral's triangles keep their size on screen
  }
  baseTexture_.bindUnit(0);
  levelTextures_.bindUnit(1);
  if (surfaceCube_.id() != 0) {
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    surfaceCube_.bindUnit(2);
    reliefCube_.bindUnit(3);
    skyCube_.bindUnit(4);
    fill_.set("uSurface", 2);
    fill_.set("uRelief", 3);
    fill_.set("uSky", 4);
    // The clouds drift eastwards about the axis.
    const float angle = float(glm::radians(double(frame_) * options_.cloudDegreesPerFrame));
    const glm::mat3 rotation(std::cos(angle), std::sin(angle), 0.0f, -std::sin(angle),
                             std::cos(angle), 0.0f, 0.0f, 0.0f, 1.0f);
    glProgramUniformMatrix3fv(fill_.id(), fill_.location("uCloudRotation"), 1, GL_FALSE,
                              &rotation[0][0]);
  }
  const int n = mesh_.perRevolution;
  const GLuint vao = vertexArray_.id();
  // Strip steps [first, first + steps): strip indices 2 first .. 2 (first + steps) + 1.
  const auto drawSteps = [&](int first, int steps) {
    if (steps <= 0) return;
    glDrawElements(GL_TRIANGLE_STRIP, 2 * (steps + 1), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(std::size_t(2 * first) * sizeof(std::uint32_t)));
  };
  const int outerSteps = std::min(n, state.range.count);
  const int innerSteps = state.range.count - outerSteps;
  CountQueries& q = queries_[std::size_t(frame_ % queries_.size())];
  const auto drawAll = [&](const gl::Program& program, bool withQueries) {
    program.use();
    vertexArray_.bind();
    glVertexArrayElementBuffer(vao, fanIndices_.id());
    if (withQueries) q.fan.begin();
    glDrawElements(GL_TRIANGLES, 3 * (n + 1), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(state.fanOffset));
    if (withQueries) q.fan.end();
    glVertexArrayElementBuffer(vao, strip_.id());
    drawSteps(state.range.first, innerSteps);
    if (withQueries) q.outer.begin();
    drawSteps(state.range.first + innerSteps, outerSteps);
    if (withQueries) q.outer.end();
  };
  drawWithWireframeOverlay(
      settings.wireframe, wire_, view, [&] { drawAll(fill_, count); },
      [&] { drawAll(wire_, false); });
  if (count) q.issued = true;
  FrameStats stats;
  stats.triangles = 2 * std::uint64_t(state.range.count) + std::uint64_t(n) + 1;
  stats.vertices = std::uint64_t(state.range.count) + std::uint64_t(n) + 2;
  stats.drawCalls = 3;
  if (imagery_ && withImagery) {
    setUniforms(imagery_->program(), state, view);
    imagery_->draw(count);
    stats.drawCalls += std::uint64_t(info_.imagery.nodes);
  }
  return stats;
}

FrameStats SpiralRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (imagery_ && options_.waitForHeights) {
    // A still: draw depth only, read every count at once and let the quadtrees change until
    // they settle (two rounds in a row without a change), then draw the frame once.
    GLint depthFunc = GL_GREATER;
    glGetIntegerv(GL_DEPTH_FUNC, &depthFunc);
    const float far = depthFunc == GL_GREATER || depthFunc == GL_GEQUAL ? 0.0f : 1.0f;
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    for (int round = 0, quiet = 0; round < 64 && quiet < 2; ++round) {
      drawState(current_, view, settings, true, true);
      imagery_->update(current_.focus.latRad, current_.focus.lonRad, view, true);
      info_.imagery = imagery_->frameInfo();
      ++frame_;
      glClearBufferfv(GL_DEPTH, 0, &far);
      const ImageryFrameInfo& i = info_.imagery;
      quiet = i.uploads + i.splits + i.merges + i.finerMips + i.coarserMips == 0 ? quiet + 1 : 0;
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  FrameStats stats = drawState(current_, view, settings, true, true);
  stats.tilesLoaded = std::uint64_t(info_.windowMoves);
  stats.tilesResident = std::uint64_t(info_.windowsResident);
  stats.uploadBytes = std::uint64_t(info_.windowMoves) * std::uint64_t(windowSamples_) *
                      std::uint64_t(windowSamples_) * 8 + info_.imagery.uploadBytes;
  if (imagery_) stats.textureUpdateMs = info_.imagery.updateMs;
  ++frame_;
  return stats;
}

bool SpiralRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (!previous_.valid) return false;
  drawState(previous_, view, settings, false, false);
  return true;
}

SpiralHeightStack SpiralRenderer::heightStack(const DrawState& state) const {
  SpiralHeightStack stack;
  stack.base = &base_;
  stack.baseFocal = state.baseFocal;
  for (int i = 0; i < state.levelCount; ++i) {
    const std::size_t k = std::size_t(i);
    stack.levels.push_back(state.layer[k] >= 0 ? levels_[k].window.get() : nullptr);
    stack.levelFocal.push_back(state.levelFocal[k]);
  }
  return stack;
}

std::vector<glm::vec3> SpiralRenderer::captureDrawnPositions(const ViewSetup& view) {
  const DrawState& state = current_;
  const int n = mesh_.perRevolution;
  const int count = state.range.count + n + 1;
  gl::Buffer captured(std::size_t(count + 1) * sizeof(glm::vec3), nullptr);
  setUniforms(fill_, state, view);
  baseTexture_.bindUnit(0);
  levelTextures_.bindUnit(1);
  fill_.use();
  vertexArray_.bind();
  glEnable(GL_RASTERIZER_DISCARD);
  captured.bindBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, state.range.first, count);
  glDrawArrays(GL_POINTS, GLint(centreIndex_), 1);
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  std::vector<glm::vec3> positions(std::size_t(count + 1));
  captured.download(0, positions.size() * sizeof(glm::vec3), positions.data());
  return positions;
}

std::vector<glm::vec3> SpiralRenderer::referenceDrawnPositions(const ViewSetup& view) const {
  const DrawState& state = current_;
  const SpiralHeightStack stack = heightStack(state);
  const auto n = float(mesh_.perRevolution);
  const glm::vec3 focusMinusEye(state.focusEcef - view.camera.position);
  std::vector<SpiralVertex> drawn(mesh_.vertices.begin() + state.range.first,
                                  mesh_.vertices.begin() + state.range.first + state.range.count +
                                      mesh_.perRevolution + 1);
  drawn.push_back({0.0f, 0.0f, 0.0f});
  std::vector<glm::vec3> positions;
  for (const SpiralVertex& v : drawn) {
    const glm::vec2 direction(v.dirX, v.dirY);
    const float radius = spiralCorrectedRadius(v.radius, float(state.radii.minRad),
                                               float(state.radii.maxRad), options_.correctRadius);
    const glm::vec2 latLon = spiralLatLonOffset(direction, radius, state.focus);
    const SpiralHeightLookup h = spiralLookupHeight(stack, latLon, radius, n, options_.blendDepths);
    positions.push_back(focusMinusEye + spiralProjectedOffset(options_.projection, direction, radius,
                                                              latLon, h.heightM, state.focus));
  }
  return positions;
}

std::vector<std::string> SpiralRenderer::frameReport() const {
  const SpiralFrameInfo& sf = info_;
  std::vector<std::string> lines{
      fmt::format("focus {:.4f}, {:.4f}; depth {}, {} windows ({} moved)", sf.focusLatDeg,
                  sf.focusLonDeg, sf.finestDepth, sf.windowsResident, sf.windowMoves),
      fmt::format("radii {:.3g} .. {:.3g} rad (analytic {:.3g} .. {:.3g})", sf.radii.minRad,
                  sf.radii.maxRad, sf.analytic.minRad, sf.analytic.maxRad),
      fmt::format("fan {} px, last revolution {} px", sf.fanPixels, sf.outerPixels)};
  if (sf.imagery.nodes > 0) {
    const ImageryFrameInfo& i = sf.imagery;
    lines.push_back(fmt::format("imagery: {} nodes, finest texel {:.1f} m, {:.1f} MiB, update {:.2f} ms",
                                i.nodes, i.finestTexelM, double(i.residentBytes) / double(1 << 20),
                                i.updateMs));
    lines.push_back(fmt::format("  {} transfers, {} held back, {} splits, {} merges", i.uploads,
                                i.deferred, i.splits, i.merges));
  }
  return lines;
}

}  // namespace tellus
