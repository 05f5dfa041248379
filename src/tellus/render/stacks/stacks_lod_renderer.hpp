#pragma once
// `--algo stacks`: the octree LOD renderer of stack terrain (seed 003, sections 3.3 and 3.4).
// Every frame the octree over the stack MipMap is refined by the seed's screen-space extent
// and balanced (lod/stacks/stack_octree.hpp); the visible nodes are drawn from a mesh cache
// (one GPU vertex pool and one index pool, LRU under a byte budget) with one multi-draw
// indirect call; missing meshes are made by the GPU quadrangulation pipeline, stitched to their
// coarser neighbours (no crack), at most K a frame.
//
// The octree selection is made by a worker for the camera of a frame or more before (the render
// thread takes the newest one ready), with what it keeps, splits and merges of the drawn
// selection and the geomorph masks that follow (relate()). Never waiting for the GPU: a frame's new meshes are
// written into staging buffers where the GPU places them itself, and come back a frame or more
// later, behind a fence, to be copied into the pool on the GPU by one dispatch a staging
// (StackMeshStaging, StackMeshCopy). Meshes are asked for over a frustum a fifth
// wider than the view's, so that nodes turning into view mostly have theirs already. Only
// stills (waitForMeshes), the first frame and the frame after an edit wait, for the selection
// and all its meshes.
//
// Amortisation without holes: the renderer keeps drawing the last complete selection while the
// next one's meshes are made, K a frame, most needed (largest screen-space extent) first; when
// all of them are ready it switches at once. The price is delayed detail and a larger switch
// (the harness's popping and SSE measure it). Nodes of the drawn selection that turn visible
// (the camera turned) are asked for at once, whatever K, and so is the whole new selection when
// the drawn one has become far too coarse (a geometric error over 4 times its threshold on
// screen), up to StacksRenderOptions::burstPerFrame a frame; they arrive the next frame.
//
// Geomorphing (beyond the seed; StacksRenderOptions::morphFrames = F, 0: off): every mesh
// carries each vertex's target on the next coarser level's surface
// (stitched_quadrangulation.hpp). When a new selection is chosen, the drawn nodes it merges
// slide to their targets over F frames (the switch waits for that as well as for the meshes);
// after the switch, the nodes it split in slide from their targets to their own shape over F
// frames. A morphing node's border cells stay put where a neighbour does not morph with it
// (other level, other timing), so no crack opens. The lag bound's switch does not wait for
// merges (they pop) but its splits slide in; the first frame and the frame after an edit do
// not morph. Needs a current GL 4.5 context.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <optional>
#include <memory>
#include <vector>

#include <absl/container/flat_hash_map.h>
#include <absl/container/flat_hash_set.h>

#include "tellus/core/box_cull_set.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/stacks/node_mesh_cache.hpp"
#include "tellus/lod/stacks/stack_octree.hpp"
#include "tellus/render/stacks/stack_mesh_copy.hpp"
#include "tellus/render/stacks/stack_mesh_staging.hpp"
#include "tellus/render/stacks/stack_quad_pipeline.hpp"
#include "tellus/render/stacks/stack_sky_texture.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/render/drawing/background_job.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {

