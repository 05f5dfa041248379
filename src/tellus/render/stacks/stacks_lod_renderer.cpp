#include "tellus/render/stacks/stacks_lod_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "tellus/core/frustum.hpp"
#include "tellus/core/stopwatch.hpp"
#include "tellus/core/thread_cpu_clock.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/lod/stacks/seam_blend.hpp"
#include "tellus/lod/stacks/stitched_quadrangulation.hpp"

namespace tellus {
namespace {

// The neighbourBit()s of `key`'s 26 neighbours on its level for which `alike(packed key)` is
// false.
template <class Alike>
std::uint32_t unlikeMask(const OctreeKey& key, const Alike& alike) {
  std::uint32_t unlike = 0;
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        const OctreeKey neighbour{key.level, key.x + dx, key.y + dy, key.z + dz};
        if (!alike(neighbour.packed())) unlike |= 1u << neighbourBit(dx, dy, dz);
      }
    }
  }
  return unlike;
}

// glMultiDrawElementsIndirect's command.
struct DrawCommand {
  std::uint32_t count, instanceCount, firstIndex, baseVertex, baseInstance;
};

NodeMeshKey meshKey(const SelectedNode& node) { return {node.key.packed(), node.stitchMask}; }

constexpr int kBatchNodes = 256;

}  // namespace

StacksLodRenderer::StacksLodRenderer(StackLevels levels, const StacksRenderOptions& options,
                                     bool waitForMeshes, std::uint32_t vertexCapacity,
                                     std::uint32_t indexCapacity)
    : levels_(std::move(levels)),
      options_(options),
      waitForMeshes_(waitForMeshes),
      cache_(vertexCapacity, indexCapacity) {}

Result<std::unique_ptr<StacksLodRenderer>> StacksLodRenderer::create(
    const std::vector<StackTerrain>& pyramid, const StacksRenderOptions& options,
    bool waitForMeshes) {
  if (pyramid.empty()) return makeError("the stack terrain has no level");
  if (!(options.tauPx > 0.0) || !std::isfinite(options.tauPx)) {
    return makeError("the screen-space threshold tau must be positive (got {} px)", options.tauPx);
  }
  if (!(options.errorTauPx >= 0.0) || !std::isfinite(options.errorTauPx)) {
    return makeError("the geometric error threshold must be 0 (off) or positive (got {} px)",
                     options.errorTauPx);
  }
  if (options.updatesPerFrame < 0) {
    return makeError("quadrangulations per frame must be 0 (no limit) or more (got {})",
                     options.updatesPerFrame);
  }
  if (options.poolMiB < 1 || options.poolMiB > 16384) {
    return makeError("the mesh pool must be 1 to 16384 MiB (got {})", options.poolMiB);
  }
  const Stopwatch sinceStart;
  const double cellM = options.cellM > 0.0 ? options.cellM : pyramid.front().spacingM();
  Result<StackLevels> levels = StackLevels::build(pyramid, cellM, options.quad);
  if (!levels) return levels.error();
  if (options.seamBandCells < 0) {
    return makeError("the seam blend band must be 0 (off) or more cells (got {})", options.seamBandCells);
  }
  // Two thirds of the pool for vertices (48 bytes, 80 with a geomorph target, which stills do
  // not need; the seam blend is baked into the vertices), a third for indices (about 1 vertex
  // and 6 indices a quad).
  const bool slides = options.morphFrames > 0 && !waitForMeshes;
  const std::uint64_t bytes = std::uint64_t(options.poolMiB) << 20;
  const auto vertexCapacity = std::uint32_t(
      bytes * 2 / 3 / (sizeof(StackVertex) + (slides ? sizeof(MorphTarget) : 0)));
  const auto indexCapacity = std::uint32_t(bytes / 3 / sizeof(std::uint32_t));
  std::unique_ptr<StacksLodRenderer> r(new StacksLodRenderer(
      std::move(levels.value()), options, waitForMeshes, vertexCapacity, indexCapacity));
  r->pyramid_ = pyramid;
  r->slides_ = slides;
  r->seamBand_ = std::min(options.seamBandCells, seamBandLimit(options.quad.nodeCells));
  r->octree_ = std::make_unique<StackOctree>(r->levels_);
  // 256 nodes a batch: a dozen dispatches make that many meshes (fewer, larger dispatches when
  // a frame asks for thousands), for about 0.9 MB of scratch volumes a node.
  Result<StackQuadPipelineGpu> pipeline = StackQuadPipelineGpu::create(r->levels_, kBatchNodes);
  if (!pipeline) return pipeline.error();
  r->pipeline_ = std::make_unique<StackQuadPipelineGpu>(std::move(pipeline.value()));
  r->pipeline_->setSeamBandCells(r->seamBand_);
  Result<StackMeshCopy> meshCopy = StackMeshCopy::create();
  if (!meshCopy) return meshCopy.error();
  r->meshCopy_ = std::make_unique<StackMeshCopy>(std::move(meshCopy.value()));
  // A first staging for a batch of meshes of about 1,000 vertices each; it grows as needed.
  const auto firstVertices = std::uint32_t(r->pipeline_->batchNodes() * 1024);
  r->staging_ = std::make_unique<StackMeshStaging>(slides, firstVertices, 6 * firstVertices);
  r->vertexPool_ = gl::Buffer(std::size_t(vertexCapacity) * sizeof(StackVertex), nullptr);
  r->indexPool_ = gl::Buffer(std::size_t(indexCapacity) * sizeof(std::uint32_t), nullptr);
  if (slides) r->morphPool_ = gl::Buffer(std::size_t(vertexCapacity) * sizeof(MorphTarget), nullptr);
  Result<FillAndWirePrograms> programs =
      loadFillAndWirePrograms("stacks/stacks.vert", "stacks/stacks.frag");
  if (!programs) return programs.error();
  r->programs_ = std::move(programs.value());
  r->vertexArray_ = gl::VertexArray::create();
  r->vertexArray_.setIndexBuffer(r->indexPool_);
  spdlog::info("stacks: {} levels quantised, octree top level {}, {} MiB mesh pool, in {:.2f} s",
               r->levels_.count(), r->octree_->topLevel(), options.poolMiB,
               sinceStart.elapsedS());
  return r;
}

