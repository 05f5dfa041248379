#include "tellus/render/ringo/ringo_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>

#include <glm/matrix.hpp>
#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/frustum.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/core/thread_cpu_clock.hpp"
#include "tellus/lod/globe/globe_mesh.hpp"
#include "tellus/lod/ringo/ringo_block_data.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {
namespace {

// Unused block buffers freed per frame beyond what the pool keeps (trim()).
constexpr std::size_t kFreedBytesPerFrame = std::size_t(4) << 20;

// x mod m in 0 .. m - 1.
std::int64_t wrap(std::int64_t x, std::int64_t m) {
  const std::int64_t r = x % m;
  return r < 0 ? r + m : r;
}

// The shortest signed step from column `from` to column `to` round a row of `columns` tiles.
int columnStep(std::int64_t from, std::int64_t to, int columns) {
  std::int64_t step = wrap(to - from, columns);
  if (step > columns / 2) step -= columns;
  return int(step);
}

}  // namespace

Result<std::unique_ptr<RingoRenderer>> RingoRenderer::create(
    std::shared_ptr<const GlobalStore> store, RingoOptions options) {
  if (!store) return makeError("the RINGO renderer draws a global store (tellus build --global)");
  if (options.rings < 0 || options.rings > 8) {
    return makeError("RINGO takes 0 to 8 rings, got {}", options.rings);
  }
  if (!(options.blocksToHorizon >= 0.5 && options.blocksToHorizon <= 100.0)) {
    return makeError("RINGO takes 0.5 to 100 blocks to the horizon, got {}",
                     options.blocksToHorizon);
  }
  if (options.threads < 0) return makeError("RINGO threads must be 0 (all) or more");
  if (options.morphFrames < 0 || options.morphFrames > 1000) {
    return makeError("RINGO morphs over 0 to 1000 frames, got {}", options.morphFrames);
  }
  if (options.uploadKiBPerFrame < 1) {
    return makeError("RINGO needs at least 1 KiB of uploads per frame, got {}",
                     options.uploadKiBPerFrame);
  }
  std::unique_ptr<RingoRenderer> renderer(new RingoRenderer());
  renderer->store_ = std::move(store);
  renderer->options_ = options;
  renderer->layout_ = {.rings = options.rings, .tileCells = renderer->store_->tileCells()};
  // Room for three matrices' blocks: a depth change fills one while another draws, and the
  // last frame's selection (kept one frame) may still hold a third.
  std::size_t matrixBytes = 0;
  const int half = renderer->layout_.side() / 2;
  for (int dy = -half; dy <= half; ++dy) {
    for (int dx = -half; dx <= half; ++dx) {
      const int cells = renderer->layout_.cellsAt(RingoLayout::levelAt(dx, dy));
      matrixBytes += std::size_t(cells + 1) * std::size_t(cells + 1) * sizeof(RingoVertex);
    }
  }
  // The pool keeps up to three matrices' worth (the drawn one, the one filling and the last
  // frame's) and starts with them: a fresh mapped buffer costs the render thread about 1 ms
  // per MiB on llvmpipe (its pages are touched), so buffers are made while loading, not while
  // flying (a descent changes depth every few frames).
  constexpr int kPooledMatrices = 3;
  renderer->pool_.emplace(renderer->indexBuffers_, kPooledMatrices * matrixBytes);
  std::vector<RingoBlockBuffers> warm;
  for (int copy = 0; copy < kPooledMatrices; ++copy) {
    for (int dy = -half; dy <= half; ++dy) {
      for (int dx = -half; dx <= half; ++dx) {
        warm.push_back(renderer->pool_->acquire(
            renderer->layout_.cellsAt(RingoLayout::levelAt(dx, dy))));
      }
    }
  }
  for (RingoBlockBuffers& buffers : warm) renderer->pool_->release(std::move(buffers));
  renderer->pool_->fenceReleased();
  Result<FillAndWirePrograms> programs =
      loadFillAndWirePrograms("ringo/ringo.vert", "globe/globe.frag");
  if (!programs) return programs.error();
  renderer->fill_ = std::move(programs->fill);
  renderer->wire_ = std::move(programs->wire);
  Result<GlobeSky> sky = GlobeSky::create();
  if (!sky) return sky.error();
  renderer->sky_ = std::move(sky.value());
  return renderer;
}

