#include "tellus/render/fractal/fractal_gpu_decoder.hpp"

#include <algorithm>

#include "tellus/gl/gpu_wait.hpp"

namespace tellus {
namespace {

constexpr int kGroup = 8;  // the shaders' local size

int groups(int n) {
  return (n + kGroup - 1) / kGroup;
}

void bindImage(GLuint unit, const gl::Texture& texture, GLenum access, GLenum format) {
  glBindImageTexture(unit, texture.id(), 0, GL_TRUE, 0, access, format);
}

}  // namespace

FractalGeometry geometryOf(const fractal::FractalCode& code) {
  int minLog2 = fractal::kMaxRangeLog2;
  for (const fractal::RangeBlock& range : code.ranges)
    minLog2 = std::min<int>(minLog2, range.sizeLog2);
  return {code.paddedSide, minLog2, code.shape};
}

FractalGeometry geometryForAnyRanges(const fractal::FractalCode& code) {
  FractalGeometry geometry = geometryOf(code);
  geometry.minLog2 = fractal::kMinRangeLog2;
  return geometry;
}

Result<FractalGpuDecoder> FractalGpuDecoder::create(FractalGeometry geometry, int slots) {
  if (slots < 1 || geometry.paddedSide < 2 || geometry.shape.width > geometry.paddedSide ||
      geometry.shape.height > geometry.paddedSide) {
    return makeError("invalid fractal decoder geometry ({} slots, padded side {})", slots,
                     geometry.paddedSide);
  }
  FractalGpuDecoder d;
  d.geometry_ = geometry;
  d.cells_ = geometry.paddedSide >> geometry.minLog2;
  auto program = [](const char* file) {
    return gl::Program::fromFiles({{GL_COMPUTE_SHADER, file}});
  };
  Result<gl::Program> means = program("fractal/domain_means.comp");
  if (!means) return means.error();
  Result<gl::Program> iterate = program("fractal/iterate.comp");
  if (!iterate) return iterate.error();
  Result<gl::Program> publish = program("fractal/publish.comp");
  if (!publish) return publish.error();
  d.domainMeans_ = std::move(means.value());
  d.iterate_ = std::move(iterate.value());
  d.publish_ = std::move(publish.value());
  const int side = geometry.paddedSide;
  d.params_ = gl::Texture::create2DArray(GL_RGBA32UI, d.cells_, d.cells_, slots);
  d.means_ = gl::Texture::create2DArray(GL_R32UI, d.cells_, d.cells_, slots);
  d.working_[0] = gl::Texture::create2DArray(GL_R32UI, side, side, slots);
  d.working_[1] = gl::Texture::create2DArray(GL_R32UI, side, side, slots);
  d.residual_ =
      gl::Texture::create2DArray(GL_R32I, geometry.shape.width, geometry.shape.height, slots);
  d.border_ = gl::Texture::create2DArray(
      GL_R32I, std::max(1, fractal::borderLength(geometry.shape)), 1, slots);
  d.slots_.resize(std::size_t(slots));
  return d;
}

Status FractalGpuDecoder::load(int slot, const fractal::FractalCode& code) {
  // Ranges no smaller than the decoder's cells fit; the rest of the geometry must match.
  const FractalGeometry g = geometryOf(code);
  if (g.paddedSide != geometry_.paddedSide || g.shape.width != geometry_.shape.width ||
      g.shape.height != geometry_.shape.height || g.minLog2 < geometry_.minLog2) {
    return makeError(
        "a fractal tile of {}x{} samples (padded {}, ranges from {}) does not fit "
        "the decoder's layout ({}x{}, padded {}, ranges from {})",
        g.shape.width, g.shape.height, g.paddedSide, 1 << g.minLog2, geometry_.shape.width,
        geometry_.shape.height, geometry_.paddedSide, 1 << geometry_.minLog2);
  }
  // One texel per smallest-range cell, holding its range's parameters.
  std::vector<std::uint32_t> texels(std::size_t(cells_) * std::size_t(cells_) * 4);
  for (const fractal::RangeBlock& range : code.ranges) {
    const int n = 1 << (range.sizeLog2 - geometry_.minLog2);
    const int cx = range.x >> geometry_.minLog2, cy = range.y >> geometry_.minLog2;
    const std::uint32_t packed[4] = {
        std::uint32_t(range.x) | std::uint32_t(range.y) << 16,
        std::uint32_t(range.domainX) | std::uint32_t(range.domainY) << 16,
        std::uint32_t(range.sizeLog2) | std::uint32_t(range.isometry) << 4 |
            std::uint32_t(range.scaleIndex + fractal::kMaxScaleIndex) << 8,
        range.mean};
    for (int j = cy; j < cy + n; ++j) {
      for (int i = cx; i < cx + n; ++i) {
        std::copy_n(packed, 4, texels.begin() + (std::ptrdiff_t(j) * cells_ + i) * 4);
      }
    }
  }
  params_.uploadLayer(0, slot, cells_, cells_, GL_RGBA_INTEGER, GL_UNSIGNED_INT, texels.data());
  // Start from a flat image (fractal::flatImage: every value 0), cleared on the GPU.
  Slot& s = slots_[std::size_t(slot)];
  s = {};
  const std::uint32_t zero = 0;
  glClearTexSubImage(working_[0].id(), 0, 0, 0, slot, geometry_.paddedSide, geometry_.paddedSide, 1,
                     GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  s.fullIterations = code.iterations;
  s.base = code.base;
  if (code.hasResidual) {
    s.residualBin = std::int32_t(2 * code.residualError + 1);
    residual_.uploadLayer(0, slot, code.shape.width, code.shape.height, GL_RED_INTEGER, GL_INT,
                          code.residual.data());
  }
  s.hasBorder = !code.border.empty();
  if (s.hasBorder) {
    border_.uploadLayer(0, slot, int(code.border.size()), 1, GL_RED_INTEGER, GL_INT,
                        code.border.data());
  }
  return {};
}

void FractalGpuDecoder::iterate(int slot, int count) {
  const IterationRequest request{slot, count};
  iterate(std::span(&request, 1));
}

void FractalGpuDecoder::iterate(std::span<const IterationRequest> requests) {
  int rounds = 0;
  for (const IterationRequest& r : requests) rounds = std::max(rounds, r.count);
  std::vector<int> byPhase[2];  // this round's slots by the working array they read
  for (int round = 0; round < rounds; ++round) {
    byPhase[0].clear();
    byPhase[1].clear();
    for (const IterationRequest& r : requests) {
      if (r.count > round) byPhase[slots_[std::size_t(r.slot)].current].push_back(r.slot);
    }
    for (int phase = 0; phase < 2; ++phase) {
      const std::vector<int>& layers = byPhase[phase];
      for (std::size_t first = 0; first < layers.size(); first += kMaxBatch) {
        const int count = int(std::min<std::size_t>(kMaxBatch, layers.size() - first));
        dispatchIteration(working_[phase], working_[1 - phase], layers.data() + first, count);
      }
      for (const int slot : layers) {
        Slot& s = slots_[std::size_t(slot)];
        s.current = 1 - s.current;
        ++s.iterations;
      }
    }
  }
}

void FractalGpuDecoder::dispatchIteration(const gl::Texture& in, const gl::Texture& out,
                                          const int* layers, int count) {
  bindImage(0, params_, GL_READ_ONLY, GL_RGBA32UI);
  bindImage(1, in, GL_READ_ONLY, GL_R32UI);
  bindImage(2, means_, GL_READ_WRITE, GL_R32UI);
  domainMeans_.setArray("uLayers", layers, count);
  domainMeans_.set("uCells", cells_);
  domainMeans_.use();
  glDispatchCompute(GLuint(groups(cells_)), GLuint(groups(cells_)), GLuint(count));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  bindImage(3, out, GL_WRITE_ONLY, GL_R32UI);
  iterate_.setArray("uLayers", layers, count);
  iterate_.set("uSide", geometry_.paddedSide);
  iterate_.set("uMinLog2", geometry_.minLog2);
  iterate_.use();
  glDispatchCompute(GLuint(groups(geometry_.paddedSide)), GLuint(groups(geometry_.paddedSide)),
                    GLuint(count));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void FractalGpuDecoder::publish(int slot, const gl::Texture& heights, int layer, float quantumM,
                                bool withResidual) const {
  const Slot& s = slots_[std::size_t(slot)];
  bindImage(1, working_[s.current], GL_READ_ONLY, GL_R32UI);
  bindImage(4, residual_, GL_READ_ONLY, GL_R32I);
  bindImage(5, heights, GL_WRITE_ONLY, GL_R32F);
  bindImage(6, border_, GL_READ_ONLY, GL_R32I);
  const bool residual = withResidual && s.residualBin > 0 && s.iterations >= s.fullIterations;
  publish_.set("uLayer", slot);
  publish_.set("uTargetLayer", layer);
  publish_.set("uShape", glm::ivec2(geometry_.shape.width, geometry_.shape.height));
  publish_.set("uBase", s.base);
  publish_.set("uResidualBin", residual ? s.residualBin : 0);
  publish_.set("uQuantum", quantumM);
  publish_.set("uHasBorder", int(s.hasBorder));
  publish_.use();
  glDispatchCompute(GLuint(groups(geometry_.shape.width)), GLuint(groups(geometry_.shape.height)),
                    1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
}

std::vector<std::uint32_t> FractalGpuDecoder::readWorking(int slot) const {
  const int side = geometry_.paddedSide;
  std::vector<std::uint32_t> values(std::size_t(side) * std::size_t(side));
  gl::readTextureSubImage(working_[slots_[std::size_t(slot)].current].id(), 0, 0, 0, slot, side,
                          side, 1, GL_RED_INTEGER, GL_UNSIGNED_INT,
                          values.size() * sizeof(std::uint32_t), values.data());
  return values;
}

}  // namespace tellus