Result<StacksEditReport> StacksLodRenderer::applyEdit(const SphereEdit& edit) {
  gl::finish();  // the frames drawn before are done: what follows is the edit's own time
  selection_.discard();  // the worker reads the levels this edit changes; its selection is stale
  collectMeshes(true);  // made from the stacks before the edit: dropped below where stale
  const Stopwatch wholeEdit;
  Stopwatch stage;
  StacksEditReport report;
  Result<StackRegion> region = applySphereEdit(pyramid_.front(), edit);
  if (!region) return region.error();
  report.region = region.value();
  if (report.region.empty()) return report;
  const std::vector<StackRegion> changed = updatePyramid(pyramid_, report.region);
  report.stacksMs = stage.lapMs();
  if (Status rebuilt = levels_.rebuild(pyramid_, changed); !rebuilt) return rebuilt.error();
  report.levelsMs = stage.lapMs();
  if (Status reloaded = pipeline_->reloadStacks(levels_, changed); !reloaded) return reloaded.error();
  gl::finish();  // the upload's cost belongs to the edit, not to the next frame
  report.uploadMs = stage.lapMs();
  // A node of level k reads its level's stacks over its samples and the smoothing's reach, and
  // (stitched) level k + 1's over about the same region: stale when either changed there.
  const int n = levels_.params().nodeCells;
  const int reach = 2 * (levels_.params().filterRadius + 2);
  const auto overlaps = [&](int level, int x0, int x1, int y0, int y1) {
    if (level >= int(changed.size()) || changed[std::size_t(level)].empty()) return false;
    const StackRegion& c = changed[std::size_t(level)];
    const int h = levels_.level(level).stacks.height;
    // Region rows (row 0 north) to sample y (north up).
    const int sy0 = h - 1 - c.y1, sy1 = h - 1 - c.y0;
    return x0 <= c.x1 && c.x0 <= x1 && y0 <= sy1 && sy0 <= y1;
  };
  report.meshesDropped = cache_.eraseIf([&](std::uint64_t packed) {
    const int level = int(packed >> 48);
    const auto field = [&](int shift) { return int(std::int16_t(std::uint16_t(packed >> shift))); };
    const int ox = field(32) * (n - 1), oy = field(16) * (n - 1);
    if (overlaps(level, ox - reach, ox + n + reach, oy - reach, oy + n + reach)) return true;
    return overlaps(level + 1, ox / 2 - reach, (ox + n) / 2 + reach, oy / 2 - reach,
                    (oy + n) / 2 + reach);
  });
  edited_ = true;
  skyStale_ = true;
  report.editMs = wholeEdit.elapsedMs();
  return report;
}

StacksLodRenderer::NodesInView StacksLodRenderer::nodesInView(const std::vector<SelectedNode>& nodes,
                                                               const BoxCullSet& boxes, const ViewSetup& view,
                                                               float exaggeration, double margin,
                                                               bool visibleToo) const {
  // Widened in clip space: x/w and y/w up to +-margin instead of +-1.
  glm::dmat4 widen(1.0);
  widen[0][0] = widen[1][1] = 1.0 / margin;
  const Frustum wide = Frustum::fromMatrix(widen * view.relativeViewProjection());
  const Frustum own = Frustum::fromMatrix(view.relativeViewProjection());
  NodesInView out;
  if (boxes.size() == nodes.size()) {
    constexpr std::uint8_t kNear = 1, kVisible = 2;
    cullFlags_.assign(nodes.size(), 0);
    boxes.markInside(wide, view.camera.position, exaggeration, kNear, cullFlags_);
    const bool ownTest = visibleToo && margin != 1.0;
    if (ownTest) boxes.markInside(own, view.camera.position, exaggeration, kVisible, cullFlags_);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::uint8_t flags = cullFlags_[i];
      if (!(flags & kNear)) continue;
      out.near.push_back(&nodes[i]);
      if (visibleToo && (!ownTest || (flags & kVisible))) out.visible.push_back(&nodes[i]);
    }
    return out;
  }
  for (const SelectedNode& node : nodes) {
    Aabb box = node.box;
    box.min.z *= exaggeration;
    box.max.z *= exaggeration;
    box.min -= view.camera.position;
    box.max -= view.camera.position;
    if (!wide.intersects(box)) continue;
    out.near.push_back(&node);
    if (visibleToo && (margin == 1.0 || own.intersects(box))) out.visible.push_back(&node);
  }
  return out;
}

std::size_t StacksLodRenderer::requestMeshes(const std::vector<const SelectedNode*>& nodes) {
  const Stopwatch sinceStart;
  const double threadStart = threadCpuSeconds();
  const std::size_t batch = std::size_t(pipeline_->batchNodes());
  std::size_t taken = 0;
  for (std::size_t first = 0; first < nodes.size(); first += batch) {
    const std::size_t size = std::min(batch, nodes.size() - first);
    std::vector<StackQuadPipelineGpu::NodeJob> jobs;
    std::vector<NodeMeshKey> keys;
    for (std::size_t i = 0; i < size; ++i) {
      const SelectedNode& node = *nodes[first + i];
      const StitchGeometry geometry = StitchGeometry::of(*octree_, node.key, node.stitchMask);
      jobs.push_back({octree_->origin(node.key), node.key.level, geometry.parentFirst,
                      node.key.level + 1 < levels_.count() ? node.stitchMask : 0u});
      keys.push_back(meshKey(node));
    }
    Result<bool> added = staging_->add(*pipeline_, jobs, keys);
    if (!added) {
      spdlog::error("stacks: {}", added.error().message);
      break;
    }
    if (!added.value()) break;  // every staging in flight: asked for again next frame
    taken += size;
  }
  last_.quadrangulations += taken;
  last_.quadMs += sinceStart.elapsedMs();
  last_.dispatchThreadMs += (threadCpuSeconds() - threadStart) * 1e3;
  return taken;
}