RingoRenderer::~RingoRenderer() {
  copies_->wait();  // they write into buffers this renderer owns
}

void RingoRenderer::startMatrix(int depth, const GeoTileKey& centre,
                                std::shared_ptr<const RingoMorphSource> morphFrom) {
  Matrix fresh;
  fresh.blocks.emplace(layout_, depth, centre.x, centre.y);
  fresh.slots.resize(std::size_t(fresh.blocks->slotCount()));
  fresh.reorganiser = std::make_unique<RingoReorganiser>(
      layout_, fresh.blocks->slotCount(),
      [store = store_, layout = layout_](const RingoBlock& block) {
        return loadRingoBlock(*store, layout, block);
      },
      options_.geoid, options_.threads);
  fresh.reorganiser->setMorphSource(morphFrom);
  fresh.morphFrom = std::move(morphFrom);
  fresh.morphRemaining = fresh.morphFrom ? 1.0f : 0.0f;
  submitMove(fresh, ringoInitialUpdates(*fresh.blocks));
  retire(current_);
  current_ = std::move(fresh);
  ++matrixGeneration_;  // copies in flight for the old matrix are dropped when they end
}

std::shared_ptr<const RingoMorphSource> RingoRenderer::captureMorphSource(Matrix& drawn) const {
  drawn.morphFrozen = true;
  if (options_.morphFrames <= 0 || !drawn.blocks) return nullptr;
  auto source = std::make_shared<RingoMorphSource>(drawn.blocks->depth(), drawn.morphRemaining);
  for (const std::shared_ptr<const GpuBlock>& slot : drawn.slots) {
    if (!slot || !slot->heights) continue;
    source->add(slot->block.key, {slot->gpu.cells, slot->heights, slot->morphDeltas});
  }
  return source->empty() ? nullptr : std::move(source);
}

RingoRenderer::Matrix& RingoRenderer::drawnMatrix() {
  return filled(current_) || !previous_.blocks ? current_ : previous_;
}

void RingoRenderer::submitMove(Matrix& matrix, std::vector<RingoBlockUpdate> updates) {
  const std::size_t count = updates.size();
  const std::int64_t move = matrix.reorganiser->submit(std::move(updates));
  if (move >= 0) matrix.moveSizes[std::uint64_t(move)] = count;
}

void RingoRenderer::retire(Matrix& matrix) {
  if (matrix.reorganiser) {
    matrix.reorganiser->cancelQueued();
    retiring_.push_back(std::move(matrix.reorganiser));
  }
  matrix = Matrix{};
}

double RingoRenderer::workerCpuSeconds() const {
  double seconds = retiredWorkerCpuSeconds_ + 1e-9 * double(copyCpuNanoseconds_.load());
  for (const Matrix* m : {&current_, &previous_}) {
    if (m->reorganiser) seconds += m->reorganiser->stats().workerCpuSeconds;
  }
  for (const auto& r : retiring_) seconds += r->stats().workerCpuSeconds;
  return seconds;
}

