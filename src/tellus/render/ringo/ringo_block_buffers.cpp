#include "tellus/render/ringo/ringo_block_buffers.hpp"

#include <cstddef>

#include "tellus/lod/ringo/ringo_block_mesh.hpp"

namespace tellus {
namespace {

std::size_t vertexBytes(int cells) {
  return std::size_t(cells + 1) * std::size_t(cells + 1) * sizeof(RingoVertex);
}

// The vertex array of ringo.vert's attributes over `vertices`.
gl::VertexArray ringoVertexArray(const gl::Buffer& vertices, const gl::Buffer& indices) {
  gl::VertexArray vertexArray = gl::VertexArray::create();
  const GLuint vao = vertexArray.id();
  glVertexArrayVertexBuffer(vao, 0, vertices.id(), 0, sizeof(RingoVertex));
  const auto attribute = [vao](GLuint location, GLint size, GLenum type, GLboolean normalised,
                               std::size_t offset) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribFormat(vao, location, size, type, normalised, GLuint(offset));
    glVertexArrayAttribBinding(vao, location, 0);
  };
  // Integer attributes: no conversion to float.
  const auto integers = [vao](GLuint location, GLint size, GLenum type, std::size_t offset) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribIFormat(vao, location, size, type, GLuint(offset));
    glVertexArrayAttribBinding(vao, location, 0);
  };
  integers(0, 3, GL_INT, offsetof(RingoVertex, whole));
  attribute(1, 3, GL_FLOAT, GL_FALSE, offsetof(RingoVertex, fraction));
  integers(2, 3, GL_INT, offsetof(RingoVertex, collapsedWhole));
  attribute(3, 3, GL_FLOAT, GL_FALSE, offsetof(RingoVertex, collapsedFraction));
  attribute(4, 4, GL_INT_2_10_10_10_REV, GL_TRUE, offsetof(RingoVertex, normal));
  attribute(5, 1, GL_FLOAT, GL_FALSE, offsetof(RingoVertex, heightM));
  integers(6, 1, GL_UNSIGNED_INT, offsetof(RingoVertex, edges));
  attribute(7, 1, GL_FLOAT, GL_FALSE, offsetof(RingoVertex, morphDeltaM));
  attribute(8, 1, GL_FLOAT, GL_FALSE, offsetof(RingoVertex, collapsedMorphDeltaM));
  glVertexArrayElementBuffer(vao, indices.id());
  return vertexArray;
}

}  // namespace

RingoBufferPool::RingoBufferPool(GridIndexBuffers& indices, std::size_t maxFreeBytes)
    : indices_(indices), maxFreeBytes_(maxFreeBytes) {}

RingoBufferPool::~RingoBufferPool() = default;

RingoBlockBuffers RingoBufferPool::acquire(int cells) {
  std::vector<Released>& list = free_[cells];
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (!it->fence->passed()) continue;
    RingoBlockBuffers reused = std::move(it->buffers);
    list.erase(it);
    freeBytes_ -= reused.vertices.size();
    return reused;
  }
  constexpr GLbitfield kMapping = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  RingoBlockBuffers made;
  made.cells = cells;
  made.vertices = gl::Buffer(vertexBytes(cells), nullptr, kMapping);
  made.mapped = glMapNamedBufferRange(made.vertices.id(), 0, GLsizeiptr(vertexBytes(cells)),
                                      kMapping);
  made.indices = &indices_.forGrid(cells + 1, cells + 1);
  made.vertexArray = ringoVertexArray(made.vertices, *made.indices);
  return made;
}

void RingoBufferPool::release(RingoBlockBuffers buffers) {
  if (!buffers.vertices.id()) return;
  const std::size_t bytes = buffers.vertices.size();
  if (freeBytes_ + bytes > maxFreeBytes_) {
    doomed_.push_back(std::move(buffers));  // freed by trim() (deleting unmaps it)
    return;
  }
  freeBytes_ += bytes;
  unfenced_.push_back(std::move(buffers));
}

void RingoBufferPool::fenceReleased() {
  if (unfenced_.empty()) return;
  const auto fence = std::make_shared<gl::Fence>(gl::Fence::insert());
  for (RingoBlockBuffers& buffers : unfenced_) {
    const int cells = buffers.cells;
    free_[cells].push_back({std::move(buffers), fence});
  }
  unfenced_.clear();
}

void RingoBufferPool::trim(std::size_t maxBytes) {
  std::size_t freed = 0;
  while (!doomed_.empty() && (freed == 0 || freed < maxBytes)) {
    freed += doomed_.back().vertices.size();
    doomed_.pop_back();
  }
}

}  // namespace tellus