void StacksLodRenderer::collectMeshes(bool wait) {
  const Stopwatch sinceStart;
  arrivedKeys_.clear();
  turnedAway_.clear();
  staging_->submit();
  staging_->collect(wait, [&](std::span<const NodeMeshKey> keys,
                              std::span<const StackMeshStaging::NodePlacement> placements,
                              const StackMeshStaging::StagingBuffers& from) {
    std::vector<StackMeshCopy::MeshCopy> copies;
    copies.reserve(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const StackMeshStaging::NodePlacement& at = placements[i];
      if (!at.placed()) {  // the staging was too small: asked for again
        turnedAway_.insert(keys[i]);
        continue;
      }
      const std::optional<CachedNodeMesh> placed =
          cache_.insert(keys[i], at.vertexCount, at.indexCount, frame_);
      if (!placed) {
        turnedAway_.insert(keys[i]);
        if (!poolWarned_) {
          spdlog::warn("stacks: the {} MiB mesh pool cannot hold this frame's meshes; raise "
                       "--stack-pool-mib", options_.poolMiB);
          poolWarned_ = true;
        }
        continue;
      }
      ++last_.arrived;
      arrivedKeys_.insert(keys[i]);
      if (at.vertexCount == 0 && at.indexCount == 0) continue;
      copies.push_back({at.firstVertex, placed->firstVertex, at.vertexCount, at.firstIndex,
                        placed->firstIndex, at.indexCount});
    }
    const bool targets = from.morphTargets && morphPool_.id() != 0;
    const double copyStart = threadCpuSeconds();
    meshCopy_->copy(copies, {from.vertices, from.indices, targets ? from.morphTargets : nullptr},
                    {&vertexPool_, &indexPool_, targets ? &morphPool_ : nullptr});
    last_.copyThreadMs += (threadCpuSeconds() - copyStart) * 1e3;
  });
  last_.quadMs += sinceStart.elapsedMs();
  last_.arrivalsMs += sinceStart.elapsedMs();
}

void StacksLodRenderer::makeMeshesNow(const std::vector<const SelectedNode*>& nodes) {
  std::vector<const SelectedNode*> ask = nodes;
  // Again for what a too small staging turned away (it has grown since, up to its bound), as
  // long as each try places some (a pool too small for them all stops it).
  while (!ask.empty()) {
    requestMeshes(ask);
    collectMeshes(true);
    std::vector<const SelectedNode*> again;
    for (const SelectedNode* node : ask) {
      if (!cache_.contains(meshKey(*node))) again.push_back(node);
    }
    if (again.size() == ask.size()) break;
    ask = std::move(again);
  }
}

const CachedNodeMesh* StacksLodRenderer::useMesh(const SelectedNode& node) {
  const auto hintIn = [&](const std::vector<SelectedNode>& nodes,
                          std::vector<NodeMeshCache::SlotHint>& hints) -> NodeMeshCache::SlotHint* {
    const std::less<const SelectedNode*> before;
    if (hints.size() != nodes.size() || before(&node, nodes.data()) || !before(&node, nodes.data() + nodes.size())) {
      return nullptr;
    }
    return &hints[std::size_t(&node - nodes.data())];
  };
  NodeMeshCache::SlotHint* hint = hintIn(*drawn_, drawnHints_);
  if (!hint) hint = hintIn(pending_, pendingHints_);
  return hint ? cache_.use(meshKey(node), frame_, *hint) : cache_.use(meshKey(node), frame_);
}

StacksLodRenderer::MissingMeshes StacksLodRenderer::afterArrivals(MissingMeshes before) const {
  // Nothing else changed for these nodes: a node not in flight before is still neither cached
  // nor in flight, and one still in flight is still missing; an arrival is stamped used in
  // this frame when it is placed (no later placement of the frame evicts it).
  if (arrivedKeys_.empty() && turnedAway_.empty()) return before;
  MissingMeshes out;
  out.toAsk = std::move(before.toAsk);
  for (const SelectedNode* node : before.absent) {
    const NodeMeshKey key = meshKey(*node);
    if (arrivedKeys_.contains(key)) continue;
    ++out.missing;
    out.absent.push_back(node);
    if (turnedAway_.contains(key)) out.toAsk.push_back(node);
  }
  return out;
}

StacksLodRenderer::MissingMeshes StacksLodRenderer::missingMeshes(
    const std::vector<const SelectedNode*>& nodes) {
  MissingMeshes out;
  for (const SelectedNode* node : nodes) {
    if (useMesh(*node)) continue;
    ++out.missing;
    out.absent.push_back(node);
    if (!staging_->inFlight(meshKey(*node))) out.toAsk.push_back(node);
  }
  return out;
}

void StacksLodRenderer::drawSelection(const std::vector<SelectedNode>& selection,
                                      const std::vector<NodeMorphValue>& values,
                                      const ViewSetup& view, const RenderSettings& settings) {
  FrameStats ignored;
  const std::vector<const SelectedNode*> visible =
      nodesInView(selection, BoxCullSet(), view, std::max(settings.verticalExaggeration, 1e-3f)).visible;
  drawNodes(visible, visibleValues(selection, visible, values), view, settings, ignored);
}