void RingoRenderer::uploadReady(std::size_t budgetBytes, bool wait) {
  installCopied();
  while (budgetBytes > 0 || wait) {
    std::vector<RingoReadyBlock> next = current_.reorganiser->takeReady(1);
    if (next.empty()) break;
    RingoReadyBlock& ready = next.front();
    auto upload = std::make_unique<PendingUpload>();
    upload->generation = matrixGeneration_;
    upload->move = ready.move;
    upload->slot = ready.slot;
    upload->failed = ready.failed;
    if (ready.failed || !ready.block.exists) {  // the slot keeps its block / empties, in turn
      upload->copied.store(true);
      copying_.push_back(std::move(upload));
      continue;
    }
    // The block's buffers go back to the pool when the last frame that draws it is done.
    std::shared_ptr<GpuBlock> block(new GpuBlock, [pool = &*pool_](GpuBlock* b) {
      pool->release(std::move(b->gpu));
      delete b;
    });
    block->block = ready.block;
    block->bounds = ready.mesh.bounds;
    block->heights = std::make_shared<const std::vector<float>>(std::move(ready.heights));
    if (!ready.mesh.morphDeltasM.empty()) {
      block->morphDeltas =
          std::make_shared<const std::vector<float>>(std::move(ready.mesh.morphDeltasM));
    }
    block->gpu = pool_->acquire(ready.mesh.cells);
    const std::size_t bytes = ready.mesh.vertices.size() * sizeof(RingoVertex);
    budgetBytes -= std::min(budgetBytes, bytes);
    info_.uploadBytes += bytes;
    upload->block = std::move(block);
    upload->vertices = std::move(ready.mesh.vertices);
    // A worker copies the vertices into the mapped buffer (and frees them there).
    copies_->run([this, u = upload.get(), bytes] {
      const double start = threadCpuSeconds();
      std::memcpy(u->block->gpu.mapped, u->vertices.data(), bytes);
      std::vector<RingoVertex>().swap(u->vertices);
      copyCpuNanoseconds_.fetch_add(std::int64_t((threadCpuSeconds() - start) * 1e9));
      u->copied.store(true, std::memory_order_release);
    });
    copying_.push_back(std::move(upload));
  }
  if (wait) {
    copies_->wait();
    installCopied();
  }
}

void RingoRenderer::installCopied() {
  // Copies for matrices since abandoned go once they have ended.
  std::erase_if(copying_, [this](const std::unique_ptr<PendingUpload>& u) {
    return u->generation != matrixGeneration_ && u->copied.load(std::memory_order_acquire);
  });
  // Moves are shown whole, oldest first: half a move could put blocks two levels apart side
  // by side (a crack), a whole one leaves the matrix as recentre() made it.
  std::map<std::uint64_t, std::size_t>& moves = current_.moveSizes;
  while (!moves.empty()) {
    const auto [move, size] = *moves.begin();
    std::size_t arrived = 0;
    bool copied = true;
    for (const auto& u : copying_) {
      if (u->generation != matrixGeneration_ || u->move != move) continue;
      ++arrived;
      copied = copied && u->copied.load(std::memory_order_acquire);
    }
    if (arrived < size || !copied) return;
    for (auto& u : copying_) {
      if (u->generation != matrixGeneration_ || u->move != move) continue;
      // The old block goes (its buffers once no kept selection holds them).
      if (!u->failed) current_.slots[std::size_t(u->slot)] = std::move(u->block);
      ++info_.uploads;
      u.reset();
    }
    std::erase_if(copying_, [](const std::unique_ptr<PendingUpload>& u) { return !u; });
    moves.erase(move);
  }
}

bool RingoRenderer::covers(const Matrix& matrix, double latDeg, double lonDeg) const {
  if (!matrix.blocks) return false;
  const GeoTileKey under = GlobalTiling::tileAt(matrix.blocks->depth(), latDeg, lonDeg);
  const int columns = GlobalTiling::tilesX(under.depth);
  const int dx = columnStep(wrap(matrix.blocks->centreX(), columns), under.x, columns);
  const int half = layout_.side() / 2;
  return std::abs(dx) <= half && std::abs(under.y - matrix.blocks->centreY()) <= half;
}

