#include "tellus/lod/stacks/node_mesh_cache.hpp"

#include <algorithm>
#include <iterator>

namespace tellus {

RangeAllocator::RangeAllocator(std::uint32_t capacity) : capacity_(capacity) {
  if (capacity > 0) addFree(0, capacity);
}

void RangeAllocator::addFree(std::uint32_t first, std::uint32_t count) {
  free_.emplace(first, count);
  bySize_.emplace(count, first);
}

void RangeAllocator::removeFree(absl::btree_map<std::uint32_t, std::uint32_t>::iterator range) {
  bySize_.erase({range->second, range->first});
  free_.erase(range);
}

std::optional<std::uint32_t> RangeAllocator::allocate(std::uint32_t count) {
  if (count == 0) return std::nullopt;
  const auto best = bySize_.lower_bound({count, 0});
  if (best == bySize_.end()) return std::nullopt;
  const std::uint32_t first = best->second, left = best->first - count;
  removeFree(free_.find(first));
  if (left > 0) addFree(first + count, left);
  used_ += count;
  return first;
}

void RangeAllocator::release(std::uint32_t first, std::uint32_t count) {
  if (count == 0) return;
  used_ -= count;
  // Merge with the following range and the preceding one.
  const auto next = free_.lower_bound(first);
  if (next != free_.end() && first + count == next->first) {
    count += next->second;
    removeFree(next);
  }
  const auto after = free_.lower_bound(first);
  if (after != free_.begin()) {
    const auto previous = std::prev(after);
    if (previous->first + previous->second == first) {
      first = previous->first;
      count += previous->second;
      removeFree(previous);
    }
  }
  addFree(first, count);
}

std::uint32_t RangeAllocator::largestFree() const {
  return bySize_.empty() ? 0u : bySize_.rbegin()->first;
}

NodeMeshCache::NodeMeshCache(std::uint32_t vertexCapacity, std::uint32_t indexCapacity)
    : vertices_(vertexCapacity), indices_(indexCapacity) {}

const CachedNodeMesh* NodeMeshCache::use(const NodeMeshKey& key, std::uint64_t frame) {
  const auto found = entries_.find(key);
  if (found == entries_.end()) return nullptr;
  return useSlot(found->second, frame);
}

const CachedNodeMesh* NodeMeshCache::use(const NodeMeshKey& key, std::uint64_t frame, SlotHint& hint) {
  // A slot holds one mesh a key at a time: an occupied slot with this key holds this key's mesh.
  if (hint.slot < slots_.size() && slots_[hint.slot].occupied && slots_[hint.slot].key == key) {
    return useSlot(hint.slot, frame);
  }
  const auto found = entries_.find(key);
  if (found == entries_.end()) return nullptr;
  hint.slot = found->second;
  return useSlot(found->second, frame);
}

const CachedNodeMesh* NodeMeshCache::useSlot(std::uint32_t index, std::uint64_t frame) {
  Slot& slot = slots_[index];
  // Eviction passes over every mesh used in the frame it evicts for, so the order among one
  // frame's meshes does not matter: a mesh moves to the front once a frame, not at every use.
  if (slot.mesh.lastUsedFrame != frame) {
    slot.mesh.lastUsedFrame = frame;
    unlink(index);
    makeNewest(index);
  }
  return &slot.mesh;
}

void NodeMeshCache::unlink(std::uint32_t index) {
  Slot& slot = slots_[index];
  (slot.newer != kNoSlot ? slots_[slot.newer].older : newest_) = slot.older;
  (slot.older != kNoSlot ? slots_[slot.older].newer : oldest_) = slot.newer;
  slot.newer = slot.older = kNoSlot;
}

void NodeMeshCache::makeNewest(std::uint32_t index) {
  Slot& slot = slots_[index];
  slot.newer = kNoSlot;
  slot.older = newest_;
  (newest_ != kNoSlot ? slots_[newest_].newer : oldest_) = index;
  newest_ = index;
}

void NodeMeshCache::erase(const NodeMeshKey& key) {
  const auto found = entries_.find(key);
  const std::uint32_t index = found->second;
  const CachedNodeMesh& mesh = slots_[index].mesh;
  vertices_.release(mesh.firstVertex, mesh.vertexCount);
  indices_.release(mesh.firstIndex, mesh.indexCount);
  unlink(index);
  slots_[index].occupied = false;
  freeSlots_.push_back(index);
  entries_.erase(found);
}

bool NodeMeshCache::evictOne(std::uint64_t frame) {
  // The least recently used mesh with room to give, unless the frame uses it. Empty meshes
  // passed over on the way are least recently used too: they go as well (each is passed over
  // once, not at every eviction).
  while (oldest_ != kNoSlot) {
    const Slot& oldest = slots_[oldest_];
    if (oldest.mesh.lastUsedFrame >= frame) return false;  // the rest are newer still
    const bool empty = oldest.mesh.vertexCount == 0 && oldest.mesh.indexCount == 0;
    erase(NodeMeshKey(oldest.key));
    ++evictions_;
    if (!empty) return true;
  }
  return false;
}

std::size_t NodeMeshCache::eraseIf(const std::function<bool(std::uint64_t node)>& stale) {
  std::vector<NodeMeshKey> doomed;
  for (const auto& [key, slot] : entries_) {
    if (stale(key.node)) doomed.push_back(key);
  }
  for (const NodeMeshKey& key : doomed) erase(key);
  return doomed.size();
}

std::optional<CachedNodeMesh> NodeMeshCache::insert(const NodeMeshKey& key, std::uint32_t vertices,
                                                    std::uint32_t indices, std::uint64_t frame) {
  if (contains(key)) erase(key);
  CachedNodeMesh mesh;
  mesh.vertexCount = vertices;
  mesh.indexCount = indices;
  mesh.lastUsedFrame = frame;
  if (vertices > vertices_.capacity() || indices > indices_.capacity()) return std::nullopt;
  for (;;) {
    std::optional<std::uint32_t> v = vertices > 0 ? vertices_.allocate(vertices) : 0u;
    std::optional<std::uint32_t> i;
    if (v) {
      i = indices > 0 ? indices_.allocate(indices) : 0u;
      if (!i && vertices > 0) vertices_.release(*v, vertices);
    }
    if (v && i) {
      mesh.firstVertex = *v;
      mesh.firstIndex = *i;
      break;
    }
    if (!evictOne(frame)) return std::nullopt;
  }
  std::uint32_t index = 0;
  if (!freeSlots_.empty()) {
    index = freeSlots_.back();
    freeSlots_.pop_back();
  } else {
    index = std::uint32_t(slots_.size());
    slots_.emplace_back();
  }
  slots_[index].key = key;
  slots_[index].mesh = mesh;
  slots_[index].occupied = true;
  makeNewest(index);
  entries_.emplace(key, index);
  return mesh;
}

}  // namespace tellus
