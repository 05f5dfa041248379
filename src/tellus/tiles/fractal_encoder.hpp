#pragma once
// The fractal (PIFS) encoder: finds, for every range block of a tile, the domain block,
// isometry and scale that approximate it best (seed 000, section 7).
//
// The seed scans the whole codebook for every range. This encoder uses Saupe's nearest-neighbour
// formulation instead: with the offset fitted by least squares, the fit error of range R from
// domain D is |R - mean(R)|^2 (1 - <r, d>^2), where r and d are the blocks with their mean
// removed, normalised to unit length. The best domain therefore maximises |<r, d>|, i.e. it is
// the nearest neighbour of r or of -r among the normalised domains. Every (domain, isometry)
// pair's normalised block, averaged down to at most 4 x 4, goes into a k-d tree (nanoflann);
// each range looks up its few nearest candidates for both signs and keeps the one whose
// quantised scale and mean fit best on the full block.
#include <cstdint>
#include <span>

#include "tellus/core/result.hpp"
#include "tellus/tiles/fractal_code.hpp"

namespace tellus::fractal {

// Checks the options (sizes, levels, step, thresholds); errors name the bad parameter.
Status checkOptions(const FractalOptions& options);

// Encodes one tile of samples (quantum steps). With options.residual the code carries the
// residual layer for |decoded - samples| <= maxErrorSteps. Fails when the tile's relief exceeds
// kMaxReliefSteps.
Result<FractalCode> encode(std::span<const std::int32_t> samples, TileShape shape,
                           const FractalOptions& options, std::uint32_t maxErrorSteps);

// Iterations a code needs: the first k at which no working value moved by more than
// kConvergedChange (1/8 step) from iteration k - 1, at most `cap`. (Integer rounding keeps a
// few values wobbling by a 16th of a step forever, so exact equality is not a criterion.)
inline constexpr std::uint32_t kConvergedChange = kOne / 8;
int iterationsUntilConverged(const FractalCode& code, int cap);

}  // namespace tellus::fractal
