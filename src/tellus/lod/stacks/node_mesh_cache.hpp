#pragma once
// The bookkeeping of the octree renderer's mesh cache (seed 003, section 3.3: "the surface
// mesh is cached for subsequent frames"): every node mesh lives in one vertex pool and one
// index pool of fixed capacity, at ranges a best-fit allocator hands out; meshes are keyed
// by node and stitch mask (a node stitched differently is another mesh) and evicted least
// recently used when a new mesh does not fit. GL-free: the renderer owns the GPU buffers.
#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include <absl/container/btree_map.h>
#include <absl/container/btree_set.h>
#include <absl/container/flat_hash_map.h>

namespace tellus {

// Best-fit ranges of elements in [0, capacity); freed neighbours merge. allocate() and
// release() take O(log n) in the number of free ranges (a pool fragmented into thousands of
// ranges stays fast: the octree renderer places thousands of meshes in a frame; B-trees keep
// the ranges in few, dense nodes).
class RangeAllocator {
 public:
  explicit RangeAllocator(std::uint32_t capacity = 0);
  // The first element of `count` free elements (count > 0), or none: the smallest free range
  // that holds them (the lowest such first element among equals), its start.
  std::optional<std::uint32_t> allocate(std::uint32_t count);
  void release(std::uint32_t first, std::uint32_t count);
  std::uint32_t capacity() const { return capacity_; }
  std::uint32_t used() const { return used_; }
  std::uint32_t largestFree() const;

 private:
  void addFree(std::uint32_t first, std::uint32_t count);
  void removeFree(absl::btree_map<std::uint32_t, std::uint32_t>::iterator range);

  std::uint32_t capacity_ = 0, used_ = 0;
  absl::btree_map<std::uint32_t, std::uint32_t> free_;               // first -> count
  absl::btree_set<std::pair<std::uint32_t, std::uint32_t>> bySize_;  // (count, first) of free_
};

struct NodeMeshKey {
  std::uint64_t node = 0;  // OctreeKey::packed()
  std::uint32_t stitchMask = 0;
  bool operator==(const NodeMeshKey&) const = default;
  template <typename H>
  friend H AbslHashValue(H hash, const NodeMeshKey& key) {
    return H::combine(std::move(hash), key.node, key.stitchMask);
  }
};

struct CachedNodeMesh {
  std::uint32_t firstVertex = 0, vertexCount = 0;
  std::uint32_t firstIndex = 0, indexCount = 0;
  std::uint64_t lastUsedFrame = 0;
};

class NodeMeshCache {
 public:
  NodeMeshCache(std::uint32_t vertexCapacity, std::uint32_t indexCapacity);

  // Where a mesh was found last: use() with a hint skips the key's hash look-up while that mesh
  // is still in the slot (a caller keeps one per node it looks up every frame).
  struct SlotHint {
    std::uint32_t slot = 0xffffffffu;
  };

  // The mesh, marked used in `frame` (most recently used), or null; the pointer is good until
  // the next insert() (the entries are stored flat).
  const CachedNodeMesh* use(const NodeMeshKey& key, std::uint64_t frame);
  // The same, trying `hint` first and updating it.
  const CachedNodeMesh* use(const NodeMeshKey& key, std::uint64_t frame, SlotHint& hint);
  bool contains(const NodeMeshKey& key) const { return entries_.count(key) != 0; }
  // Places a mesh of these counts, evicting the least recently used meshes not used in
  // `frame` until it fits; none when it cannot fit (the pool is too small for what the frame
  // uses). An empty mesh takes no room.
  std::optional<CachedNodeMesh> insert(const NodeMeshKey& key, std::uint32_t vertices,
                                       std::uint32_t indices, std::uint64_t frame);

  // Drops every mesh whose node (OctreeKey::packed) `stale` says; returns how many.
  std::size_t eraseIf(const std::function<bool(std::uint64_t node)>& stale);

  std::size_t size() const { return entries_.size(); }
  std::uint64_t evictions() const { return evictions_; }
  const RangeAllocator& vertexPool() const { return vertices_; }
  const RangeAllocator& indexPool() const { return indices_; }

 private:
  // The meshes live in slots (reused once freed) chained from the most recently used to the
  // least: no allocation per mesh, O(1) to mark one used or to evict the oldest.
  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
  struct Slot {
    NodeMeshKey key;
    CachedNodeMesh mesh;
    std::uint32_t newer = kNoSlot, older = kNoSlot;  // neighbours in the order of use
    bool occupied = false;                           // false once freed (until reused)
  };
  bool evictOne(std::uint64_t frame);
  const CachedNodeMesh* useSlot(std::uint32_t slot, std::uint64_t frame);
  void erase(const NodeMeshKey& key);
  void unlink(std::uint32_t slot);
  void makeNewest(std::uint32_t slot);

  RangeAllocator vertices_, indices_;
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> freeSlots_;
  std::uint32_t newest_ = kNoSlot, oldest_ = kNoSlot;
  absl::flat_hash_map<NodeMeshKey, std::uint32_t> entries_;  // key -> slot
  std::uint64_t evictions_ = 0;
};

}  // namespace tellus