// What the octree renderer did in its last frame (FrameStats carries the same as tile
// counts: tilesLoaded = quadrangulations, tilesWanted = visible nodes of the selection being
// made, cacheMisses = those still missing, tilesResident = cached meshes).
struct StacksLodFrame {
  std::size_t selected = 0;        // leaves of the newest selection
  std::size_t drawnNodes = 0;      // visible nodes drawn (with a mesh)
  std::size_t quadrangulations = 0;  // node meshes asked for this frame (all reasons)
  std::size_t forced = 0;          // of which for drawn nodes that turned visible
  std::size_t arrived = 0;         // meshes asked for earlier that came into the pool
  std::size_t inFlight = 0;        // meshes asked for and not back yet
  std::size_t pendingMissing = 0;  // visible meshes the next selection still lacks
  std::size_t framesBehind = 0;    // frames since the drawn selection was chosen
  std::size_t morphing = 0;        // drawn nodes between their coarse targets and their shape
  int finestLevel = 0, coarsestLevel = 0;
  // The drawn selection had a visible node whose geometric error on screen was over 4 times the
  // error threshold: the whole new selection was made this frame, whatever K.
  bool lagBound = false;
  double quadMs = 0.0;  // wall time asking for meshes and copying arrivals into the pool
  // Parts of the frame's prepare(): the octree selection (wall ms); the render thread's CPU
  // inside the quadrangulation's dispatches (about 0 on a GPU; a software rasteriser runs the
  // compute shaders there); arrivals read and copied into the pool (wall ms).
  double selectMs = 0.0, dispatchThreadMs = 0.0, arrivalsMs = 0.0;  // select: taking it (a worker makes it)
  double copyThreadMs = 0.0;  // the render thread's CPU inside the arrivals' copy dispatch (as dispatchThreadMs)
  std::size_t wanted = 0;  // visible (and nearly visible) nodes of the selection being made
  double selectionWaitMs = 0.0;  // the render thread waited for the worker's selection (lag bound)
};

// What one edit did (StacksLodRenderer::applyEdit).
struct StacksEditReport {
  StackRegion region;             // finest-level columns changed (empty: nothing changed)
  std::size_t meshesDropped = 0;  // cached node meshes of every level the edit touched
  double editMs = 0.0;            // stacks and MipMap edited, levels quantised and uploaded
  // editMs in parts: the stacks of every level edited (finest, then the MipMap above), the
  // changed levels quantised again with their errors, the quantised levels uploaded.
  double stacksMs = 0.0, levelsMs = 0.0, uploadMs = 0.0;
};

class StacksLodRenderer final : public TerrainRenderer {
 public:
  // `pyramid`: every level of a .tstack (level 0 first). waitForMeshes: make every missing
  // mesh in the frame (stills, tests, K ignored).
  static Result<std::unique_ptr<StacksLodRenderer>> create(const std::vector<StackTerrain>& pyramid,
                                                           const StacksRenderOptions& options,
                                                           bool waitForMeshes);
  ~StacksLodRenderer() override;
  std::string_view name() const override { return "stacks"; }
  // The selection, the meshes asked for and those that came back (everything but drawing).
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  // Draws what prepare() chose (calls it first when it was not called for this frame).
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  // The popping metric: the selection drawn the frame before, from `view`.
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;
  // The crack metric's open-air test: the last frame's meshes, back faces only.
  bool drawLastFrameBackFaces(const ViewSetup& view, const RenderSettings& settings) override;

  // Live editing (beyond the seed): `edit` applied to the finest level, the MipMap above and
  // the GPU's copy of the stacks updated, and every cached mesh the edit can change dropped
  // (all levels, and the neighbours that read the edited stacks through smoothing and
  // stitching): the next draw() makes the visible ones again at once (not limited by K), so
  // the frame after a stroke shows it, crack-free. Errors: a bad sphere (nothing changed).
  Result<StacksEditReport> applyEdit(const SphereEdit& edit);
  // The stacks as edited so far (every level), e.g. to save them.
  const std::vector<StackTerrain>& pyramid() const { return pyramid_; }

  const StacksLodFrame& lastFrame() const { return last_; }
  // Tests: the geomorph masks kept for the drawn nodes sliding this frame (worked out beside, at
  // a switch or a new pending selection, or here when needed), checked against the masks worked
  // out from the drawn selection now.
  struct MorphMaskCheck {
    std::size_t checked = 0, wrong = 0;
  };
  MorphMaskCheck checkMorphMasks() const;
  const StackOctree& octree() const { return *octree_; }
  const NodeMeshCache& cache() const { return cache_; }
  // The selection drawn in the last frame (leaves with their stitch masks).
  const std::vector<SelectedNode>& drawnSelection() const { return *drawn_; }