bool StacksLodRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (!previous_) return false;
  drawSelection(*previous_, previousValues_, view, settings);
  return true;
}

bool StacksLodRenderer::drawLastFrameBackFaces(const ViewSetup& view, const RenderSettings& settings) {
  if (frame_ == 0) return false;
  RenderSettings fillOnly = settings;
  fillOnly.wireframe = false;
  culledFaces_ = GL_FRONT;
  drawSelection(*drawn_, drawnValues_, view, fillOnly);
  culledFaces_ = GL_BACK;
  return true;
}

std::vector<StacksLodRenderer::NodeMorphValue> StacksLodRenderer::visibleValues(
    const std::vector<SelectedNode>& selection, const std::vector<const SelectedNode*>& visible,
    const std::vector<NodeMorphValue>& values) {
  std::vector<NodeMorphValue> out;
  if (values.size() != selection.size()) return out;
  for (const SelectedNode* node : visible) out.push_back(values[std::size_t(node - selection.data())]);
  return out;
}

std::uint32_t StacksLodRenderer::unlikeNeighbours(std::size_t i) const {
  // The neighbours that do not morph exactly as this one (the shader keeps the border vertices
  // it shares with any of them in place).
  return unlikeMask((*drawn_)[i].key, [&](std::uint64_t neighbour) {
    const auto it = drawnIndex_->find(neighbour);
    return it != drawnIndex_->end() && drawnMorph_[it->second] == drawnMorph_[i];
  });
}

double StacksLodRenderer::morphFactor(const NodeMorph& m) const {
  const int frames = options_.morphFrames;
  if (frames <= 0) return 1.0;
  const double grow =
      m.growStart < 0 ? 1.0 : std::min(1.0, double(std::int64_t(frame_) - m.growStart + 1) / frames);
  const double out =
      m.outStart < 0 ? 1.0 : std::max(0.0, 1.0 - double(std::int64_t(frame_) - m.outStart + 1) / frames);
  return std::min(grow, out);
}

StacksLodRenderer::MorphMaskCheck StacksLodRenderer::checkMorphMasks() const {
  MorphMaskCheck check;
  if (unlikeStale_ || drawnUnlike_.size() != drawn_->size() || drawnMorph_.size() != drawn_->size()) {
    return check;
  }
  for (std::size_t i = 0; i < drawn_->size(); ++i) {
    if (drawnUnlike_[i] == kUnknownMask || morphFactor(drawnMorph_[i]) >= 1.0) continue;
    ++check.checked;
    if (drawnUnlike_[i] != unlikeNeighbours(i)) ++check.wrong;
  }
  return check;
}

std::vector<StacksLodRenderer::NodeMorphValue> StacksLodRenderer::morphValues(
    const std::vector<const SelectedNode*>& near) {
  std::vector<NodeMorphValue> values(drawn_->size());
  if (options_.morphFrames <= 0 || drawnMorph_.size() != drawn_->size()) return values;
  // The masks change only when the nodes' morph timings do (a switch, a new pending
  // selection); they are worked out for the nodes near the view that slide, when first needed.
  // Unknown (kUnknownMask) also for a node far from the view: it pins every border.
  if (unlikeStale_ || drawnUnlike_.size() != drawn_->size()) {
    drawnUnlike_.assign(drawn_->size(), kUnknownMask);
    unlikeStale_ = false;
  }
  for (const SelectedNode* node : near) {
    const auto i = std::size_t(node - drawn_->data());
    if (drawnUnlike_[i] == kUnknownMask && morphFactor(drawnMorph_[i]) < 1.0) drawnUnlike_[i] = unlikeNeighbours(i);
  }
  for (std::size_t i = 0; i < drawn_->size(); ++i) {
    const double f = morphFactor(drawnMorph_[i]);
    if (f < 1.0) values[i] = {float(f), drawnUnlike_[i]};
  }
  return values;
}

void StacksLodRenderer::switchToPending(bool morph) {
  std::vector<NodeMorph> morphs(pending_.size());
  if (morph && pendingDrawnIndexOf_.size() == pending_.size()) {
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      const std::int64_t from = pendingDrawnIndexOf_[i];
      if (from >= 0) {
        morphs[i].growStart = drawnMorph_[std::size_t(from)].growStart;  // still sliding in, maybe
      } else if (from == kSplitIn) {
        morphs[i].growStart = std::int64_t(frame_);  // slides in from the next coarser level's shape
      }
    }
  }
  std::vector<std::int64_t> growStarts(morphs.size());
  for (std::size_t i = 0; i < morphs.size(); ++i) growStarts[i] = morphs[i].growStart;
  drawn_ = std::make_shared<const std::vector<SelectedNode>>(std::move(pending_));
  pending_.clear();
  drawnBoxes_ = std::move(pendingBoxes_);
  pendingBoxes_ = {};
  drawnHints_ = std::move(pendingHints_);
  pendingHints_.clear();
  drawnIndex_ = std::make_shared<const SelectionIndex>(std::move(pendingIndex_));
  pendingIndex_ = {};
  drawnGrowStart_ = std::make_shared<const std::vector<std::int64_t>>(std::move(growStarts));
  pendingDrawnIndexOf_.clear();
  hasPending_ = false;
  drawnChosenFrame_ = pendingChosenFrame_;
  drawnMorph_ = std::move(morphs);
  // The masks of the nodes that split in were worked out beside (the others', when needed).
  const bool masksKnown = morph && pendingSwitchUnlike_.size() == drawn_->size();
  if (masksKnown) drawnUnlike_ = std::move(pendingSwitchUnlike_);
  unlikeStale_ = !masksKnown;
  pendingSwitchUnlike_.clear();
  pendingMerges_ = false;
}

