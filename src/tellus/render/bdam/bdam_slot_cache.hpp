#pragma once
// BDAM's GPU patch cache: fixed-size slots of patch vertices (bdam::PackedVertex) and 16-bit
// indices, each with a record (origin x, origin y, level) the vertex shader finds by
// gl_VertexID / slot vertices. A patch is kept under a key of the caller's choosing; when the
// cache is full the least recently used slot is reused, never one drawn by the frame being made
// or the one before (the popping metric redraws the previous frame), and when every slot is
// that recent the cache doubles. Needs a current GL 4.5 context for its whole life.
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/vec4.hpp>

#include "tellus/formats/bdam/bdam_file.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/vertex_array.hpp"

namespace tellus {

class BdamSlotCache {
 public:
  BdamSlotCache() = default;
  // `slots` at first, each of `slotVertices` vertices and `slotIndices` indices; `what` names
  // the cache in log lines.
  BdamSlotCache(std::size_t slots, std::uint32_t slotVertices, std::uint32_t slotIndices, std::string what);

  bool created() const { return slotVertices_ > 0; }
  std::uint32_t slotVertices() const { return slotVertices_; }
  std::size_t slots() const { return keyOfSlot_.size(); }
  std::size_t resident() const { return resident_; }

  // Marks `key` used by frame `frame` and returns true when it is resident.
  bool touch(std::uint64_t key, std::uint64_t frame);
  // Uploads a patch under `key` (not resident), used by frame `frame`. Returns the bytes sent.
  std::uint64_t put(std::uint64_t key, std::span<const bdam::PackedVertex> vertices,
                    std::span<const std::uint16_t> indices, const glm::uvec4& record, std::uint64_t frame);

  // Draws the resident ones among `keys` with one glMultiDrawElementsBaseVertex, `program` in
  // use: binds the records to shader storage binding 0 and sets uSlotVertices.
  void draw(const gl::Program& program, const std::vector<std::uint64_t>& keys) const;
  // Triangles of the resident ones among `keys`.
  std::uint64_t triangles(const std::vector<std::uint64_t>& keys) const;

 private:
  int freeSlot(std::uint64_t frame);
  void grow();

  std::string what_;
  std::uint32_t slotVertices_ = 0, slotIndices_ = 0;
  std::unordered_map<std::uint64_t, int> slotOfKey_;
  std::vector<std::uint64_t> keyOfSlot_;
  std::vector<bool> slotUsed_;
  std::vector<std::uint64_t> slotLastUsed_;  // frame number
  std::vector<std::uint32_t> slotIndexCount_;
  std::size_t resident_ = 0;
  gl::Buffer vertices_, indices_, records_;
  gl::VertexArray array_;
};

}  // namespace tellus