 private:
  StacksLodRenderer(StackLevels levels, const StacksRenderOptions& options, bool waitForMeshes,
                    std::uint32_t vertexCapacity, std::uint32_t indexCapacity);
  // The newest selection a worker finished (none yet: nullopt), starting the next for `view`;
  // waitForWorker: waits for the worker's selection in progress; wait: made here for `view`
  // (stills, the first frame, after an edit).
  using Selection = std::shared_ptr<const std::vector<SelectedNode>>;
  using SelectionIndex = absl::flat_hash_map<std::uint64_t, std::size_t>;  // packed key -> index
  // drawnIndexOf's values for a node not in the drawn selection.
  static constexpr std::int64_t kSplitIn = -1;   // a drawn node's descendant (slides in)
  static constexpr std::int64_t kNotDrawn = -2;  // neither (a drawn node's ancestor)
  static constexpr std::uint32_t kUnknownMask = 0xffffffffu;  // a geomorph mask not worked out
  // A selection with each node's index by packed key, and how it relates to the drawn
  // selection it was made beside (`relatedTo`): per node, its index in that one or kSplitIn or
  // kNotDrawn; per node of that one, whether this selection merges it (holds an ancestor).
  // And the geomorph masks (unlikeNeighbours()) this brings: of its nodes that split in, at the
  // switch to it (switchUnlike, parallel to the selection), and of the drawn nodes that it
  // merges or that may still slide in, when it becomes pending (acceptUnlike, parallel to
  // relatedTo); kUnknownMask elsewhere. Made where the selection is made: the worker, mostly.
  struct IndexedSelection {
    StackSelection selection;
    SelectionIndex index;
    BoxCullSet boxes;  // the nodes' boxes, for culling them all at once
    Selection relatedTo;
    std::vector<std::int64_t> drawnIndexOf;
    std::vector<std::uint8_t> mergesDrawn;
    std::vector<std::uint32_t> switchUnlike, acceptUnlike;
  };
  static IndexedSelection indexedSelection(const StackOctree& octree, const SelectionView& view);
  // Works out `next`'s relation to `drawn` (whose index is `drawnIndex`, whose nodes started
  // sliding in at `drawnGrowStart`, -1: never) and its masks; a drawn node that started sliding
  // in before `slidingSince` has stopped by the time `next` can be taken. withMasks: the masks
  // too (else left empty).
  static void relate(IndexedSelection& next, const Selection& drawn, const SelectionIndex& drawnIndex,
                     const std::vector<std::int64_t>& drawnGrowStart, std::int64_t slidingSince,
                     int topLevel, bool withMasks);
  // relate()'s slidingSince for a selection started (or related) in this frame.
  std::int64_t slidingSince() const { return std::int64_t(frame_) + 1 - std::max(options_.morphFrames, 0); }
  std::optional<IndexedSelection> takeSelection(const SelectionView& view, bool wait, bool waitForWorker);
  // Asks for the meshes of `nodes` (none may be cached or in flight; batches through the
  // pipeline into the staging); returns how many were taken (none when every staging is in
  // flight).
  std::size_t requestMeshes(const std::vector<const SelectedNode*>& nodes);
  // Meshes that came back go into the pool; wait: every one asked for, waiting for the GPU.
  // Their keys land in arrivedKeys_, those a staging or the pool turned away in turnedAway_.
  void collectMeshes(bool wait);
  // Asks for `nodes` and waits for them (stills, the first frame, after an edit): those a
  // full staging turned away are asked for again, with the staging grown.
  void makeMeshesNow(const std::vector<const SelectedNode*>& nodes);
  // The nodes of `nodes` in the view's frustum widened by `margin` (near), and of those the
  // ones in the view's own frustum (visible; only when `visibleToo`); one pass.
  struct NodesInView {
    std::vector<const SelectedNode*> near, visible;
  };
  // `boxes`: the nodes' (BoxCullSet, vectorised); when it does not hold them (its size differs),
  // each node is tested on its own.
  NodesInView nodesInView(const std::vector<SelectedNode>& nodes, const BoxCullSet& boxes, const ViewSetup& view,
                          float exaggeration, double margin = 1.0, bool visibleToo = true) const;
  // The mesh of `node`, marked used this frame, or null (through its slot hint when it is a
  // node of pending_ or *drawn_).
  const CachedNodeMesh* useMesh(const SelectedNode& node);
  // Of `nodes`, those with no mesh in the cache (marking those that have one used this
  // frame), and of those the ones not in flight either.
  struct MissingMeshes {
    std::size_t missing = 0;
    std::vector<const SelectedNode*> absent;  // every node without a mesh (`missing` of them)
    std::vector<const SelectedNode*> toAsk;   // of those, the ones not in flight either
  };
  MissingMeshes missingMeshes(const std::vector<const SelectedNode*>& nodes);
  // `before` (missingMeshes() of some nodes before collectMeshes()) after the arrivals: those
  // whose mesh arrived are no longer missing, those turned away are to be asked for again.
  MissingMeshes afterArrivals(MissingMeshes before) const;
  // Draws the visible nodes of `nodes` that have a mesh (one multi-draw); adds to `stats`.
  // A drawn node's geomorph state in one frame, as the vertex shader reads it per instance.
  struct NodeMorphValue {
    float factor = 1.0f;                  // 0: at the coarser targets .. 1: its own shape
    std::uint32_t unlikeNeighbours = 0;   // neighbourBit()s of those not morphing as it does
  };
  // `morph`: per visible node, its morph state (empty: none morph).
  void drawNodes(const std::vector<const SelectedNode*>& visible,
                 const std::vector<NodeMorphValue>& morph, const ViewSetup& view,
                 const RenderSettings& settings, FrameStats& stats);