void StacksLodRenderer::drawNodes(const std::vector<const SelectedNode*>& visible,
                                  const std::vector<NodeMorphValue>& morph,
                                  const ViewSetup& view, const RenderSettings& settings,
                                  FrameStats& stats) {
  // One multi-draw of every visible node's mesh at its own shape, one of the morphing ones (a
  // command's base instance picks its node's morph values): a sliding mesh may fold over for a
  // few frames, so those are drawn without back-face culling (no hole where it folds).
  std::vector<DrawCommand> commands, morphing;
  std::vector<NodeMorphValue> nodeMorph, morphingValues;
  for (std::size_t i = 0; i < visible.size(); ++i) {
    const CachedNodeMesh* mesh = useMesh(*visible[i]);
    if (!mesh || mesh->indexCount == 0) continue;
    const NodeMorphValue value = morph.empty() ? NodeMorphValue{} : morph[i];
    const bool slides = value.factor < 1.0f;
    (slides ? morphing : commands).push_back({mesh->indexCount, 1u, mesh->firstIndex, mesh->firstVertex, 0u});
    (slides ? morphingValues : nodeMorph).push_back(value);
    stats.triangles += mesh->indexCount / 3;
    stats.vertices += mesh->vertexCount;
  }
  const std::size_t staticCount = commands.size();
  commands.insert(commands.end(), morphing.begin(), morphing.end());
  nodeMorph.insert(nodeMorph.end(), morphingValues.begin(), morphingValues.end());
  for (std::size_t c = 0; c < commands.size(); ++c) commands[c].baseInstance = std::uint32_t(c);
  stats.drawCalls +=
      std::size_t((staticCount > 0 ? 1 : 0) + (morphing.empty() ? 0 : 1)) * (settings.wireframe ? 2 : 1);
  if (commands.size() > commandCapacity_) {
    commandCapacity_ = std::max<std::size_t>(commands.size() * 2, 256);
    commands_ = gl::Buffer(commandCapacity_ * sizeof(DrawCommand), nullptr, GL_DYNAMIC_STORAGE_BIT);
    nodeMorph_ = gl::Buffer(commandCapacity_ * sizeof(NodeMorphValue), nullptr, GL_DYNAMIC_STORAGE_BIT);
    vertexArray_.setInstanceBuffer(0, nodeMorph_, sizeof(NodeMorphValue));
    vertexArray_.setFloatAttribute(0, 0, 1, offsetof(NodeMorphValue, factor));
    vertexArray_.setUintAttribute(1, 0, 1, offsetof(NodeMorphValue, unlikeNeighbours));
  }
  if (!commands.empty()) {
    commands_.upload(0, commands.size() * sizeof(DrawCommand), commands.data());
    nodeMorph_.upload(0, nodeMorph.size() * sizeof(nodeMorph[0]), nodeMorph.data());
  }
  const bool morphTargets = morphPool_.id() != 0;

  applyShadingMode(programs_.fill, view, settings);
  if (settings.imagery) {
    if (skyStale_) sky_.update(pyramid_.front());
    skyStale_ = false;
    sky_.apply(programs_.fill);
  }
  const float finestCellM = float(std::max(levels_.spacingM(), levels_.cellM()));
  for (const gl::Program* program : {&programs_.fill, &programs_.wire}) {
    program->set("uViewProjection", glm::mat4(view.relativeViewProjection()));
    program->set("uCameraPosition", glm::vec3(view.camera.position));
    program->set("uExaggeration", settings.verticalExaggeration);
    program->set("uFinestCellM", finestCellM);
    program->set("uMorph", morphTargets ? 1 : 0);
  }
  programs_.wire.set("uSpacing", glm::vec2(float(levels_.spacingM())));
  const auto drawMeshes = [&] {
    if (commands.empty()) return;
    vertexArray_.bind();
    vertexPool_.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    if (morphTargets) morphPool_.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    // Closed surfaces wound counter-clockwise seen from the air (see stacks-full).
    glEnable(GL_CULL_FACE);
    glCullFace(culledFaces_);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commands_.id());
    if (staticCount > 0) {
      glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, GLsizei(staticCount), 0);
    }
    if (!morphing.empty()) {
      if (culledFaces_ == GL_BACK) glDisable(GL_CULL_FACE);
      glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                  reinterpret_cast<const void*>(staticCount * sizeof(DrawCommand)),
                                  GLsizei(morphing.size()), 0);
    }
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glDisable(GL_CULL_FACE);
  };
  drawWithWireframeOverlay(
      settings.wireframe, programs_.wire, view,
      [&] {
        programs_.fill.use();
        drawMeshes();
      },
      [&] {
        programs_.wire.use();
        drawMeshes();
      });
}

