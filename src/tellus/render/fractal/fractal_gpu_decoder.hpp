#pragma once
// The fractal codec's decoder on the GPU (seed 000, section 7): each iteration is two compute
// passes over a tile's working image (the mean of every range's shrunk domain, then every
// value), ping-ponging between two image arrays, with the code's parameters in a texture.
// The arithmetic is the CPU reference's (tiles/fractal_code.hpp) in integers, so both produce
// identical working images after any number of iterations.
//
// The decoder holds `slots` tiles at once (one array layer each) so a renderer can keep every
// resident tile's decoding state and continue iterating a tile as the viewer approaches it
// (the seed's "Base incremental"). All tiles share one geometry: padded side, smallest range,
// tile shape. Needs a current GL 4.5 context.
#include <cstdint>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/tiles/fractal_code.hpp"

namespace tellus {

struct FractalGeometry {
  int paddedSide = 0;  // FractalCode::paddedSide
  int minLog2 = 2;     // smallest range block, log2
  TileShape shape;     // tile samples
  bool operator==(const FractalGeometry&) const = default;
};

// The geometry of a code (its smallest range size is read from its ranges).
FractalGeometry geometryOf(const fractal::FractalCode& code);
// The same with cells of the smallest range size any code can have, so every tile of the same
// shape fits (a decoder for a whole store).
FractalGeometry geometryForAnyRanges(const fractal::FractalCode& code);

class FractalGpuDecoder {
 public:
  static Result<FractalGpuDecoder> create(FractalGeometry geometry, int slots);

  // Uploads `code` (validated, of this decoder's geometry) into `slot` and starts it from a
  // flat image: iterations(slot) becomes 0. Fails when the geometry differs.
  Status load(int slot, const fractal::FractalCode& code);
  // Runs `count` more iterations on `slot`.
  void iterate(int slot, int count);
  // Runs request.count more iterations on each request.slot (each slot at most once). All the
  // slots' k-th iterations share one pair of dispatches (two where slots are at different
  // ping-pong phases), so a frame that brings many tiles costs a few dispatches per iteration,
  // not a few per tile and iteration.
  struct IterationRequest {
    int slot = 0;
    int count = 0;
  };
  void iterate(std::span<const IterationRequest> requests);
  static constexpr int kMaxBatch = 64;  // slots per dispatch (shaders/fractal/fractal_code.glsl)
  int iterations(int slot) const { return slots_[std::size_t(slot)].iterations; }
  // The iteration count the slot's code was made for (after which the residual applies).
  int fullIterations(int slot) const { return slots_[std::size_t(slot)].fullIterations; }

  // Writes the slot's heights, metres = sample * quantumM, into layer `layer` of `heights`
  // (an R32F 2D array of at least the tile's shape). The residual layer is added when
  // `withResidual`, the code has one and the slot has run its full iterations. Border samples
  // of a code with an exact border are written exactly after any number of iterations.
  void publish(int slot, const gl::Texture& heights, int layer, float quantumM,
               bool withResidual) const;

  // The slot's working image (paddedSide^2 values), for tests.
  std::vector<std::uint32_t> readWorking(int slot) const;

  const FractalGeometry& geometry() const { return geometry_; }
  int slotCount() const { return int(slots_.size()); }

 private:
  struct Slot {
    int iterations = 0;
    int fullIterations = 0;
    int current = 0;  // which working array holds the latest image
    std::int32_t base = 0;
    std::int32_t residualBin = 0;  // 0: no residual
    bool hasBorder = false;
  };
  // One iteration of `count` slots (layers) reading `in` and writing `out`.
  void dispatchIteration(const gl::Texture& in, const gl::Texture& out, const int* layers,
                         int count);

  FractalGeometry geometry_;
  int cells_ = 0;  // smallest-range cells per side
  gl::Program domainMeans_, iterate_, publish_;
  gl::Texture params_, working_[2], means_, residual_;
  gl::Texture border_;  // R32I, borderLength x 1 per slot: the exact border loop
  std::vector<Slot> slots_;
};

}  // namespace tellus
