#include "tellus/render/stacks/stack_mesh_copy.hpp"

#include <algorithm>

namespace tellus {

Result<StackMeshCopy> StackMeshCopy::create() {
  StackMeshCopy c;
  if (Status built = gl::buildComputePrograms({{&c.program_, "stacks/copy_meshes.comp"}}); !built) {
    return built.error();
  }
  return c;
}

void StackMeshCopy::copy(std::span<const MeshCopy> copies, const MeshBuffers& from,
                         const MeshBuffers& to) {
  if (copies.empty()) return;
  if (copies.size() > tableCapacity_) {
    tableCapacity_ = std::max<std::size_t>(copies.size() * 2, 256);
    table_ = gl::Buffer(tableCapacity_ * sizeof(MeshCopy), nullptr, GL_DYNAMIC_STORAGE_BIT);
  }
  table_.upload(0, copies.size_bytes(), copies.data());
  const bool targets = from.morphTargets && to.morphTargets;
  program_.use();
  program_.set("uMorphTargets", targets ? 1 : 0);
  table_.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  from.vertices->bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  from.indices->bindBase(GL_SHADER_STORAGE_BUFFER, 2);
  to.vertices->bindBase(GL_SHADER_STORAGE_BUFFER, 4);
  to.indices->bindBase(GL_SHADER_STORAGE_BUFFER, 5);
  // Unused bindings still need a buffer: the vertex buffers stand in.
  (targets ? *from.morphTargets : *from.vertices).bindBase(GL_SHADER_STORAGE_BUFFER, 3);
  (targets ? *to.morphTargets : *to.vertices).bindBase(GL_SHADER_STORAGE_BUFFER, 6);
  // A work group per mesh, at most 65,535 a dispatch.
  constexpr std::size_t kMostGroups = 65535;
  for (std::size_t first = 0; first < copies.size(); first += kMostGroups) {
    program_.set("uFirstCopy", int(first));
    glDispatchCompute(GLuint(std::min(kMostGroups, copies.size() - first)), 1, 1);
  }
  // The pool is read by draws (vertices as storage, indices as elements) and written again by
  // later copies; the staging is written again by the quadrangulation.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT);
}

}  // namespace tellus
