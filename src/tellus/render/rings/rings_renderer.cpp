#include "tellus/render/rings/rings_renderer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/frustum.hpp"
#include "tellus/lod/rings/patch_mesh.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {
namespace {

constexpr int kMaxShaderLevels = 24;  // rings.vert's kMaxLevels
constexpr GLuint kMeshBinding = 0, kInstanceBinding = 1;
constexpr int kNoLod = 1 << 20;  // slotLod_: no patch used the slot this frame

// Edge order of the instance's packed edge levels: up, right, down, left (PatchEdge bit order).
constexpr std::array<std::array<int, 2>, 4> kEdgeNeighbour = {{{0, -1}, {1, 0}, {0, 1}, {-1, 0}}};

}  // namespace

RingsRenderer::~RingsRenderer() = default;

int RingsRenderer::wantedLevel(int lod) const {
  return std::min(lod + levelShift_, residency_.coarsestLevel());
}

Result<std::unique_ptr<RingsRenderer>> RingsRenderer::create(std::shared_ptr<const TileStore> store,
                                                             RingsOptions options) {
  if (!store) return makeError("rings renderer: no tile store");
  const PyramidLayout& layout = store->layout();
  const int tileSize = layout.tileSize();
  if (options.patchCells == 0) options.patchCells = tileSize;
  if (options.patchCells < 1 || options.patchCells > tileSize ||
      !std::has_single_bit(unsigned(options.patchCells))) {
    return makeError("patch cells must be a power of two in 1..{} (the store's tile size), got {}",
                     tileSize, options.patchCells);
  }
  if (layout.levelCount() > kMaxShaderLevels) {
    return makeError("the store has {} levels; the rings renderer handles at most {}",
                     layout.levelCount(), kMaxShaderLevels);
  }
  if (options.maxUploadsPerFrame < 0) return makeError("uploads per frame must be >= 0");
  if (options.incrementalFractal && store->codec().id() != CodecId::Fractal) {
    return makeError(
        "'{}' is coded with {}: incremental decoding needs a store built with "
        "--codec fractal",
        store->path().string(), store->metadata().codec);
  }

  auto r = std::unique_ptr<RingsRenderer>(new RingsRenderer());
  r->options_ = std::move(options);
  r->store_ = store;
  r->tileSize_ = tileSize;
  r->patchesX_ = layout.tilesX(0);
  r->patchesY_ = layout.tilesY(0);
  r->levelShift_ = std::countr_zero(unsigned(tileSize / r->options_.patchCells));
  r->dataWidth_ = layout.dataWidth();
  r->dataHeight_ = layout.dataHeight();
  r->spacingXM_ = store->metadata().spacingXM;
  r->spacingYM_ = store->metadata().spacingYM;

  int rings = r->options_.rings;
  if (rings == 0) {
    // Reach 2^rings - 1 >= patches - 1 along the longer side: the window covers the terrain
    // wherever the viewer stands.
    rings = std::max(1, int(std::bit_width(unsigned(std::max(r->patchesX_, r->patchesY_) - 1))));
  }
  // The coarsest level of detail: a one-cell mesh, or the last ring.
  const int maxLod = std::min(std::countr_zero(unsigned(r->options_.patchCells)), rings - 1);
  r->maxLod_ = r->options_.bruteForce ? 0 : maxLod;
  Result<RingsStructure> structure = RingsStructure::create(
      rings, maxLod, r->patchesX_, r->patchesY_, r->patchesX_ / 2, r->patchesY_ / 2);
  if (!structure) return structure.error();
  r->structure_ = std::move(structure.value());
  Result<TileResidency> residency = TileResidency::create(layout, r->options_.gpuSlots);
  if (!residency) return residency.error();
  r->residency_ = std::move(residency.value());

  // Patch bounds from the level-0 tiles' statistics, padded by the codec's error bound.
  const auto pad = float(store->metadata().maxErrorM);
  r->patchMinM_.resize(std::size_t(r->patchesX_) * std::size_t(r->patchesY_));
  r->patchMaxM_.resize(r->patchMinM_.size());
  for (int y = 0; y < r->patchesY_; ++y) {
    for (int x = 0; x < r->patchesX_; ++x) {
      const TileRecord* record = store->find({0, x, y});
      if (!record) return makeError("the store lacks {}", TileStore::describe({0, x, y}));
      const std::size_t i = std::size_t(y) * std::size_t(r->patchesX_) + std::size_t(x);
      r->patchMinM_[i] = record->stats.minHeightM - pad;
      r->patchMaxM_[i] = record->stats.maxHeightM + pad;
    }
  }

  Result<FillAndWirePrograms> programs =
      loadFillAndWirePrograms("rings/rings.vert", "rings/rings.frag");
  if (!programs) return programs.error();
  r->fill_ = std::move(programs->fill);
  r->wire_ = std::move(programs->wire);
  r->setConstantUniforms();

  // Static patch meshes, one per level of detail, built once.
  for (int lod = 0; lod <= r->maxLod_; ++lod) {
    Result<PatchMesh> mesh = buildPatchMesh(r->options_.patchCells >> lod);
    if (!mesh) return mesh.error();
    LodMesh gpu;
    gpu.cells = mesh->cells;
    gpu.triangles = mesh->triangleCount();
    gpu.vertices = gl::Buffer(std::span<const PatchVertex>(mesh->vertices));
    gpu.indices = gl::Buffer(std::span<const std::uint32_t>(mesh->indices));
    r->meshes_.push_back(std::move(gpu));
  }
  r->vertexArray_ = gl::VertexArray::create();
  const GLuint vao = r->vertexArray_.id();
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribIFormat(vao, 0, 4, GL_UNSIGNED_SHORT, 0);
  glVertexArrayAttribBinding(vao, 0, kMeshBinding);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribIFormat(vao, 1, 4, GL_INT, 0);
  glVertexArrayAttribBinding(vao, 1, kInstanceBinding);
  glVertexArrayBindingDivisor(vao, kInstanceBinding, 1);

  const int side = tileSize + 1;
  r->heights_ = gl::Texture::create2DArray(GL_R32F, side, side, r->options_.gpuSlots);
  r->heights_.setFilter(GL_LINEAR, GL_LINEAR);
  r->heights_.setWrap(GL_CLAMP_TO_EDGE);
  r->pageTable_ = gl::Buffer(r->residency_.pageTable().size() * sizeof(std::int32_t), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
  r->instanceBuffer_ =
      gl::Buffer(r->patchMinM_.size() * sizeof(PatchInstance), nullptr, GL_DYNAMIC_STORAGE_BIT);
  r->slotErrorM_.assign(std::size_t(r->options_.gpuSlots), 0.0f);
  r->slotErrorBuffer_ = gl::Buffer(r->slotErrorM_.size() * sizeof(float), r->slotErrorM_.data(),
                                   GL_DYNAMIC_STORAGE_BIT);

  TileCacheOptions cacheOptions;
  cacheOptions.budgetBytes = r->options_.cpuCacheBytes;
  cacheOptions.fractalCodes = r->options_.incrementalFractal;
  r->cache_ = std::make_unique<TileCache>(store, std::move(cacheOptions));
  // The coarsest tile, pinned: every patch can always draw from it.
  const TileKey top{r->residency_.coarsestLevel(), 0, 0};
  Result<TileHandle> topTile = r->cache_->get(top);
  if (!topTile) return topTile.error();
  if (r->options_.incrementalFractal) {
    // One decoder slot per GPU cache slot; cells fine enough for any range size.
    Result<FractalGpuDecoder> decoder = FractalGpuDecoder::create(
        geometryForAnyRanges(*topTile.value()->fractalCode), r->options_.gpuSlots);
    if (!decoder) return decoder.error();
    r->fractalDecoder_ = std::make_unique<FractalGpuDecoder>(std::move(decoder.value()));
    r->slotLod_.assign(std::size_t(r->options_.gpuSlots), kNoLod);
  }
  const int slot = r->residency_.acquireSlot();
  r->residency_.assign(slot, top, true);
  r->pending_.push_back({slot, topTile.value()});
  r->instancesByLod_.resize(std::size_t(r->maxLod_) + 1);
  spdlog::debug("rings: {}x{} patches, {} rings, lod 0..{}, data level shift {}, {} GPU slots",
                r->patchesX_, r->patchesY_, rings, r->maxLod_, r->levelShift_,
                r->options_.gpuSlots);
  return r;
}

void RingsRenderer::setConstantUniforms() {
  std::array<int, 9> outward{};
  for (int o = 0; o < 9; ++o) outward[std::size_t(o)] = outwardEdges(PatchOrientation(o));
  std::array<int, kMaxShaderLevels> levelOffset{}, levelTilesX{};
  for (int level = 0; level < residency_.levelCount(); ++level) {
    levelOffset[std::size_t(level)] = residency_.levelOffset(level);
    levelTilesX[std::size_t(level)] = residency_.tilesX(level);
  }
  for (const gl::Program* program : {&fill_, &wire_}) {
    program->set("uSampleSpacing", glm::vec2(float(spacingXM_), float(spacingYM_)));
    program->set("uDataSize", glm::ivec2(dataWidth_, dataHeight_));
    program->set("uTileSize", tileSize_);
    program->setArray("uOutwardEdges", outward.data(), int(outward.size()));
    program->setArray("uLevelOffset", levelOffset.data(), int(levelOffset.size()));
    program->setArray("uLevelTilesX", levelTilesX.data(), int(levelTilesX.size()));
  }
}

std::pair<double, double> RingsRenderer::sampleCoordinates(const glm::dvec3& world) const {
  return {world.x / spacingXM_, double(dataHeight_ - 1) - world.y / spacingYM_};
}

void RingsRenderer::moveCentreTo(int x, int y) {
  while (structure_.centreX() != x || structure_.centreY() != y) {
    const int dx = x - structure_.centreX(), dy = y - structure_.centreY();
    if (std::max(std::abs(dx), std::abs(dy)) > structure_.reach()) {
      // A jump beyond the window: every slot changes anyway, rebuild.
      Result<RingsStructure> fresh = RingsStructure::create(
          structure_.rings(), structure_.maxLevel(), patchesX_, patchesY_, x, y);
      if (fresh) structure_ = std::move(fresh.value());
      frame_.slotsRefilled += structure_.side() * structure_.side();
      return;
    }
    const int stepX = structure_.centreX() + (dx > 0) - (dx < 0);
    const int stepY = structure_.centreY() + (dy > 0) - (dy < 0);
    Result<int> refilled = structure_.updateRings(stepX, stepY);
    frame_.slotsRefilled += refilled ? refilled.value() : 0;
  }
}

Aabb RingsRenderer::patchBox(int x, int y, const glm::dvec3& camera, float exaggeration) const {
  const std::size_t i = std::size_t(y) * std::size_t(patchesX_) + std::size_t(x);
  const double west = x * tileSize_ * spacingXM_;
  const double east = std::min((x + 1) * tileSize_, dataWidth_ - 1) * spacingXM_;
  const double north = (dataHeight_ - 1 - y * tileSize_) * spacingYM_;
  const double south =
      (dataHeight_ - 1 - std::min((y + 1) * tileSize_, dataHeight_ - 1)) * spacingYM_;
  double low = double(patchMinM_[i]) * exaggeration, high = double(patchMaxM_[i]) * exaggeration;
  if (low > high) std::swap(low, high);
  return {glm::dvec3(west, south, low) - camera, glm::dvec3(east, north, high) - camera};
}

int RingsRenderer::lodOfNeighbour(int x, int y) const {
  if (options_.bruteForce) return 0;
  return structure_.levelOf(x, y);
}

void RingsRenderer::prepare(const ViewSetup& view, const RenderSettings& settings) {
  frame_ = RingsFrameInfo{};
  residency_.beginFrame();
  std::fill(slotLod_.begin(), slotLod_.end(), kNoLod);
  const glm::dvec3& camera = view.camera.position;

  // 1. The centre patch follows the camera (clamped to the terrain).
  const auto [col, row] = sampleCoordinates(camera);
  const int cx = std::clamp(int(std::floor(col / tileSize_)), 0, patchesX_ - 1);
  const int cy = std::clamp(int(std::floor(row / tileSize_)), 0, patchesY_ - 1);
  moveCentreTo(cx, cy);
  frame_.centreX = cx;
  frame_.centreY = cy;
  // Height above the highest ground of the centre patch, in patch widths.
  const double ground =
      double(patchMaxM_[std::size_t(cy) * std::size_t(patchesX_) + std::size_t(cx)]) *
      settings.verticalExaggeration;
  const double patchWidthM = tileSize_ * std::min(spacingXM_, spacingYM_);
  structure_.setViewerHeight(int(std::max(0.0, camera.z - ground) / patchWidthM));
  frame_.viewerHeight = structure_.viewerHeight();

  // 2. Active patches, culled against the frustum with their height bounds.
  const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
  visible_.clear();
  const std::vector<RingPatch> window = structure_.activePatches();
  frame_.windowPatches = int(window.size());
  for (const RingPatch& p : window) {
    if (options_.frustumCulling &&
        !frustum.intersects(patchBox(p.x, p.y, camera, settings.verticalExaggeration))) {
      continue;
    }
    VisiblePatch v;
    v.x = p.x;
    v.y = p.y;
    v.distance = p.distance;
    if (!options_.bruteForce) {
      v.lod = p.level;
      v.orientation = p.orientation;
      v.coarserOutside = p.stitchEdges != 0;
    }
    visible_.push_back(v);
  }
  frame_.visiblePatches = int(visible_.size());

  // 3. Tiles: request, load, then decide what each patch draws from.
  requestTiles();
  loadTiles();
  buildInstances();
}

void RingsRenderer::requestTiles() {
  wanted_.clear();
  const int top = residency_.coarsestLevel();
  for (const VisiblePatch& v : visible_) {
    for (int level = top; level >= wantedLevel(v.lod); --level) {
      const TileKey key{level, v.x >> level, v.y >> level};
      if (!residency_.firstRequestThisFrame(key)) continue;
      ++frame_.tilesWanted;
      if (const int slot = residency_.slotOf(key); slot >= 0) {
        residency_.touch(key);
        wantIterationsFor(slot, v.lod);
      } else {
        ++frame_.misses;
        wanted_.push_back({key, v.distance, v.lod});
      }
    }
  }
  // Coarse tiles first (a patch can only use a level whose ancestors are resident), then near.
  std::sort(wanted_.begin(), wanted_.end(), [](const WantedTile& a, const WantedTile& b) {
    if (a.key.level != b.key.level) return a.key.level > b.key.level;
    return a.distance < b.distance;
  });
}

void RingsRenderer::loadTiles() {
  const bool wait = options_.waitForTiles;
  if (!wait) cache_->pausePrefetching(true);  // post everything, then let the best start first
  for (std::size_t i = 0; i < wanted_.size(); ++i) {
    const TileKey key = wanted_[i].key;
    if (options_.tileFilter && !options_.tileFilter(key)) continue;
    const auto priority = float(1000 * key.level - wanted_[i].distance);
    if (!wait && frame_.uploads >= options_.maxUploadsPerFrame) {
      cache_->prefetch(key, priority);
      continue;
    }
    TileHandle tile;
    if (wait) {
      Result<TileHandle> loaded = cache_->get(key);
      if (!loaded) {
        if (!reportedLoadError_) spdlog::error("rings: {}", loaded.error().message);
        reportedLoadError_ = true;
        continue;
      }
      tile = loaded.value();
    } else {
      tile = cache_->tryGet(key, priority);
      if (!tile) continue;  // queued; it arrives in a later frame
    }
    const int slot = residency_.acquireSlot();
    if (slot < 0) break;  // every slot holds a tile this frame draws
    residency_.assign(slot, key);
    if (fractalDecoder_) slotLod_[std::size_t(slot)] = kNoLod;
    wantIterationsFor(slot, wanted_[i].lod);
    pending_.push_back({slot, std::move(tile)});
    ++frame_.uploads;
  }
  if (!wait) cache_->pausePrefetching(false);
}

int RingsRenderer::fractalIterationsOf(TileKey key) const {
  const int slot = residency_.slotOf(key);
  if (!fractalDecoder_ || slot < 0) return -1;
  return fractalDecoder_->iterations(slot);
}

int RingsRenderer::fractalFullIterationsOf(TileKey key) const {
  const int slot = residency_.slotOf(key);
  if (!fractalDecoder_ || slot < 0) return -1;
  return fractalDecoder_->fullIterations(slot);
}

void RingsRenderer::wantIterationsFor(int slot, int lod) {
  if (!fractalDecoder_) return;
  int& wanted = slotLod_[std::size_t(slot)];
  wanted = std::min(wanted, lod);
}

void RingsRenderer::decodeFractalTiles() {
  const float quantum = float(store_->metadata().quantumM);
  for (const PendingUpload& upload : pending_) {
    if (Status s = fractalDecoder_->load(upload.slot, *upload.tile->fractalCode); !s) {
      if (!reportedLoadError_) spdlog::error("rings: {}", s.error().message);
      reportedLoadError_ = true;
    }
  }
  // Every slot that needs more iterations gets them in one batch, then publishes.
  std::vector<FractalGpuDecoder::IterationRequest> requests;
  for (int slot = 0; slot < fractalDecoder_->slotCount(); ++slot) {
    const int lod = slotLod_[std::size_t(slot)];
    if (lod == kNoLod) continue;
    const int full = fractalDecoder_->fullIterations(slot);
    const int wanted = std::clamp(full - lod, 1, full);
    const int more = wanted - fractalDecoder_->iterations(slot);
    if (more > 0) {
      requests.push_back({slot, more});
      frame_.fractalIterations += more;
    }
  }
  fractalDecoder_->iterate(requests);
  for (const FractalGpuDecoder::IterationRequest& r : requests) {
    fractalDecoder_->publish(r.slot, heights_, r.slot, quantum, true);
  }
}

void RingsRenderer::buildInstances() {
  for (auto& list : instancesByLod_) list.clear();
  const int reach = structure_.reach();
  for (const VisiblePatch& v : visible_) {
    const int level = residency_.closedLevel(v.x, v.y, wantedLevel(v.lod));
    if (level > wantedLevel(v.lod)) ++frame_.fallbackPatches;
    PatchInstance instance;
    instance.x = v.x;
    instance.y = v.y;
    instance.lodInfo = v.lod | (int(v.orientation) << 4) | (int(v.coarserOutside) << 8);
    instance.levels = level;
    for (std::size_t e = 0; e < kEdgeNeighbour.size(); ++e) {
      const int nx = v.x + kEdgeNeighbour[e][0], ny = v.y + kEdgeNeighbour[e][1];
      int edgeLevel = level;
      const bool inTerrain = nx >= 0 && ny >= 0 && nx < patchesX_ && ny < patchesY_;
      const bool inWindow = std::abs(nx - structure_.centreX()) <= reach &&
                            std::abs(ny - structure_.centreY()) <= reach;
      if (inTerrain && inWindow) {
        edgeLevel =
            std::max(level, residency_.closedLevel(nx, ny, wantedLevel(lodOfNeighbour(nx, ny))));
      }
      instance.levels |= edgeLevel << (5 + 5 * int(e));
    }
    instancesByLod_[std::size_t(v.lod)].push_back(instance);
    ++frame_.patchesPerLod[std::size_t(std::min(v.lod, 15))];
  }
  // The previous frame's selection is kept for drawPreviousSelection (the popping metric).
  std::swap(previousInstances_, instances_);
  std::swap(previousLodFirstInstance_, lodFirstInstance_);
  instances_.clear();
  lodFirstInstance_.clear();
  for (const auto& list : instancesByLod_) {
    lodFirstInstance_.push_back(int(instances_.size()));
    instances_.insert(instances_.end(), list.begin(), list.end());
  }
  lodFirstInstance_.push_back(int(instances_.size()));
}

void RingsRenderer::drawPass(const gl::Program& program, bool wire,
                             const std::vector<int>& lodFirstInstance, FrameStats* stats) {
  program.use();
  for (std::size_t lod = 0; lod + 1 < lodFirstInstance.size(); ++lod) {
    const int first = lodFirstInstance[lod];
    const int count = lodFirstInstance[lod + 1] - first;
    if (count == 0) continue;
    const LodMesh& mesh = meshes_[lod];
    const int stride = tileSize_ / mesh.cells;
    program.set("uMeshStride", stride);
    if (wire) {
      // wire.frag fades lines by the cell size on screen.
      program.set("uSpacing", glm::vec2(float(spacingXM_ * stride), float(spacingYM_ * stride)));
    }
    glVertexArrayVertexBuffer(vertexArray_.id(), kMeshBinding, mesh.vertices.id(), 0,
                              sizeof(PatchVertex));
    glVertexArrayVertexBuffer(vertexArray_.id(), kInstanceBinding, instanceBuffer_.id(),
                              GLintptr(first) * GLintptr(sizeof(PatchInstance)),
                              sizeof(PatchInstance));
    vertexArray_.setIndexBuffer(mesh.indices);
    const auto indexCount = GLsizei(mesh.triangles * 3);
    glDrawElementsInstanced(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr, count);
    if (stats) {
      stats->triangles += mesh.triangles * std::uint64_t(count);
      stats->vertices +=
          std::uint64_t(mesh.cells + 1) * std::uint64_t(mesh.cells + 1) * std::uint64_t(count);
      ++stats->drawCalls;
    }
  }
}

FrameStats RingsRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  // Streamed tiles reach their slots, then the page table and this frame's instances.
  const int side = tileSize_ + 1;
  std::uint64_t uploadBytes = 0;
  if (fractalDecoder_) {
    decodeFractalTiles();
  } else {
    for (const PendingUpload& upload : pending_) {
      heights_.uploadLayer(0, upload.slot, side, side, GL_RED, GL_FLOAT,
                           upload.tile->heightsM.data());
      uploadBytes += std::uint64_t(side) * std::uint64_t(side) * sizeof(float);
    }
  }
  if (!pending_.empty()) {  // the screen-space error shading mode reads each slot's error
    for (const PendingUpload& upload : pending_) {
      const TileRecord* record = store_->find(residency_.tileIn(upload.slot));
      slotErrorM_[std::size_t(upload.slot)] = record ? record->stats.geometricErrorM : 0.0f;
    }
    slotErrorBuffer_.upload(0, slotErrorM_.size() * sizeof(float), slotErrorM_.data());
  }
  pending_.clear();
  if (residency_.changed()) {
    const auto& table = residency_.pageTable();
    pageTable_.upload(0, table.size() * sizeof(std::int32_t), table.data());
    residency_.clearChanged();
  }
  FrameStats stats = drawInstances(view, settings, instances_, lodFirstInstance_);
  stats.tilesLoaded = std::uint64_t(frame_.uploads);
  stats.uploadBytes = uploadBytes;
  stats.cacheMisses = std::uint64_t(frame_.misses);
  stats.tilesWanted = std::uint64_t(frame_.tilesWanted);
  stats.tilesResident = std::uint64_t(residency_.residentCount());
  const double workerCpuSeconds = cache_->stats().workerCpuSeconds;
  stats.backgroundCpuMs = (workerCpuSeconds - reportedWorkerCpuSeconds_) * 1e3;
  reportedWorkerCpuSeconds_ = workerCpuSeconds;
  return stats;
}

