#include "tellus/render/clipmaps/clipmap_texel_staging.hpp"

#include <algorithm>
#include <cstring>

namespace tellus {
namespace {

constexpr GLbitfield kMapping = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
constexpr GLuint kTexelsBinding = 0, kRectsBinding = 1, kHeightsImage = 0;
// Rectangles a level's update can be cut into: the L the window gains (two strips), each cut in
// up to four where the texture wraps; twice that for margin.
constexpr std::size_t kRectsPerLevel = 16;

template <class T>
T* mapWhole(const gl::Buffer& buffer) {
  return static_cast<T*>(glMapNamedBufferRange(buffer.id(), 0, GLsizeiptr(buffer.size()), kMapping));
}

}  // namespace

Result<std::unique_ptr<ClipmapTexelStaging>> ClipmapTexelStaging::create(const clipmaps::ClipmapShape& shape) {
  std::unique_ptr<ClipmapTexelStaging> s(new ClipmapTexelStaging());
  if (Status built = gl::buildComputePrograms({{&s->program_, "clipmaps/copy_texels.comp"}}); !built) {
    return built.error();
  }
  const std::size_t levels = std::size_t(shape.levels);
  s->texelCapacity_ = levels * std::size_t(shape.textureSize) * std::size_t(shape.textureSize);
  s->rectCapacity_ = levels * kRectsPerLevel;
  for (Slot& slot : s->slots_) {
    slot.texels = gl::Buffer(s->texelCapacity_ * sizeof(glm::vec2), nullptr, kMapping);
    slot.rects = gl::Buffer(s->rectCapacity_ * sizeof(StagedRect), nullptr, kMapping);
    slot.mappedTexels = mapWhole<glm::vec2>(slot.texels);
    slot.mappedRects = mapWhole<StagedRect>(slot.rects);
    if (!slot.mappedTexels || !slot.mappedRects) {
      return makeError("clipmaps: could not map a {:.1f} MiB texel staging buffer (GL error {:#x})",
                       double(s->slotBytes()) / double(1 << 20), glGetError());
    }
  }
  return s;
}

std::size_t ClipmapTexelStaging::slotBytes() const {
  return texelCapacity_ * sizeof(glm::vec2) + rectCapacity_ * sizeof(StagedRect);
}

int ClipmapTexelStaging::acquire() {
  for (int k = 0; k < kSlots; ++k) {
    Slot& slot = slots_[std::size_t(k)];
    if (slot.held || !slot.copied.passed()) continue;
    slot.held = true;
    return k;
  }
  return -1;
}

void ClipmapTexelStaging::release(int slot) { slots_[std::size_t(slot)].held = false; }

bool ClipmapTexelStaging::write(int slotIndex, clipmaps::ClipmapUpdate& update) {
  Slot& slot = slots_[std::size_t(slotIndex)];
  if (update.rects.size() > rectCapacity_ || update.samples > texelCapacity_) return false;
  std::size_t texels = 0, rects = 0;
  for (clipmaps::TexelRect& rect : update.rects) {
    if (rect.texels.empty()) continue;
    slot.mappedRects[rects++] = StagedRect{glm::ivec4(rect.texel, rect.level, rect.size.x),
                                           glm::uvec4(std::uint32_t(texels), 0u, 0u, 0u)};
    std::memcpy(slot.mappedTexels + texels, rect.texels.data(), rect.texels.size() * sizeof(glm::vec2));
    texels += rect.texels.size();
    rect.texels = {};  // they live in the slot now
  }
  slot.texelCount = texels;
  slot.rectCount = rects;
  return true;
}

void ClipmapTexelStaging::dispatch(const Slot& slot, const gl::Texture& heights, std::size_t texels) {
  slot.texels.bindBase(GL_SHADER_STORAGE_BUFFER, kTexelsBinding);
  slot.rects.bindBase(GL_SHADER_STORAGE_BUFFER, kRectsBinding);
  glBindImageTexture(kHeightsImage, heights.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
  program_.use();
  program_.set("uRectCount", int(slot.rectCount));
  program_.set("uTexelCount", int(texels));
  glDispatchCompute(std::max<GLuint>(gl::workGroups(texels, 64), 1), 1, 1);
  // The next draws sample the texture; a later direct upload into it must follow the stores.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void ClipmapTexelStaging::prime(const gl::Texture& heights) { dispatch(slots_[0], heights, 0); }

void ClipmapTexelStaging::copy(int slotIndex, const gl::Texture& heights) {
  Slot& slot = slots_[std::size_t(slotIndex)];
  if (slot.texelCount > 0) {
    dispatch(slot, heights, slot.texelCount);
    slot.copied = gl::Fence::insert();
  }
  slot.held = false;
}

}  // namespace tellus
