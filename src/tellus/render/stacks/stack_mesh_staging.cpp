#include "tellus/render/stacks/stack_mesh_staging.hpp"

#include <algorithm>
#include <bit>

#include "tellus/gl/gpu_wait.hpp"
#include "tellus/lod/stacks/stitched_quadrangulation.hpp"

namespace tellus {
namespace {

// The most a staging grows to: 4 Mi vertices (320 MiB with their targets) and 24 Mi indices
// (96 MiB); a frame that asks for more gets the rest the next frame.
constexpr std::uint32_t kMaxVertices = 1u << 22, kMaxIndices = 24u << 20;

// Half again what was wanted, within the bounds.
std::uint32_t grown(std::uint32_t wanted, std::uint32_t most) {
  return std::uint32_t(std::min<std::uint64_t>(std::uint64_t(wanted) + wanted / 2, most));
}

}  // namespace

StackMeshStaging::StackMeshStaging(bool morphTargets, std::uint32_t vertices, std::uint32_t indices)
    : morphTargets_(morphTargets),
      wantVertices_(std::min(std::max(vertices, 1u), kMaxVertices)),
      wantIndices_(std::min(std::max(indices, 1u), kMaxIndices)) {}

StackMeshStaging::StagingBuffers StackMeshStaging::Slot::buffers() const {
  StagingBuffers b;
  b.vertices = &vertices;
  b.vertexCapacity = vertexCapacity;
  b.indices = &indices;
  b.indexCapacity = indexCapacity;
  b.morphTargets = morphTargets.id() != 0 ? &morphTargets : nullptr;
  b.placements = &placements;
  return b;
}

StackMeshStaging::Slot* StackMeshStaging::open() {
  for (Slot& slot : slots_) {
    if (slot.state == State::Open) return &slot;
  }
  for (Slot& slot : slots_) {
    if (slot.state != State::Free) continue;
    // Its last use (the copies out of it) comes before what is written now in the GL's
    // command order: the buffers are reused as they are.
    const std::uint32_t vertices = wantVertices_, indices = wantIndices_;
    if (slot.vertexCapacity < vertices) {
      slot.vertices = gl::Buffer(std::size_t(vertices) * sizeof(StackVertex), nullptr);
      if (morphTargets_) slot.morphTargets = gl::Buffer(std::size_t(vertices) * sizeof(MorphTarget), nullptr);
      slot.vertexCapacity = vertices;
    }
    if (slot.indexCapacity < indices) {
      slot.indices = gl::Buffer(std::size_t(indices) * sizeof(std::uint32_t), nullptr);
      slot.indexCapacity = indices;
    }
    ensurePlacements(slot, 256);
    const StackQuadPipelineGpu::StagingCursor empty;
    slot.placements.upload(0, sizeof empty, &empty);
    slot.keys.clear();
    slot.state = State::Open;
    return &slot;
  }
  return nullptr;
}

void StackMeshStaging::ensurePlacements(Slot& slot, std::size_t count) {
  if (count <= slot.placementCapacity) return;
  const auto capacity = std::uint32_t(std::max<std::size_t>(count, 2 * std::size_t(slot.placementCapacity)));
  gl::Buffer larger((1 + std::size_t(capacity)) * sizeof(NodePlacement), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (slot.state == State::Open) {  // keep the cursor and what this frame placed so far
    glCopyNamedBufferSubData(slot.placements.id(), larger.id(), 0, 0,
                             GLsizeiptr((1 + slot.keys.size()) * sizeof(NodePlacement)));
  }
  slot.placements = std::move(larger);
  slot.placementCapacity = capacity;
}

Result<bool> StackMeshStaging::add(StackQuadPipelineGpu& pipeline,
                                   std::span<const StackQuadPipelineGpu::NodeJob> jobs,
                                   std::span<const NodeMeshKey> keys) {
  if (jobs.size() != keys.size()) {
    return makeError("{} jobs for {} keys", jobs.size(), keys.size());
  }
  if (jobs.empty()) return true;
  Slot* slot = open();
  if (!slot) return false;
  ensurePlacements(*slot, slot->keys.size() + jobs.size());
  if (Status made = pipeline.makeBatch(jobs, slot->buffers(), std::uint32_t(slot->keys.size())); !made) {
    return made.error();
  }
  slot->keys.insert(slot->keys.end(), keys.begin(), keys.end());
  inFlight_.insert(keys.begin(), keys.end());
  return true;
}

void StackMeshStaging::submit() {
  for (Slot& slot : slots_) {
    if (slot.state != State::Open) continue;
    if (slot.keys.empty()) {
      slot.state = State::Free;
      continue;
    }
    slot.fence = gl::Fence::insert();
    slot.submitted = ++submits_;
    slot.state = State::Submitted;
  }
}

void StackMeshStaging::collect(bool wait, const Arrival& arrive) {
  std::vector<Slot*> submitted;
  for (Slot& slot : slots_) {
    if (slot.state == State::Submitted) submitted.push_back(&slot);
  }
  std::sort(submitted.begin(), submitted.end(),
            [](const Slot* a, const Slot* b) { return a->submitted < b->submitted; });
  for (Slot* slot : submitted) {
    if (wait) slot->fence.wait();
    if (!slot->fence.passed()) break;  // fences pass in order: the later ones have not either
    hand(*slot, arrive);
  }
}

void StackMeshStaging::hand(Slot& slot, const Arrival& arrive) {
  std::vector<NodePlacement> placements(1 + slot.keys.size());
  gl::readCompletedBuffer(slot.placements.id(), 0, placements.size() * sizeof(NodePlacement),
                          placements.data());
  const auto cursor = std::bit_cast<StackQuadPipelineGpu::StagingCursor>(placements[0]);
  // Every staging opened from now on is large enough for what this frame wanted.
  if (cursor.wantedVertices > slot.vertexCapacity) {
    wantVertices_ = std::max(wantVertices_, grown(cursor.wantedVertices, kMaxVertices));
  }
  if (cursor.wantedIndices > slot.indexCapacity) {
    wantIndices_ = std::max(wantIndices_, grown(cursor.wantedIndices, kMaxIndices));
  }
  for (const NodeMeshKey& key : slot.keys) inFlight_.erase(key);
  arrive(slot.keys, std::span<const NodePlacement>(placements).subspan(1), slot.buffers());
  slot.keys.clear();
  slot.fence = {};
  slot.state = State::Free;
}

std::size_t StackMeshStaging::bytes() const {
  std::size_t total = 0;
  for (const Slot& slot : slots_) {
    total += slot.vertices.size() + slot.indices.size() + slot.morphTargets.size() + slot.placements.size();
  }
  return total;
}

}  // namespace tellus