void StacksLodRenderer::relate(IndexedSelection& next, const Selection& drawn,
                               const SelectionIndex& drawnIndex, const std::vector<std::int64_t>& drawnGrowStart,
                               std::int64_t slidingSince, int topLevel, bool withMasks) {
  // Both are cuts of one octree: a node of one is in the other, or has an ancestor there, or
  // is an ancestor of nodes there (and a cut holds no node together with an ancestor).
  const std::vector<SelectedNode>& nodes = next.selection.nodes;
  next.relatedTo = drawn;
  // Masks worked out beside another drawn selection (a worker's, before a switch) describe
  // that one: never kept. Without masks here, they are worked out when needed.
  next.switchUnlike.clear();
  next.acceptUnlike.clear();
  next.drawnIndexOf.assign(nodes.size(), kNotDrawn);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const OctreeKey& key = nodes[i].key;
    if (const auto it = drawnIndex.find(key.packed()); it != drawnIndex.end()) {
      next.drawnIndexOf[i] = std::int64_t(it->second);
      continue;
    }
    for (OctreeKey a = key.parent(); a.level <= topLevel; a = a.parent()) {
      if (drawnIndex.contains(a.packed())) {
        next.drawnIndexOf[i] = kSplitIn;
        break;
      }
    }
  }
  next.mergesDrawn.assign(drawn->size(), 0);
  for (std::size_t j = 0; j < drawn->size(); ++j) {
    const OctreeKey& key = (*drawn)[j].key;
    if (next.index.contains(key.packed())) continue;  // kept
    for (OctreeKey a = key.parent(); a.level <= topLevel; a = a.parent()) {
      if (next.index.contains(a.packed())) {
        next.mergesDrawn[j] = 1;
        break;
      }
    }
  }
  if (!withMasks) return;
  // Geomorph masks (unlikeNeighbours() as they will be). At the switch, the nodes that split in
  // all start sliding in that frame: alike among themselves, unlike every other node.
  next.switchUnlike.assign(nodes.size(), kUnknownMask);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (next.drawnIndexOf[i] != kSplitIn) continue;
    next.switchUnlike[i] = unlikeMask(nodes[i].key, [&](std::uint64_t neighbour) {
      const auto it = next.index.find(neighbour);
      return it != next.index.end() && next.drawnIndexOf[it->second] == kSplitIn;
    });
  }
  // When it becomes pending, the drawn nodes it merges all start sliding out: alike when both
  // merge, or both do not, and they started sliding in together. Worked out for those that
  // merge and those that may still be sliding in (since `slidingSince`).
  next.acceptUnlike.assign(drawn->size(), kUnknownMask);
  if (drawnGrowStart.size() != drawn->size()) return;
  for (std::size_t j = 0; j < drawn->size(); ++j) {
    const std::uint8_t merges = next.mergesDrawn[j];
    const std::int64_t growStart = drawnGrowStart[j];
    if (!merges && (growStart < 0 || growStart < slidingSince)) continue;
    next.acceptUnlike[j] = unlikeMask((*drawn)[j].key, [&](std::uint64_t neighbour) {
      const auto it = drawnIndex.find(neighbour);
      return it != drawnIndex.end() && next.mergesDrawn[it->second] == merges &&
             drawnGrowStart[it->second] == growStart;
    });
  }
}

StacksLodRenderer::IndexedSelection StacksLodRenderer::indexedSelection(const StackOctree& octree,
                                                                       const SelectionView& view) {
  IndexedSelection out;
  out.selection = selectStackNodes(octree, view);
  out.boxes = BoxCullSet::of(out.selection.nodes, [](const SelectedNode& node) { return node.box; });
  out.index.reserve(out.selection.nodes.size());
  for (std::size_t i = 0; i < out.selection.nodes.size(); ++i) {
    out.index.emplace(out.selection.nodes[i].key.packed(), i);
  }
  return out;
}

std::optional<StacksLodRenderer::IndexedSelection> StacksLodRenderer::takeSelection(
    const SelectionView& view, bool wait, bool waitForWorker) {
  if (wait) {
    selection_.discard();
    return indexedSelection(*octree_, view);
  }
  if (waitForWorker && selection_.running()) {
    const Stopwatch waiting;
    selection_.wait();
    last_.selectionWaitMs = waiting.elapsedMs();
  }
  std::optional<IndexedSelection> ready;
  if (selection_.ready()) {
    auto [selection, workerMs] = selection_.take();
    ready = std::move(selection);
    unreportedWorkerCpuMs_ += workerMs;
  }
  if (!selection_.running()) {
    selectionJobFrame_ = frame_;
    // The worker only reads the octree and the levels; applyEdit() waits for it before it
    // changes them.
    // Related to the drawn selection for geomorphing (what slides in and out at the switch).
    selection_.start([this, view, relateTo = slides_, drawn = drawn_, drawnIndex = drawnIndex_,
                      growStart = drawnGrowStart_, slidingSince = slidingSince()] {
      IndexedSelection next = indexedSelection(*octree_, view);
      if (relateTo) relate(next, drawn, *drawnIndex, *growStart, slidingSince, octree_->topLevel(), true);
      return next;
    });
  }
  return ready;
}

StacksLodRenderer::~StacksLodRenderer() { selection_.wait(); }

