#pragma once
// Clipmap updates uploaded by the GPU. A worker that built an update (clipmap_update.hpp) also
// writes its texels and rectangles into a staging slot, persistently mapped GL buffers, with no
// GL call; the render thread then only issues one compute pass (shaders/clipmaps/copy_texels.comp)
// that stores them into the height texture array, instead of copying them itself through
// glTextureSubImage3D (a memcpy of up to megabytes on the calling thread, on a real driver as on
// llvmpipe). ClipmapRenderer::upload, that direct path, stays the CPU reference and the fallback
// (first fill, jumps, a slot not free).
//
// Slots take turns: the render thread acquires a free one before starting a worker's update,
// hands it to the worker, and copies from it once the update is taken; the slot is free again
// when the GPU has passed the fence after that copy. acquire() never waits: with no free slot the
// update goes the direct way. Needs a current GL 4.5 context (except write()).
#include <array>
#include <cstddef>
#include <memory>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "tellus/core/result.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/fence.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/lod/clipmaps/clipmap_layout.hpp"
#include "tellus/lod/clipmaps/clipmap_update.hpp"

namespace tellus {

class ClipmapTexelStaging {
 public:
  static constexpr int kSlots = 3;

  // Slots that hold any update of `shape` (every level's whole window).
  static Result<std::unique_ptr<ClipmapTexelStaging>> create(const clipmaps::ClipmapShape& shape);

  // Render thread: a slot that no worker holds and no copy in flight reads (its last copy's
  // fence has passed), now held; -1 when there is none. Never waits.
  int acquire();
  // Render thread: gives a held slot back unused (its update was uploaded directly or dropped).
  void release(int slot);

  // Any thread, no GL call (the worker that built `update`): writes its rectangles into held
  // slot `slot` and frees their texel vectors. False, writing nothing, when they do not fit.
  bool write(int slot, clipmaps::ClipmapUpdate& update);

  // Render thread, after the writer finished: stores the slot's rectangles into `heights`'s
  // layers (RG32F), fences the slot and releases it (free once the GPU passed the fence).
  void copy(int slot, const gl::Texture& heights);

  // Render thread: runs the copy pass once over no texels, so that the driver compiles it before
  // the first frame that needs it (llvmpipe compiles a compute shader at its first dispatch).
  void prime(const gl::Texture& heights);

  // Bytes of one slot (texels and rectangles).
  std::size_t slotBytes() const;

 private:
  struct StagedRect {  // as copy_texels.comp reads it
    glm::ivec4 placement;  // first texel x, y, layer, width
    glm::uvec4 first;      // x: first texel in the slot's texels
  };
  struct Slot {
    gl::Buffer texels, rects;
    glm::vec2* mappedTexels = nullptr;
    StagedRect* mappedRects = nullptr;
    std::size_t texelCount = 0, rectCount = 0;  // written by the writer, read by copy()
    gl::Fence copied;                          // after the last copy from it
    bool held = false;
  };

  ClipmapTexelStaging() = default;
  void dispatch(const Slot& slot, const gl::Texture& heights, std::size_t texels);

  gl::Program program_;
  std::size_t texelCapacity_ = 0, rectCapacity_ = 0;
  std::array<Slot, kSlots> slots_;
};

}  // namespace tellus
