#include "tellus/lod/stacks/node_mesh_cache.hpp"

#include <algorithm>

namespace tellus {

RangeAllocator::RangeAllocator(std::uint32_t capacity) : capacity_(capacity) {
  if (capacity > 0) free_[0] = capacity;
}

std::optional<std::uint32_t> RangeAllocator::allocate(std::uint32_t count) {
  if (count == 0) return std::nullopt;
  for (auto it = free_.begin(); it != free_.end(); ++it) {
    if (it->second < count) continue;
    const std::uint32_t first = it->first, left = it->second - count;
    free_.erase(it);
    if (left > 0) free_[first + count] = left;
    used_ += count;
    return first;
  }
  return std::nullopt;
}

void RangeAllocator::release(std::uint32_t first, std::uint32_t count) {
  if (count == 0) return;
  used_ -= count;
  auto [it, inserted] = free_.emplace(first, count);
  // Merge with the following range, then with the preceding one.
  const auto next = std::next(it);
  if (next != free_.end() && it->first + it->second == next->first) {
    it->second += next->second;
    free_.erase(next);
  }
  if (it != free_.begin()) {
    const auto previous = std::prev(it);
    if (previous->first + previous->second == it->first) {
      previous->second += it->second;
      free_.erase(it);
    }
  }
}

std::uint32_t RangeAllocator::largestFree() const {
  std::uint32_t largest = 0;
  for (const auto& [first, count] : free_) largest = std::max(largest, count);
  return largest;
}

NodeMeshCache::NodeMeshCache(std::uint32_t vertexCapacity, std::uint32_t indexCapacity)
    : vertices_(vertexCapacity), indices_(indexCapacity) {}

const CachedNodeMesh* NodeMeshCache::use(const NodeMeshKey& key, std::uint64_t frame) {
  const auto found = entries_.find(key);
  if (found == entries_.end()) return nullptr;
  found->second.mesh.lastUsedFrame = frame;
  order_.splice(order_.begin(), order_, found->second.order);
  return &found->second.mesh;
}

void NodeMeshCache::erase(const NodeMeshKey& key) {
  const auto found = entries_.find(key);
  const CachedNodeMesh& mesh = found->second.mesh;
  vertices_.release(mesh.firstVertex, mesh.vertexCount);
  indices_.release(mesh.firstIndex, mesh.indexCount);
  order_.erase(found->second.order);
  entries_.erase(found);
}

bool NodeMeshCache::evictOne(std::uint64_t frame) {
  // The least recently used mesh with room to give, unless the frame uses it.
  for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
    const Entry& entry = entries_.at(*it);
    if (entry.mesh.lastUsedFrame >= frame) return false;  // the rest are newer still
    if (entry.mesh.vertexCount == 0 && entry.mesh.indexCount == 0) continue;
    erase(*it);
    ++evictions_;
    return true;
  }
  return false;
}

std::size_t NodeMeshCache::eraseIf(const std::function<bool(std::uint64_t node)>& stale) {
  std::vector<NodeMeshKey> doomed;
  for (const auto& [key, entry] : entries_) {
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
  order_.push_front(key);
  entries_[key] = Entry{mesh, order_.begin()};
  return mesh;
}

}  // namespace tellus