void StacksLodRenderer::prepare(const ViewSetup& view, const RenderSettings& settings) {
  ++frame_;
  last_ = {};
  prepared_ = true;
  const Stopwatch selecting;
  const float exaggeration = std::max(settings.verticalExaggeration, 1e-3f);
  SelectionView selectionView;
  selectionView.camera = view.camera.position;
  selectionView.camera.z /= exaggeration;
  selectionView.fovYDeg = view.camera.fovYDeg;
  selectionView.viewportHeightPx = view.height;
  selectionView.tauPx = options_.tauPx;
  selectionView.errorTauPx = options_.errorTauPx;
  previous_ = drawn_;
  previousValues_ = std::move(drawnValues_);
  // Meshes are asked for over a wider frustum than the view's: nodes turning into view then
  // mostly have theirs already (they arrive a frame after they are asked for).
  constexpr double kAskMargin = 1.2;
  // The drawn selection's meshes near the view are this frame's: never evicted for the next
  // one. Those it lacks are looked for again after the arrivals.
  NodesInView drawnInView = nodesInView(*drawn_, drawnBoxes_, view, exaggeration, kAskMargin);
  std::vector<const SelectedNode*> drawnVisible = std::move(drawnInView.visible);
  std::vector<const SelectedNode*> drawnNear = std::move(drawnInView.near);
  std::vector<const SelectedNode*> drawnAbsent;
  for (const SelectedNode* node : drawnNear) {
    if (!useMesh(*node)) drawnAbsent.push_back(node);
  }

  // A bound on the lag: when a visible node of the drawn selection has a geometric error that
  // now spans more than kLagBound times the error threshold (the camera came close to a roof
  // its level lost: the sky would show through), the new selection is made whole this frame.
  constexpr double kLagBound = 4.0;
  bool tooCoarse = false;
  if (options_.errorTauPx > 0.0 && options_.updatesPerFrame > 0) {
    for (const SelectedNode* node : drawnVisible) {
      if (node->key.level == 0) continue;
      const double errorPx = selectionView.extentPx(node->errorM, node->box.distanceTo(selectionView.camera));
      if (errorPx > kLagBound * options_.errorTauPx) {
        tooCoarse = true;
        break;
      }
    }
  }
  last_.lagBound = tooCoarse;
  // Stills, the first frame and the frame after an edit wait for their selection and meshes;
  // otherwise the selection comes from a worker, for the camera of a frame or more before. The
  // lag is bounded: past the lag bound, or when the worker's selection is kMaxSelectionLag
  // frames old, the render thread waits for the worker (not for the GPU) instead of drawing an
  // ever staler selection.
  const bool waitNow = waitForMeshes_ || drawn_->empty() || edited_;
  constexpr std::uint64_t kMaxSelectionLag = 2;
  // A pending selection whose meshes are on their way (a lag bound's burst, made over a few
  // frames) is not replaced: waiting for a newer one would be for nothing.
  const auto pendingInFlight = [&] {  // a pass over the pending selection: only when it matters
    if (!hasPending_ || staging_->inFlightCount() == 0) return false;
    return std::any_of(pending_.begin(), pending_.end(),
                       [&](const SelectedNode& node) { return staging_->inFlight(meshKey(node)); });
  };
  const bool needSelection =
      (tooCoarse && !pendingInFlight()) ||
      (!hasPending_ && selection_.running() && frame_ - selectionJobFrame_ >= kMaxSelectionLag);
  std::optional<IndexedSelection> fresh = takeSelection(selectionView, waitNow, needSelection);
  // Geomorphing needs the new selection related to the drawn one. A worker's selection made
  // beside a drawn selection since replaced (a switch while it ran) is dropped: the worker is
  // making the next one beside this one already. Only when the frame cannot wait is it related
  // here (a pass over both selections; the masks are then worked out when needed).
  const bool morphing = slides_;
  if (fresh && morphing && fresh->relatedTo != drawn_ && !waitNow && !tooCoarse) fresh.reset();
  last_.selectMs = selecting.elapsedMs();
  if (fresh) {
    selectedCount_ = fresh->selection.nodes.size();
    selectedLevels_ = {fresh->selection.finestLevel, fresh->selection.coarsestLevel};
  }
  last_.selected = selectedCount_;
  last_.finestLevel = selectedLevels_[0];
  last_.coarsestLevel = selectedLevels_[1];
  // After an edit the old selection's bounds and meshes are stale: the whole new selection is
  // made in this frame. Such immediate switches do not morph.
  // The lag bound's switch comes a frame later (when the meshes are back).
  const bool immediate = waitNow || tooCoarse;
  const bool unlimited = immediate || options_.updatesPerFrame <= 0;
  const bool morph = slides_ && !immediate;
  // The lag bound's switch cannot wait for merges to slide, but its splits still slide in;
  // after an edit the old shapes are stale and nothing slides.
  const bool growIn = slides_ && !waitForMeshes_ && !drawn_->empty() && !edited_;
  edited_ = false;
  // A new selection replaces the pending one at once when the frame waits for its meshes, or
  // when the pending one is made whole anyway (lag bound, no K) and none of its meshes is on its
  // way: otherwise a camera that keeps moving would replace it every frame before its meshes
  // come back, and it would never be drawn.
  const bool replaceAtOnce =
      waitNow || (fresh && hasPending_ && (tooCoarse || (unlimited && !slides_)) &&
                  !pendingInFlight());
  if (fresh && (!hasPending_ || replaceAtOnce)) {
    // Made beside another drawn selection (a switch since the worker started), or here.
    if (morphing && fresh->relatedTo != drawn_) {
      relate(*fresh, drawn_, *drawnIndex_, *drawnGrowStart_, slidingSince(), octree_->topLevel(), false);
    }
    pending_ = std::move(fresh->selection.nodes);
    pendingBoxes_ = std::move(fresh->boxes);
    pendingHints_.assign(pending_.size(), {});
    if (fresh->drawnIndexOf.size() == pending_.size() && drawnHints_.size() == drawn_->size()) {
      for (std::size_t i = 0; i < pending_.size(); ++i) {
        const std::int64_t from = fresh->drawnIndexOf[i];
        if (from >= 0) pendingHints_[i] = drawnHints_[std::size_t(from)];  // a guess, checked at use
      }
    }
    pendingIndex_ = std::move(fresh->index);
    pendingDrawnIndexOf_ = std::move(fresh->drawnIndexOf);
    pendingSwitchUnlike_ = std::move(fresh->switchUnlike);
    hasPending_ = true;
    pendingChosenFrame_ = frame_;
    // Drawn nodes the new selection merges slide to their coarser targets first.
    pendingMerges_ = false;
    for (NodeMorph& m : drawnMorph_) m.outStart = -1;
    unlikeStale_ = true;
    if (morph) {
      const std::vector<std::uint8_t>& merges = fresh->mergesDrawn;
      for (std::size_t i = 0; i < drawn_->size() && i < drawnMorph_.size(); ++i) {
        if (merges[i]) drawnMorph_[i].outStart = std::int64_t(frame_);
      }
      // The switch waits for merges the camera sees.
      for (const SelectedNode* node : drawnVisible) {
        pendingMerges_ = pendingMerges_ || merges[std::size_t(node - drawn_->data())] != 0;
      }
      if (fresh->acceptUnlike.size() == drawn_->size()) {  // worked out beside
        drawnUnlike_ = std::move(fresh->acceptUnlike);
        unlikeStale_ = false;
      }
    }
  }
  const std::vector<const SelectedNode*> pendingNear =
      nodesInView(pending_, pendingBoxes_, view, exaggeration, kAskMargin, false).near;
  // Marks the pending selection's cached meshes used this frame (collecting evicts none of
  // them); of those it lacks, the arrivals are then struck off (afterArrivals).
  MissingMeshes beforeArrivals = missingMeshes(pendingNear);
  // Meshes asked for in earlier frames whose fences have passed: into the pool (evicting only
  // meshes this frame does not use).
  collectMeshes(false);
  MissingMeshes missing = afterArrivals(std::move(beforeArrivals));
  if (waitNow) {
    makeMeshesNow(missing.toAsk);
  } else {
    // The K most needed first: the largest screen-space extent of a cell (ties by key, so that
    // the choice does not depend on the order the nodes came in).
    // K a frame; past the lag bound, the burst a frame (it spreads a whole new selection's
    // meshes over a few frames, which bounds the frame's GPU work and the arrivals' bookkeeping).
    std::size_t budget = missing.toAsk.size();
    if (!unlimited) {
      budget = std::min(budget, std::size_t(options_.updatesPerFrame));
    } else if (tooCoarse && options_.burstPerFrame > 0) {
      budget = std::min(budget, std::size_t(options_.burstPerFrame));
    }
    const auto mostNeeded = [](const SelectedNode* a, const SelectedNode* b) {
      const double needA = a->needPx(), needB = b->needPx();
      return needA != needB ? needA > needB : a->key.packed() < b->key.packed();
    };
    const auto chosenEnd = missing.toAsk.begin() + std::ptrdiff_t(budget);
    std::partial_sort(missing.toAsk.begin(), chosenEnd, missing.toAsk.end(), mostNeeded);
    requestMeshes(std::vector<const SelectedNode*>(missing.toAsk.begin(), chosenEnd));
  }
  // Asking adds nothing to the cache; making them now does.
  std::size_t stillMissing = missing.missing;
  if (waitNow) {
    stillMissing = 0;
    for (const SelectedNode* node : pendingNear) stillMissing += cache_.contains(meshKey(*node)) ? 0 : 1;
  }
  last_.pendingMissing = stillMissing;
  // Merged nodes have slid to their targets once their last frame of sliding is drawn.
  const bool slidOut = !pendingMerges_ ||
                       frame_ - pendingChosenFrame_ >= std::uint64_t(std::max(options_.morphFrames, 0));
  if (hasPending_ && stillMissing == 0 && (immediate || slidOut)) {
    switchToPending(growIn);
    drawnInView = nodesInView(*drawn_, drawnBoxes_, view, exaggeration, kAskMargin);
    drawnVisible = std::move(drawnInView.visible);
    drawnNear = std::move(drawnInView.near);
    drawnAbsent = drawnNear;  // all looked for below
  }
  last_.framesBehind = std::size_t(frame_ - drawnChosenFrame_);

  // Drawn nodes near the view without a mesh (turned towards, or evicted): asked for now,
  // whatever K.
  const std::size_t before = last_.quadrangulations;
  const MissingMeshes forced = missingMeshes(drawnAbsent);
  if (waitNow) {
    makeMeshesNow(forced.toAsk);
  } else {
    requestMeshes(forced.toAsk);
  }
  last_.forced = last_.quadrangulations - before;
  staging_->submit();
  last_.inFlight = staging_->inFlightCount();

  drawnValues_ = morphValues(drawnNear);
  for (const NodeMorphValue& value : drawnValues_) last_.morphing += value.factor < 1.0f ? 1 : 0;
  drawnVisible_ = std::move(drawnVisible);
  last_.wanted = pendingNear.size();
}