  // Geomorphing: when a drawn node's split-in slide started (growStart) and its slide to a
  // merge started (outStart), in frames (-1: none).
  struct NodeMorph {
    std::int64_t growStart = -1, outStart = -1;
    bool operator==(const NodeMorph&) const = default;
  };
  // 0: at the coarser targets .. 1: its own shape, in this frame.
  double morphFactor(const NodeMorph& morph) const;
  // Each drawn node's morph state in this frame (`near`: the drawn nodes near the view, whose
  // neighbour masks are worked out; the others pin every border).
  std::vector<NodeMorphValue> morphValues(const std::vector<const SelectedNode*>& near);
  // The neighbourBit()s of drawn node i's neighbours that do not morph as it does.
  std::uint32_t unlikeNeighbours(std::size_t i) const;
  // Per visible node of `selection`, its entry of `values` (parallel to `selection`).
  static std::vector<NodeMorphValue> visibleValues(
      const std::vector<SelectedNode>& selection, const std::vector<const SelectedNode*>& visible,
      const std::vector<NodeMorphValue>& values);
  // Switches the drawn selection to pending_ (morph: its split-in nodes slide in).
  void switchToPending(bool morph);
  // Draws the visible nodes of a kept selection (`values` parallel to it) without counting
  // them: the popping metric's previous selection, the crack metric's back faces.
  void drawSelection(const std::vector<SelectedNode>& selection,
                     const std::vector<NodeMorphValue>& values, const ViewSetup& view,
                     const RenderSettings& settings);

