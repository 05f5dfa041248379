#include "tellus/render/bdam/bdam_slot_cache.hpp"

#include <limits>

#include <spdlog/spdlog.h>

namespace tellus {

BdamSlotCache::BdamSlotCache(std::size_t slots, std::uint32_t slotVertices, std::uint32_t slotIndices,
                             std::string what)
    : what_(std::move(what)), slotVertices_(slotVertices), slotIndices_(slotIndices) {
  vertices_ = gl::Buffer(slots * slotVertices_ * sizeof(bdam::PackedVertex), nullptr, GL_DYNAMIC_STORAGE_BIT);
  indices_ = gl::Buffer(slots * slotIndices_ * sizeof(std::uint16_t), nullptr, GL_DYNAMIC_STORAGE_BIT);
  records_ = gl::Buffer(slots * sizeof(glm::uvec4), nullptr, GL_DYNAMIC_STORAGE_BIT);
  keyOfSlot_.assign(slots, 0);
  slotUsed_.assign(slots, false);
  slotLastUsed_.assign(slots, 0);
  slotIndexCount_.assign(slots, 0);
  array_ = gl::VertexArray::create();
  const GLuint vao = array_.id();
  glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, GLsizei(sizeof(bdam::PackedVertex)));
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribIFormat(vao, 0, 2, GL_UNSIGNED_SHORT, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribFormat(vao, 1, 1, GL_FLOAT, GL_FALSE, 4);
  glVertexArrayAttribBinding(vao, 1, 0);
  array_.setIndexBuffer(indices_);
}

bool BdamSlotCache::touch(std::uint64_t key, std::uint64_t frame) {
  const auto it = slotOfKey_.find(key);
  if (it == slotOfKey_.end()) return false;
  slotLastUsed_[std::size_t(it->second)] = frame;
  return true;
}

int BdamSlotCache::freeSlot(std::uint64_t frame) {
  int best = -1;
  std::uint64_t oldest = std::numeric_limits<std::uint64_t>::max();
  for (std::size_t s = 0; s < keyOfSlot_.size(); ++s) {
    if (!slotUsed_[s]) return int(s);
    // Never a patch this frame or the previous one drew (popping redraws the previous frame).
    if (slotLastUsed_[s] + 1 < frame && slotLastUsed_[s] < oldest) {
      oldest = slotLastUsed_[s];
      best = int(s);
    }
  }
  if (best >= 0) {
    slotOfKey_.erase(keyOfSlot_[std::size_t(best)]);
    slotUsed_[std::size_t(best)] = false;
    --resident_;
  }
  return best;
}

void BdamSlotCache::grow() {
  const std::size_t old = keyOfSlot_.size(), slots = old * 2;
  const auto regrow = [&](gl::Buffer& buffer, std::size_t bytesPerSlot) {
    gl::Buffer bigger(slots * bytesPerSlot, nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCopyNamedBufferSubData(buffer.id(), bigger.id(), 0, 0, GLsizeiptr(old * bytesPerSlot));
    buffer = std::move(bigger);
  };
  regrow(vertices_, slotVertices_ * sizeof(bdam::PackedVertex));
  regrow(indices_, slotIndices_ * sizeof(std::uint16_t));
  regrow(records_, sizeof(glm::uvec4));
  glVertexArrayVertexBuffer(array_.id(), 0, vertices_.id(), 0, GLsizei(sizeof(bdam::PackedVertex)));
  array_.setIndexBuffer(indices_);
  keyOfSlot_.resize(slots, 0);
  slotUsed_.resize(slots, false);
  slotLastUsed_.resize(slots, 0);
  slotIndexCount_.resize(slots, 0);
  spdlog::info("BDAM: the {} grows to {} slots (a frame needs more than {})", what_, slots, old);
}

std::uint64_t BdamSlotCache::put(std::uint64_t key, std::span<const bdam::PackedVertex> vertices,
                                 std::span<const std::uint16_t> indices, const glm::uvec4& record,
                                 std::uint64_t frame) {
  int slot = freeSlot(frame);
  if (slot < 0) {
    grow();
    slot = freeSlot(frame);
  }
  const std::size_t s = std::size_t(slot);
  vertices_.upload(s * slotVertices_ * sizeof(bdam::PackedVertex), vertices.size_bytes(), vertices.data());
  indices_.upload(s * slotIndices_ * sizeof(std::uint16_t), indices.size_bytes(), indices.data());
  records_.upload(s * sizeof(glm::uvec4), sizeof(record), &record);
  slotOfKey_[key] = slot;
  keyOfSlot_[s] = key;
  slotUsed_[s] = true;
  slotLastUsed_[s] = frame;
  slotIndexCount_[s] = std::uint32_t(indices.size());
  ++resident_;
  return vertices.size_bytes() + indices.size_bytes() + sizeof(record);
}

void BdamSlotCache::draw(const gl::Program& program, const std::vector<std::uint64_t>& keys) const {
  std::vector<GLsizei> counts;
  std::vector<const void*> offsets;
  std::vector<GLint> baseVertices;
  for (const std::uint64_t key : keys) {
    const auto it = slotOfKey_.find(key);
    if (it == slotOfKey_.end()) continue;  // evicted since (cannot happen for the last two frames)
    const std::size_t slot = std::size_t(it->second);
    counts.push_back(GLsizei(slotIndexCount_[slot]));
    offsets.push_back(reinterpret_cast<const void*>(slot * slotIndices_ * sizeof(std::uint16_t)));
    baseVertices.push_back(GLint(slot * slotVertices_));
  }
  if (counts.empty()) return;
  records_.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  program.use();
  program.set("uSlotVertices", int(slotVertices_));
  array_.bind();
  glMultiDrawElementsBaseVertex(GL_TRIANGLES, counts.data(), GL_UNSIGNED_SHORT, offsets.data(),
                                GLsizei(counts.size()), baseVertices.data());
}

std::uint64_t BdamSlotCache::triangles(const std::vector<std::uint64_t>& keys) const {
  std::uint64_t sum = 0;
  for (const std::uint64_t key : keys) {
    const auto it = slotOfKey_.find(key);
    if (it != slotOfKey_.end()) sum += slotIndexCount_[std::size_t(it->second)] / 3;
  }
  return sum;
}

}  // namespace tellus