FrameStats StacksLodRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!prepared_) prepare(view, settings);
  prepared_ = false;
  FrameStats stats;
  drawNodes(drawnVisible_, visibleValues(*drawn_, drawnVisible_, drawnValues_), view, settings, stats);
  last_.drawnNodes = std::size_t(stats.triangles > 0 ? drawnVisible_.size() : 0);
  stats.tilesLoaded = last_.quadrangulations;
  stats.tilesWanted = last_.wanted;
  stats.cacheMisses = last_.pendingMissing;
  stats.tilesResident = cache_.size();
  stats.stageMs["select"] = last_.selectMs;
  stats.stageMs["quad_dispatch_thread"] = last_.dispatchThreadMs;
  stats.stageMs["mesh_arrivals"] = last_.arrivalsMs;
  stats.stageMs["copy_dispatch_thread"] = last_.copyThreadMs;
  stats.stageMs["selection_wait"] = last_.selectionWaitMs;
  stats.backgroundCpuMs = unreportedWorkerCpuMs_;
  unreportedWorkerCpuMs_ = 0.0;
  return stats;
}

std::vector<std::string> StacksLodRenderer::frameReport() const {
  const StacksLodFrame& f = last_;
  return {fmt::format("{} nodes selected (levels {}..{}), {} drawn", f.selected, f.finestLevel,
                      f.coarsestLevel, f.drawnNodes),
          fmt::format("{} asked for this frame ({} forced), {} arrived, {} in flight, {:.1f} ms",
                      f.quadrangulations, f.forced, f.arrived, f.inFlight, f.quadMs),
          fmt::format("next selection: {} meshes missing, drawn one {} frames old",
                      f.pendingMissing, f.framesBehind),
          fmt::format("{} nodes sliding between levels (geomorph)", f.morphing)};
}

}  // namespace tellus