  std::vector<StackTerrain> pyramid_;  // the renderer's own copy: edits change it
  StackSkyTexture sky_;                // where imagery is draped: made when first drawn with it
  bool skyStale_ = true;               // an edit changed the tops since sky_ was made
  StackLevels levels_;
  std::unique_ptr<StackOctree> octree_;
  StacksRenderOptions options_;
  bool waitForMeshes_ = false;
  std::unique_ptr<StackQuadPipelineGpu> pipeline_;
  std::unique_ptr<StackMeshStaging> staging_;
  std::unique_ptr<StackMeshCopy> meshCopy_;  // staging to pool, one dispatch a staging
  NodeMeshCache cache_;
  gl::Buffer vertexPool_, indexPool_, commands_;
  // Geomorphing on (StacksRenderOptions::morphFrames > 0, not for stills): nodes slide.
  bool slides_ = false;
  // The seam blend's band in cells (StacksRenderOptions::seamBandCells, at most
  // seamBandLimit()); 0: off.
  int seamBand_ = 0;
  gl::Buffer morphPool_;      // a MorphTarget per vertex of vertexPool_ (geomorphing on)
  gl::Buffer nodeMorph_;      // per draw command: morph factor, pinned border bits
  std::size_t commandCapacity_ = 0;
  gl::VertexArray vertexArray_;
  FillAndWirePrograms programs_;
  Selection drawn_ = std::make_shared<const std::vector<SelectedNode>>();
  Selection previous_;  // drawn_ of the frame before the last draw()
  std::vector<NodeMorph> drawnMorph_;  // parallel to *drawn_
  // Per drawn node, unlikeNeighbours() once worked out (parallel to *drawn_; all ones: not
  // yet; stale after drawnMorph_ changed).
  std::vector<std::uint32_t> drawnUnlike_;
  bool unlikeStale_ = true;
  // Index of *drawn_ (shared with the worker, which relates its next selection to it).
  std::shared_ptr<const SelectionIndex> drawnIndex_ = std::make_shared<const SelectionIndex>();
  // Per drawn node, the frame it started sliding in (NodeMorph::growStart; shared likewise).
  std::shared_ptr<const std::vector<std::int64_t>> drawnGrowStart_ =
      std::make_shared<const std::vector<std::int64_t>>();
  // The morph values drawn the last frame (parallel to *drawn_) and the frame before.
  std::vector<NodeMorphValue> drawnValues_, previousValues_;
  bool pendingMerges_ = false;  // the pending selection merges drawn nodes (they slide first)
  std::vector<SelectedNode> pending_;
  BoxCullSet pendingBoxes_, drawnBoxes_;  // pending_'s and *drawn_'s boxes
  // Per node of pending_ and of *drawn_ (parallel to them), the cache slot its mesh was found in
  // last: the look-ups of every frame skip the hashing (a pending node starts with its drawn
  // node's).
  std::vector<NodeMeshCache::SlotHint> pendingHints_, drawnHints_;
  mutable std::vector<std::uint8_t> cullFlags_;  // nodesInView's scratch
  absl::flat_hash_set<NodeMeshKey> arrivedKeys_, turnedAway_;  // by the last collectMeshes()
  SelectionIndex pendingIndex_;  // packed key -> index in pending_
  std::vector<std::int64_t> pendingDrawnIndexOf_;  // IndexedSelection::drawnIndexOf of pending_
  std::vector<std::uint32_t> pendingSwitchUnlike_;  // IndexedSelection::switchUnlike of pending_
  bool hasPending_ = false;  // pending_ holds a selection to switch to (it may be empty)
  std::uint64_t frame_ = 0, drawnChosenFrame_ = 0, pendingChosenFrame_ = 0;
  bool poolWarned_ = false;
  bool edited_ = false;  // the next frame selects anew and makes every mesh it lacks
  bool prepared_ = false;  // prepare() ran for the next draw()
  BackgroundJob<IndexedSelection> selection_{"stacks"};  // the selection a worker is making
  std::uint64_t selectionJobFrame_ = 0;                 // the frame it was started in
  double unreportedWorkerCpuMs_ = 0.0;
  std::size_t selectedCount_ = 0;            // leaves of the newest selection
  std::array<int, 2> selectedLevels_{0, 0};  // its finest and coarsest levels
  std::vector<const SelectedNode*> drawnVisible_;  // prepare()'s visible nodes of *drawn_
  GLenum culledFaces_ = GL_BACK;  // drawNodes(): GL_FRONT for drawLastFrameBackFaces()
  StacksLodFrame last_;
};

}  // namespace tellus