bool RingoRenderer::filled(const Matrix& matrix) const {
  if (!matrix.blocks) return false;
  for (int i = 0; i < matrix.blocks->slotCount(); ++i) {
    if (matrix.blocks->slot(i).exists && !matrix.slots[std::size_t(i)]) return false;
  }
  return true;
}

double RingoRenderer::groundUnderM(double latDeg, double lonDeg) const {
  const Matrix& matrix = filled(current_) || !previous_.blocks ? current_ : previous_;
  if (!matrix.blocks) return std::numeric_limits<double>::quiet_NaN();
  const GeoTileKey key = GlobalTiling::tileAt(matrix.blocks->depth(), latDeg, lonDeg);
  for (const std::shared_ptr<const GpuBlock>& slot : matrix.slots) {
    if (!slot || slot->block.key != key || !slot->heights || slot->heights->empty()) continue;
    const GeoBounds box = GlobalTiling::bounds(key);
    const int cells = slot->gpu.cells;
    const double u = (lonDeg - box.westDeg) / (box.eastDeg - box.westDeg) * cells;
    const double v = (box.northDeg - latDeg) / (box.northDeg - box.southDeg) * cells;
    double h = ringoDrawnHeight(*slot->heights, cells, u, v);
    if (slot->morphDeltas && matrix.morphRemaining > 0.0f) {  // as drawn, mid-morph
      h += double(matrix.morphRemaining) * ringoDrawnHeight(*slot->morphDeltas, cells, u, v);
    }
    return options_.geoid ? options_.geoid->ellipsoidalHeightM(h, latDeg, lonDeg) : h;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

int RingoRenderer::deepestStoredAround(const GeoTileKey& centre) {
  if (deepestAround_ && deepestAround_->first == centre) return deepestAround_->second;
  const int half = layout_.side() / 2;
  const int columns = GlobalTiling::tilesX(centre.depth), rows = GlobalTiling::tilesY(centre.depth);
  int deepest = 0;
  for (int dy = -half; dy <= half; ++dy) {
    const int y = centre.y + dy;
    if (y < 0 || y >= rows) continue;
    for (int dx = -half; dx <= half; ++dx) {
      const GeoTileKey key{centre.depth, int(wrap(centre.x + dx, columns)), y};
      deepest = std::max(deepest, store_->deepestStored(key).depth);
    }
  }
  deepestAround_ = {centre, deepest};
  return deepest;
}

double RingoRenderer::storeGroundM(double latDeg, double lonDeg) const {
  const GeoTileKey key = store_->deepestStored(
      GlobalTiling::tileAt(store_->metadata().deepestDepth, latDeg, lonDeg));
  std::vector<float> heights(store_->tileShape().sampleCount());
  if (!store_->readTileMetres(key, heights)) return 0.0;
  const int n = store_->tileCells();
  const GeoBounds box = GlobalTiling::bounds(key);
  const double u = (lonDeg - box.westDeg) / (box.eastDeg - box.westDeg) * n;
  const double v = (box.northDeg - latDeg) / (box.northDeg - box.southDeg) * n;
  const double h = tileSurfaceAt(heights, n, u, v);
  return options_.geoid ? options_.geoid->ellipsoidalHeightM(h, latDeg, lonDeg) : h;
}

void RingoRenderer::prepare(const ViewSetup& view, const RenderSettings&) {
  const wgs84::Geodetic eye = wgs84::ecefToGeodetic(view.camera.position);
  const double lat = eye.latRad / wgs84::kDegree, lon = eye.lonRad / wgs84::kDegree;
  // Blocks whose copies ended since the last frame are shown first: a matrix they complete
  // lets the depth below move on in this frame rather than the next.
  installCopied();
  // The ground under the viewer as drawn; where no block is drawn under it (yet), the last
  // ground known, and before the first matrix one tile read from the store.
  const double groundBefore = lastGroundM_;
  double ground = groundUnderM(lat, lon);
  if (!std::isfinite(ground)) {
    ground = std::isfinite(groundBefore) ? groundBefore : storeGroundM(lat, lon);
  }
  lastGroundM_ = ground;
  const double groundM = std::isfinite(ground) ? ground : 0.0;
  const double clearance = eye.heightM - groundM;
  // A matrix started now is drawn two frames later (built and copied on the workers, then
  // installed): while descending, the depth is planned for the clearance the viewer will have
  // by then (its own descent, not the ground's rise and fall, extrapolated).
  const double planned = ringoPlannedClearanceInFlight(eye.heightM, lastEyeHeightM_, groundM,
                                                       groundBefore, kRingoMatrixLatencyFrames);
  lastEyeHeightM_ = eye.heightM;
  // How far the ideal depth moved since the last frame (log4 of the clearances' ratio): the
  // morph keeps up with it.
  depthsMovedThisFrame_ = 0.0;
  if (std::isfinite(lastClearanceM_) && lastClearanceM_ > 1.0 && clearance > 1.0) {
    depthsMovedThisFrame_ = std::abs(std::log(clearance / lastClearanceM_)) / std::log(4.0);
  }
  lastClearanceM_ = clearance;
  // Where the viewer will be when a matrix started now is drawn: matrices are centred there.
  const RingoLatLon plannedEye =
      ringoPlannedPosition({lat, lon}, lastEye_, kRingoMatrixLatencyFrames);
  lastEye_ = {lat, lon};
  // The depth the clearance asks for, capped by the finest data within the matrix's reach at
  // that depth (over the sea near a coast, the land ahead is what needs the depth).
  const int current = current_.blocks ? current_.blocks->depth() : -1;
  const int wanted = ringoDepthFor(planned, store_->metadata().deepestDepth, layout_, current,
                                   options_.blocksToHorizon);
  const int deepest =
      deepestStoredAround(GlobalTiling::tileAt(wanted, plannedEye.latDeg, plannedEye.lonDeg));
  int depth = ringoDepthFor(planned, deepest, layout_, current, options_.blocksToHorizon);
  // A matrix being filled is finished before the next depth starts (while it still has the
  // ground under the viewer): abandoning it for every depth a fast descent passes would leave
  // an ever older matrix on screen.
  if (current >= 0 && depth != current && !filled(current_) && covers(current_, lat, lon)) {
    depth = current;
  }
  const GeoTileKey centre = GlobalTiling::tileAt(depth, plannedEye.latDeg, plannedEye.lonDeg);
  spdlog::debug("ringo: clearance {:.1f} m (planned {:.1f} m, ground {:.1f} m), depth {} (wanted "
                "{}, store {}, current {}), centre {}/{}/{}",
                clearance, planned, ground, depth, wanted, deepest,
                filled(current_) ? "filled" : "filling",
                centre.depth, centre.x, centre.y);
  // Abandoned matrices' reorganisers go once their running move has ended.
  std::erase_if(retiring_, [this](const std::unique_ptr<RingoReorganiser>& r) {
    if (r->working()) return false;
    retiredWorkerCpuSeconds_ += r->stats().workerCpuSeconds;
    return true;
  });
  if (!current_.blocks || current_.blocks->depth() != depth) {
    // The new matrix morphs from what is drawn now, which stops morphing.
    std::shared_ptr<const RingoMorphSource> morphFrom = captureMorphSource(drawnMatrix());
    // The drawable matrix keeps drawing until the new one is drawable.
    if (filled(current_)) {
      retire(previous_);
      previous_ = std::move(current_);
    }
    startMatrix(depth, centre, std::move(morphFrom));
  } else {
    RingoBlockMatrix& blocks = *current_.blocks;
    const int step = columnStep(blocks.centreX(), centre.x, GlobalTiling::tilesX(depth));
    if (step != 0 || centre.y != blocks.centreY()) {
      submitMove(current_, blocks.recentre(blocks.centreX() + step, centre.y));
    }
  }
  info_.uploads = 0;
  info_.uploadBytes = 0;
  // Stills wait for every block; so does the very first matrix (nothing to draw meanwhile:
  // loading the scene), and a new matrix whose complete predecessor has no block under the
  // viewer (a jump across the globe, not a flight). Otherwise the new matrix streams in while
  // the previous one draws.
  const bool nothingToDraw =
      !previous_.blocks && std::none_of(current_.slots.begin(), current_.slots.end(),
                                        [](const auto& slot) { return bool(slot); });
  const bool jumped = previous_.blocks && !covers(previous_, lat, lon);
  const bool wait = options_.waitForBlocks || nothingToDraw || jumped;
  if (wait) current_.reorganiser->waitIdle();
  uploadReady(std::size_t(options_.uploadKiBPerFrame) * 1024, wait);
  pool_->trim(kFreedBytesPerFrame);
  if (filled(current_)) retire(previous_);
  info_.depth = depth;
  info_.reorganising = !current_.reorganiser->idle();
  info_.reorganiser = current_.reorganiser->stats();
  info_.blocksResident = 0;
  for (const auto& slot : current_.slots) info_.blocksResident += slot ? 1 : 0;
}

std::vector<RingoRenderer::DrawnBlock> RingoRenderer::selection(const Matrix& matrix) const {
  std::vector<DrawnBlock> blocks;
  if (!matrix.blocks) return blocks;
  const int depth = matrix.blocks->depth();
  const int columns = GlobalTiling::tilesX(depth), rows = GlobalTiling::tilesY(depth);
  std::map<GeoTileKey, int> drawnCells;  // tile -> cells of the block drawn there
  for (const std::shared_ptr<const GpuBlock>& slot : matrix.slots) {
    if (slot) drawnCells[slot->block.key] = slot->gpu.cells;
  }
  const auto cellsAt = [&](int x, int y) {
    if (y < 0 || y >= rows) return 0;  // beyond a pole: no neighbour
    const auto it = drawnCells.find({depth, int(wrap(x, columns)), y});
    return it == drawnCells.end() ? 0 : it->second;
  };
  for (const std::shared_ptr<const GpuBlock>& slot : matrix.slots) {
    if (!slot) continue;
    const GeoTileKey& k = slot->block.key;
    const int cells = slot->gpu.cells;
    const auto coarser = [&](int neighbourCells) {
      return neighbourCells > 0 && neighbourCells < cells;
    };
    std::uint32_t mask = 0;
    if (coarser(cellsAt(k.x, k.y - 1))) mask |= kRingoNorth;
    if (coarser(cellsAt(k.x + 1, k.y))) mask |= kRingoEast;
    if (coarser(cellsAt(k.x, k.y + 1))) mask |= kRingoSouth;
    if (coarser(cellsAt(k.x - 1, k.y))) mask |= kRingoWest;
    blocks.push_back({slot, mask, matrix.morphRemaining});
  }
  return blocks;
}

void RingoRenderer::drawBlocks(std::span<const DrawnBlock> blocks, const gl::Program& program,
                               const ViewSetup& view, FrameStats* stats) {
  program.use();
  program.set("uViewProjection", glm::mat4(view.relativeViewProjection()));
  glm::ivec3 eyeWhole;
  glm::vec3 eyeFraction;
  globe::splitEcef(view.camera.position, eyeWhole, eyeFraction);
  program.set("uEyeWhole", eyeWhole);
  program.set("uEyeFraction", eyeFraction);
  const Frustum frustum = Frustum::fromMatrix(view.relativeViewProjection());
  const glm::dvec3& eye = view.camera.position;
  for (const DrawnBlock& drawn : blocks) {
    const GpuBlock& slot = *drawn.block;
    if (!frustum.intersects({slot.bounds.min - eye, slot.bounds.max - eye})) continue;
    program.set("uCoarserEdges", int(drawn.coarserEdges));
    program.set("uMorphRemaining", drawn.morphRemaining);
    slot.gpu.vertexArray.bind();
    const auto indexCount = GLsizei(slot.gpu.indices->size() / sizeof(std::uint32_t));
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    if (stats) {
      stats->triangles += std::uint64_t(indexCount / 3);
      stats->vertices += std::uint64_t(slot.gpu.cells + 1) * std::uint64_t(slot.gpu.cells + 1);
      ++stats->drawCalls;
    }
  }
}

FrameStats RingoRenderer::drawSelection(std::span<const DrawnBlock> blocks, const ViewSetup& view,
                                        const RenderSettings& settings) {
  const glm::vec3 sun = globeSunEcef(view, settings);
  if (settings.sky) sky_->draw(view, sun);
  setGlobeFillUniforms(fill_, view, settings, sun);
  fill_.set("uDrapeEnabled", false);
  // wire.frag fades lines by the cell size: the central blocks' cells on the ground.
  const int depth = blocks.empty() ? 0 : blocks.front().block->block.key.depth;
  const double cellM = GlobalTiling::tileSizeDeg(depth) * 111'320.0 / layout_.tileCells;
  wire_.set("uSpacing", glm::vec2(float(cellM), float(cellM)));
  FrameStats stats;
  drawWithWireframeOverlay(
      settings.wireframe, wire_, view, [&] { drawBlocks(blocks, fill_, view, &stats); },
      [&] { drawBlocks(blocks, wire_, view, nullptr); });
  return stats;
}

FrameStats RingoRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  Matrix& drawn = drawnMatrix();
  if (drawn.morphFrom && !drawn.morphFrozen) {
    drawn.morphRemaining =
        ringoMorphStep(drawn.morphRemaining, options_.morphFrames, depthsMovedThisFrame_);
    if (drawn.morphRemaining <= 0.0f) {  // morphed: blocks built from now on need no deltas
      drawn.morphFrom.reset();
      drawn.reorganiser->setMorphSource(nullptr);
    }
  }
  info_.morphRemaining = drawn.morphRemaining;
  drawnBefore_ = std::move(lastDrawn_);
  lastDrawn_ = selection(drawn);
  FrameStats stats = drawSelection(lastDrawn_, view, settings);
  // The buffers let go since the last frame (the selection before last, a retired matrix)
  // become reusable once the GPU is past this frame's commands: by the next frame's uploads.
  pool_->fenceReleased();
  info_.blocksDrawn = int(stats.drawCalls);
  stats.tilesLoaded = std::uint64_t(info_.uploads);
  stats.uploadBytes = std::uint64_t(info_.uploadBytes);
  stats.tilesResident = std::uint64_t(info_.blocksResident);
  const double workerCpu = workerCpuSeconds();
  stats.backgroundCpuMs = (workerCpu - reportedWorkerCpuSeconds_) * 1e3;
  reportedWorkerCpuSeconds_ = workerCpu;
  return stats;
}

bool RingoRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (drawnBefore_.empty()) return false;
  drawSelection(drawnBefore_, view, settings);
  return true;
}

std::vector<std::string> RingoRenderer::frameReport() const {
  const RingoFrameInfo& r = info_;
  return {fmt::format("blocks: depth {}, {} drawn, {} resident", r.depth, r.blocksDrawn,
                      r.blocksResident),
          fmt::format("uploads: {} blocks, {} KiB{}", r.uploads, r.uploadBytes / 1024,
                      r.reorganising ? "  (reorganising)" : ""),
          fmt::format("reorganised: {} loaded, {} derived, worker CPU {:.2f} s", r.reorganiser.loaded,
                      r.reorganiser.derived, r.reorganiser.workerCpuSeconds),
          fmt::format("morph from the previous depth: {:.0f} % to go", 100.0 * r.morphRemaining)};
}

}  // namespace tellus
