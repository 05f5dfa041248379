#pragma once
// RINGO's block geometry on the GPU: a block's vertex buffer (RingoVertex, ringo_block_mesh.hpp)
// with a vertex array that reads it through the grid's shared index buffer, and a pool that
// reuses them.
//
// The buffers are persistently mapped (GL 4.4 buffer storage, coherent), so that a worker
// thread, not the render thread, copies a block's vertices in: the render thread only hands
// out a mapped pointer and, once the copy is done, draws. (Copying on the render thread cost it
// 1.1 to 1.5 ms of CPU per MiB on llvmpipe, most of it first touches of fresh pages.) A block
// of `cells` cells always has the same size, and blocks come and go as the matrix moves, so
// released buffers are reused; a fence keeps one from being rewritten while the GPU may still
// read it: one fence a frame for every buffer released since the last (fenceReleased()), as a
// depth change releases a whole matrix at once and a fence each cost the render thread a
// millisecond. acquire(), release() and the rest need a current GL 4.5 context (render thread).
#include <cstddef>
#include <map>
#include <memory>
#include <vector>

#include "tellus/gl/buffer.hpp"
#include "tellus/gl/fence.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/render/drawing/grid_index_buffers.hpp"

namespace tellus {

struct RingoBlockBuffers {
  int cells = 0;                        // (cells + 1)^2 vertices
  gl::Buffer vertices;                  // persistently mapped, coherent
  void* mapped = nullptr;               // its mapping: any thread may write it before drawing
  gl::VertexArray vertexArray;          // RingoVertex's attributes 0..6 and the index buffer
  const gl::Buffer* indices = nullptr;  // the grid's triangles (GridIndexBuffers)
};

class RingoBufferPool {
 public:
  // Keeps at most `maxFreeBytes` of released buffers for reuse; `indices` must outlive it.
  RingoBufferPool(GridIndexBuffers& indices, std::size_t maxFreeBytes);
  ~RingoBufferPool();
  RingoBufferPool(const RingoBufferPool&) = delete;
  RingoBufferPool& operator=(const RingoBufferPool&) = delete;

  // Buffers for a block of `cells` cells: a released one of that size the GPU is done with, or
  // new ones (contents undefined until written through `mapped`).
  RingoBlockBuffers acquire(int cells);
  // Returns buffers to the pool, reusable once fenced (fenceReleased()) and the GPU is past the
  // fence; when the pool holds enough, they wait to be freed by trim().
  void release(RingoBlockBuffers buffers);
  // Sets one fence after every command so far for the buffers released since the last call:
  // call once a frame, after its draws (every command that read them has been issued).
  void fenceReleased();
  // Frees waiting buffers, about `maxBytes` of them (at least one): freeing a mapped buffer
  // costs its unmapping, and a depth change releases a whole matrix at once, so the render
  // thread frees them a few a frame.
  void trim(std::size_t maxBytes);
  std::size_t freeBytes() const { return freeBytes_; }

 private:
  GridIndexBuffers& indices_;
  std::size_t maxFreeBytes_;
  std::size_t freeBytes_ = 0;
  // A fence shared by the buffers released in one frame; deleted with the last of them.
  struct Released {
    RingoBlockBuffers buffers;
    std::shared_ptr<gl::Fence> fence;
  };
  std::map<int, std::vector<Released>> free_;  // by cells, fenced
  std::vector<RingoBlockBuffers> unfenced_;    // released since the last fenceReleased()
  std::vector<RingoBlockBuffers> doomed_;      // to free (trim)
};

}  // namespace tellus
