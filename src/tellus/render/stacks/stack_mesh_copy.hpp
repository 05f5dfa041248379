#pragma once
// Copies node meshes from a staging into the octree renderer's mesh pool on the GPU, all of a
// staging's meshes in one compute dispatch (shaders/stacks/copy_meshes.comp) instead of a copy
// command per buffer and mesh: on a GPU the driver's cost per call, on llvmpipe the copies
// themselves, stay off the render thread. The caller orders what reads the pool after it (copy()
// ends with the memory barrier the draws and later compute passes need). Needs a current GL 4.5
// context.
#include <cstdint>
#include <span>

#include "tellus/core/result.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"

namespace tellus {

class StackMeshCopy {
 public:
  // One mesh's element ranges: vertices (StackVertex, with their MorphTarget when copied) and
  // indices, from the staging's firsts to the pool's.
  struct MeshCopy {
    std::uint32_t sourceVertex = 0, targetVertex = 0, vertexCount = 0;
    std::uint32_t sourceIndex = 0, targetIndex = 0, indexCount = 0;
    std::uint32_t padding0 = 0, padding1 = 0;
  };
  static_assert(sizeof(MeshCopy) == 32);

  // The buffers of one side of a copy; morphTargets null: no geomorph targets copied.
  struct MeshBuffers {
    const gl::Buffer* vertices = nullptr;
    const gl::Buffer* indices = nullptr;
    const gl::Buffer* morphTargets = nullptr;
  };

  static Result<StackMeshCopy> create();

  // Copies every range of `copies` from `from` to `to` (targets copied when both sides have
  // them). Ranges must lie inside both sides' buffers and targets must not overlap.
  void copy(std::span<const MeshCopy> copies, const MeshBuffers& from, const MeshBuffers& to);

 private:
  StackMeshCopy() = default;
  gl::Program program_;
  gl::Buffer table_;  // the MeshCopy entries of the last copy()
  std::size_t tableCapacity_ = 0;
};

}  // namespace tellus