bool RingsRenderer::instanceIsResident(const PatchInstance& instance) const {
  const auto resident = [&](int level, int x, int y) {
    if (x < 0 || y < 0 || x >= patchesX_ || y >= patchesY_) return true;  // not read
    return residency_.slotOf({level, x >> level, y >> level}) >= 0;
  };
  const int level = instance.levels & 31;
  if (!resident(level, instance.x, instance.y)) return false;
  for (std::size_t e = 0; e < kEdgeNeighbour.size(); ++e) {
    const int edgeLevel = (instance.levels >> (5 + 5 * int(e))) & 31;
    if (!resident(edgeLevel, instance.x, instance.y) ||
        !resident(edgeLevel, instance.x + kEdgeNeighbour[e][0],
                  instance.y + kEdgeNeighbour[e][1])) {
      return false;
    }
  }
  return true;
}

bool RingsRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (previousLodFirstInstance_.empty()) return false;
  // The previous frame's patches, less any whose tiles have been evicted since (their pixels
  // stay empty and are not measured).
  std::vector<PatchInstance> instances;
  std::vector<int> firstInstance;
  for (std::size_t lod = 0; lod + 1 < previousLodFirstInstance_.size(); ++lod) {
    firstInstance.push_back(int(instances.size()));
    for (int i = previousLodFirstInstance_[lod]; i < previousLodFirstInstance_[lod + 1]; ++i) {
      const PatchInstance& instance = previousInstances_[std::size_t(i)];
      if (instanceIsResident(instance)) instances.push_back(instance);
    }
  }
  firstInstance.push_back(int(instances.size()));
  drawInstances(view, settings, instances, firstInstance);
  return true;
}

