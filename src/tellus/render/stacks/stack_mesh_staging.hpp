#pragma once
// How the octree renderer gets node meshes without waiting for the GPU: the quadrangulation
// writes each frame's new meshes into staging buffers, placed by the GPU itself
// (StackQuadPipelineGpu::makeBatch), and a fence follows them; a frame or more later, once the
// fence has passed, the placements are read back (no wait) and a staging's meshes are handed to
// the caller together, which copies them into its pool on the GPU (StackMeshCopy: one dispatch).
//
// A ring of kSlots stagings: the one open this frame takes every batch of the frame, the
// others are in flight. When none is free, add() takes nothing this frame (the nodes stay
// missing, asked for again). A staging too small for a frame's meshes places what fits and
// says what all wanted: it grows before its next use, and the nodes that did not fit stay
// missing. Needs a current GL 4.5 context.
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <absl/container/flat_hash_set.h>

#include "tellus/core/result.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/fence.hpp"
#include "tellus/lod/stacks/node_mesh_cache.hpp"
#include "tellus/render/stacks/stack_quad_pipeline.hpp"

namespace tellus {

class StackMeshStaging {
 public:
  static constexpr int kSlots = 3;
  using NodePlacement = StackQuadPipelineGpu::NodePlacement;
  using StagingBuffers = StackQuadPipelineGpu::StagingBuffers;
  // The meshes of one staging that came back: where each lies in `from`, parallel to `keys`
  // (placements[i].placed(): else it did not fit).
  using Arrival = std::function<void(std::span<const NodeMeshKey> keys,
                                     std::span<const NodePlacement> placements,
                                     const StagingBuffers& from)>;

  // morphTargets: write each vertex's geomorph target too. First capacities in vertices and
  // indices (each staging grows past them when a frame needs more).
  StackMeshStaging(bool morphTargets, std::uint32_t vertices, std::uint32_t indices);

  // Makes `jobs` (keys parallel to them, at most the pipeline's batch) into this frame's
  // staging. Returns false, doing nothing, when every staging is still in flight.
  Result<bool> add(StackQuadPipelineGpu& pipeline, std::span<const StackQuadPipelineGpu::NodeJob> jobs,
                   std::span<const NodeMeshKey> keys);
  // Ends this frame's additions: its staging gets its fence.
  void submit();
  // Hands over every mesh whose staging's fence has passed, oldest first, and frees those
  // stagings. wait: waits for every submitted staging first (a counted GPU wait: stills,
  // edits, the first frame). Call submit() before.
  void collect(bool wait, const Arrival& arrive);

  bool inFlight(const NodeMeshKey& key) const { return inFlight_.contains(key); }
  std::size_t inFlightCount() const { return inFlight_.size(); }
  // Bytes of GPU memory the stagings hold.
  std::size_t bytes() const;

 private:
  enum class State { Free, Open, Submitted };
  struct Slot {
    State state = State::Free;
    gl::Buffer vertices, indices, morphTargets, placements;
    std::uint32_t vertexCapacity = 0, indexCapacity = 0, placementCapacity = 0;  // elements
    std::vector<NodeMeshKey> keys;  // per placement
    gl::Fence fence;
    std::uint64_t submitted = 0;  // submit() count when submitted: the order of arrival
    StagingBuffers buffers() const;
  };
  // Opens a free slot (allocating or growing its buffers); null when none is free.
  Slot* open();
  void ensurePlacements(Slot& slot, std::size_t count);
  void hand(Slot& slot, const Arrival& arrive);

  bool morphTargets_ = false;
  // The capacities a staging has when it opens: the first ones, grown after a frame wanted more.
  std::uint32_t wantVertices_ = 0, wantIndices_ = 0;
  std::array<Slot, kSlots> slots_;
  std::uint64_t submits_ = 0;
  absl::flat_hash_set<NodeMeshKey> inFlight_;
};

}  // namespace tellus