FrameStats RingsRenderer::drawInstances(const ViewSetup& view, const RenderSettings& settings,
                                        const std::vector<PatchInstance>& instances,
                                        const std::vector<int>& lodFirstInstance) {
  if (!instances.empty()) {
    instanceBuffer_.upload(0, instances.size() * sizeof(PatchInstance), instances.data());
  }

  // Camera in level-0 sample coordinates: integer part and remainder in metres.
  const glm::dvec3& camera = view.camera.position;
  const auto [col, row] = sampleCoordinates(camera);
  const glm::ivec2 cameraSample(int(std::floor(col)), int(std::floor(row)));
  const glm::vec2 cameraFraction(float((col - std::floor(col)) * spacingXM_),
                                 float((row - std::floor(row)) * spacingYM_));
  for (const gl::Program* program : {&fill_, &wire_}) {
    program->set("uViewProjection", glm::mat4(view.relativeViewProjection()));
    program->set("uCameraSample", cameraSample);
    program->set("uCameraFraction", cameraFraction);
    program->set("uCameraHeight", float(camera.z));
    program->set("uExaggeration", settings.verticalExaggeration);
  }
  applyShadingMode(fill_, view, settings);

  heights_.bindUnit(0);
  pageTable_.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  slotErrorBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  vertexArray_.bind();
  FrameStats stats;
  drawWithWireframeOverlay(
      settings.wireframe, wire_, view,
      [&] { drawPass(fill_, false, lodFirstInstance, &stats); },
      [&] { drawPass(wire_, true, lodFirstInstance, nullptr); });
  return stats;
}

std::vector<std::string> RingsRenderer::frameReport() const {
  const RingsFrameInfo& r = frame_;
  std::vector<std::string> lines{fmt::format("patches: {} of {} drawn, {} from coarser data",
                                             r.visiblePatches, r.windowPatches, r.fallbackPatches)};
  if (r.fractalIterations > 0) lines.push_back(fmt::format("fractal iterations {}", r.fractalIterations));
  return lines;
}

}  // namespace tellus
