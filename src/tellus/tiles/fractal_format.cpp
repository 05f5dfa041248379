#include "tellus/tiles/fractal_format.hpp"

#include <algorithm>
#include <cstring>

#include "tellus/tiles/sample_coding.hpp"

namespace tellus::fractal {
namespace {

constexpr std::uint8_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 20;
constexpr int kStreams = 5;
enum Stream { kSplits = 0, kScales = 1, kMeans = 2, kDomains = 3, kIsometries = 4 };
constexpr int kResidualFlag = 1, kBorderFlag = 2;

template <typename T>
void put(std::vector<std::byte>& out, T value) {
  std::byte bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

template <typename T>
T get(const std::byte* at) {
  T value;
  std::memcpy(&value, at, sizeof(T));
  return value;
}

// Range means (steps) on a grid of smallest-range cells, for predicting each range's mean from
// its left, upper and upper-left neighbours (MED). In quadtree order those are always known.
class MeanGrid {
 public:
  MeanGrid(int paddedSide, int minLog2)
      : minLog2_(minLog2), side_(paddedSide >> minLog2), cells_(std::size_t(side_) * side_, 0) {}
  std::int32_t predict(int x, int y) const {
    return coding::predictAt(cells_.data(), side_, x >> minLog2_, y >> minLog2_);
  }
  void fill(int x, int y, int log2, std::int32_t mean) {
    const int cx = x >> minLog2_, cy = y >> minLog2_, n = 1 << (log2 - minLog2_);
    for (int j = cy; j < cy + n; ++j)
      std::fill_n(cells_.begin() + std::ptrdiff_t(j) * side_ + cx, n, mean);
  }

 private:
  int minLog2_, side_;
  std::vector<std::int32_t> cells_;
};

// Walks the quadtree of one top block in the stream order, calling leaf(x, y, log2) for each
// leaf and split(isSplit) for each node above the smallest size (the writer answers from the
// ranges, the reader from the split stream). Returns false when `split` fails.
template <typename SplitFn, typename LeafFn>
bool walk(int x, int y, int log2, int minLog2, SplitFn& split, LeafFn& leaf) {
  if (log2 > minLog2) {
    bool isSplit = false;
    if (!split(x, y, log2, isSplit)) return false;
    if (isSplit) {
      const int h = 1 << (log2 - 1);
      return walk(x, y, log2 - 1, minLog2, split, leaf) &&
             walk(x + h, y, log2 - 1, minLog2, split, leaf) &&
             walk(x, y + h, log2 - 1, minLog2, split, leaf) &&
             walk(x + h, y + h, log2 - 1, minLog2, split, leaf);
    }
  }
  return leaf(x, y, log2);
}

Status appendStream(std::span<const std::byte> raw, int level, std::vector<std::byte>& out) {
  put(out, std::uint32_t(raw.size()));
  const std::size_t sizeAt = out.size();
  put(out, std::uint32_t(0));
  const std::size_t start = out.size();
  if (Status s = coding::zstdCompressAppend(raw, level, out); !s) return s;
  const std::uint32_t frame = std::uint32_t(out.size() - start);
  std::memcpy(out.data() + sizeAt, &frame, 4);
  return {};
}

}  // namespace

Status write(const FractalCode& code, int minLog2, int maxLog2, int domainStep, int zstdLevel,
             std::vector<std::byte>& out) {
  std::vector<std::byte> streams[kStreams];
  std::size_t next = 0;  // the next range in code.ranges
  std::vector<std::uint32_t> meanDeltas;
  MeanGrid means(code.paddedSide, minLog2);
  auto split = [&](int x, int y, int log2, bool& isSplit) {
    if (next >= code.ranges.size()) return false;
    const RangeBlock& range = code.ranges[next];
    isSplit = !(range.x == x && range.y == y && range.sizeLog2 == log2);
    streams[kSplits].push_back(std::byte(isSplit));
    return true;
  };
  auto leaf = [&](int x, int y, int log2) {
    if (next >= code.ranges.size()) return false;
    const RangeBlock& range = code.ranges[next++];
    if (range.x != x || range.y != y || range.sizeLog2 != log2) return false;
    streams[kScales].push_back(std::byte(range.scaleIndex + kMaxScaleIndex));
    const std::int32_t mean = std::int32_t(range.mean >> kFractionBits);
    meanDeltas.push_back(coding::zigzag(std::int32_t(mean - means.predict(x, y))));
    means.fill(x, y, log2, mean);
    if (range.scaleIndex != 0) {
      const int r = 1 << log2, step = domainStepFor(r, domainStep);
      const int index = (range.domainY / step) * domainsPerSide(code.paddedSide, r, domainStep) +
                        range.domainX / step;
      streams[kDomains].push_back(std::byte(index & 0xff));
      streams[kDomains].push_back(std::byte(index >> 8));
      streams[kIsometries].push_back(std::byte(range.isometry));
    }
    return true;
  };
  const int top = 1 << maxLog2;
  for (int y = 0; y < code.paddedSide; y += top) {
    for (int x = 0; x < code.paddedSide; x += top) {
      if (!walk(x, y, maxLog2, minLog2, split, leaf)) {
        return makeError("internal error: fractal ranges are not in quadtree order");
      }
    }
  }
  // Domain indices as two byte planes.
  std::vector<std::byte>& domains = streams[kDomains];
  std::vector<std::byte> planar(domains.size());
  const std::size_t pairs = domains.size() / 2;
  for (std::size_t i = 0; i < pairs; ++i) {
    planar[i] = domains[2 * i];
    planar[pairs + i] = domains[2 * i + 1];
  }
  domains.swap(planar);
  const int planes = coding::bytesNeeded(meanDeltas);
  streams[kMeans].push_back(std::byte(planes));
  coding::appendBytePlanes(meanDeltas, planes, streams[kMeans]);

  std::vector<std::byte> borderStream;
  if (!code.border.empty()) {
    // Differences along the loop: neighbouring samples, small and zstd-friendly.
    std::vector<std::uint32_t> deltas(code.border.size());
    std::int32_t previous = 0;
    for (std::size_t k = 0; k < deltas.size(); ++k) {
      deltas[k] = coding::zigzag(code.border[k] - previous);
      previous = code.border[k];
    }
    const int borderPlanes = coding::bytesNeeded(deltas);
    borderStream.push_back(std::byte(borderPlanes));
    coding::appendBytePlanes(deltas, borderPlanes, borderStream);
  }

  out.push_back(std::byte(kVersion));
  out.push_back(
      std::byte((code.hasResidual ? kResidualFlag : 0) | (code.border.empty() ? 0 : kBorderFlag)));
  out.push_back(std::byte(minLog2));
  out.push_back(std::byte(maxLog2));
  out.push_back(std::byte(domainStep));
  out.push_back(std::byte(code.iterations));
  put(out, std::uint16_t(code.paddedSide));
  put(out, code.base);
  put(out, code.residualError);
  put(out, std::uint16_t(code.shape.width));
  put(out, std::uint16_t(code.shape.height));
  for (const std::vector<std::byte>& stream : streams) {
    if (Status s = appendStream(stream, zstdLevel, out); !s) return s;
  }
  if (!borderStream.empty()) {
    if (Status s = appendStream(borderStream, zstdLevel, out); !s) return s;
  }
  if (code.hasResidual) {
    std::vector<std::uint32_t> bins(code.residual.size());
    for (std::size_t i = 0; i < bins.size(); ++i) bins[i] = coding::zigzag(code.residual[i]);
    return coding::appendPlanedResiduals(bins, zstdLevel, out);
  }
  return {};
}

Result<FractalCode> read(std::span<const std::byte> bytes, TileShape shape) {
  if (Status s = coding::checkShape(shape, shape.sampleCount()); !s) return s.error();
  if (bytes.size() < kHeaderBytes) return makeError("fractal tile is too short");
  const std::byte* header = bytes.data();
  if (std::uint8_t(header[0]) != kVersion) {
    return makeError("fractal tile has unknown version {}", std::uint8_t(header[0]));
  }
  const int flags = int(header[1]), minLog2 = int(header[2]), maxLog2 = int(header[3]);
  const int domainStep = int(header[4]);
  FractalCode code;
  code.shape = shape;
  code.iterations = int(header[5]);
  code.paddedSide = get<std::uint16_t>(header + 6);
  code.base = get<std::int32_t>(header + 8);
  code.residualError = get<std::uint32_t>(header + 12);
  code.hasResidual = (flags & kResidualFlag) != 0;
  const bool hasBorder = (flags & kBorderFlag) != 0;
  const int width = get<std::uint16_t>(header + 16), height = get<std::uint16_t>(header + 18);
  if (width != shape.width || height != shape.height) {
    return makeError("fractal tile is {}x{}, expected {}x{}", width, height, shape.width,
                     shape.height);
  }
  if (flags > (kResidualFlag | kBorderFlag) || (hasBorder && borderLength(shape) == 0) ||
      minLog2 < kMinRangeLog2 || maxLog2 > kMaxRangeLog2 || minLog2 > maxLog2 ||
      domainStep % 2 != 0 || domainStep > 64) {
    return makeError("fractal tile has invalid parameters");
  }
  const int top = 1 << maxLog2;
  // The padded side follows from the shape and the largest range (as fractal::encode pads),
  // which also bounds every allocation below by the tile's size.
  if (code.paddedSide != paddedSideFor(shape, maxLog2)) {
    return makeError("fractal tile has a padded side of {} for a {}x{} tile", code.paddedSide,
                     shape.width, shape.height);
  }
  // Streams: no stream can be larger than a few bytes per smallest range.
  const std::size_t maxRanges =
      std::size_t(code.paddedSide >> minLog2) * std::size_t(code.paddedSide >> minLog2);
  // The border stream is bounded the same way: 4 bytes per border sample.
  const std::size_t maxRawStream = 4 * std::max(maxRanges, std::size_t(borderLength(shape))) + 1;
  std::vector<std::byte> streams[kStreams];
  std::size_t at = kHeaderBytes;
  auto readStream = [&](std::vector<std::byte>& stream) -> Status {
    if (bytes.size() - at < 8) return makeError("fractal tile is truncated");
    const std::uint32_t raw = get<std::uint32_t>(bytes.data() + at);
    const std::uint32_t frame = get<std::uint32_t>(bytes.data() + at + 4);
    at += 8;
    if (raw > maxRawStream || frame > bytes.size() - at) {
      return makeError("fractal tile has a corrupt stream header");
    }
    stream.resize(raw);
    if (Status s = coding::zstdDecompressExact(bytes.subspan(at, frame), stream); !s) return s;
    at += frame;
    return {};
  };
  for (std::vector<std::byte>& stream : streams) {
    if (Status s = readStream(stream); !s) return s.error();
  }
  if (hasBorder) {
    std::vector<std::byte> borderStream;
    if (Status s = readStream(borderStream); !s) return s.error();
    const std::size_t length = std::size_t(borderLength(shape));
    if (borderStream.empty() || int(borderStream[0]) < 1 || int(borderStream[0]) > 4 ||
        borderStream.size() != 1 + length * std::size_t(borderStream[0])) {
      return makeError("fractal tile has a corrupt border stream");
    }
    std::vector<std::uint32_t> deltas(length);
    coding::readBytePlanes(std::span(borderStream).subspan(1), int(borderStream[0]), deltas);
    code.border.resize(length);
    std::int64_t value = 0;
    for (std::size_t k = 0; k < length; ++k) {
      value += coding::unzigzag(deltas[k]);
      if (value < 0 || value > kMaxReliefSteps) {
        return makeError("fractal tile has a corrupt border stream");
      }
      code.border[k] = std::int32_t(value);
    }
  }
  // Means: [planes][planes byte planes].
  const std::vector<std::byte>& meanStream = streams[kMeans];
  if (meanStream.empty() || int(meanStream[0]) < 1 || int(meanStream[0]) > 4 ||
      (meanStream.size() - 1) % std::size_t(meanStream[0]) != 0) {
    return makeError("fractal tile has a corrupt mean stream");
  }
  const int planes = int(meanStream[0]);
  std::vector<std::uint32_t> meanDeltas((meanStream.size() - 1) / std::size_t(planes));
  coding::readBytePlanes(std::span(meanStream).subspan(1), planes, meanDeltas);
  const std::size_t nonFlatCount = streams[kDomains].size() / 2;
  if (streams[kDomains].size() % 2 != 0 || streams[kIsometries].size() != nonFlatCount) {
    return makeError("fractal tile has corrupt domain streams");
  }

  std::size_t splitAt = 0, rangeAt = 0, nonFlatAt = 0;
  MeanGrid means(code.paddedSide, minLog2);
  bool corrupt = false;
  auto split = [&](int, int, int, bool& isSplit) {
    if (splitAt >= streams[kSplits].size() || std::uint8_t(streams[kSplits][splitAt]) > 1) {
      return false;
    }
    isSplit = streams[kSplits][splitAt++] == std::byte(1);
    return true;
  };
  auto leaf = [&](int x, int y, int log2) {
    if (rangeAt >= streams[kScales].size() || rangeAt >= meanDeltas.size()) return false;
    RangeBlock range;
    range.x = std::uint16_t(x);
    range.y = std::uint16_t(y);
    range.sizeLog2 = std::uint8_t(log2);
    const int scale = int(streams[kScales][rangeAt]) - kMaxScaleIndex;
    if (scale < -kMaxScaleIndex || scale > kMaxScaleIndex) return false;
    range.scaleIndex = std::int8_t(scale);
    const std::int64_t mean =
        std::int64_t(means.predict(x, y)) + std::int64_t(coding::unzigzag(meanDeltas[rangeAt]));
    if (mean < 0 || mean > kMaxReliefSteps) return false;
    means.fill(x, y, log2, std::int32_t(mean));
    range.mean = std::uint32_t(mean) << kFractionBits;
    ++rangeAt;
    if (scale != 0) {
      if (nonFlatAt >= nonFlatCount) return false;
      const int r = 1 << log2, step = domainStepFor(r, domainStep);
      const int perSide = domainsPerSide(code.paddedSide, r, domainStep);
      const int index = int(streams[kDomains][nonFlatAt]) |
                        (int(streams[kDomains][nonFlatCount + nonFlatAt]) << 8);
      const int isometry = int(streams[kIsometries][nonFlatAt]);
      ++nonFlatAt;
      if (index >= perSide * perSide || isometry > 7) return false;
      range.domainX = std::uint16_t((index % perSide) * step);
      range.domainY = std::uint16_t((index / perSide) * step);
      range.isometry = std::uint8_t(isometry);
    }
    code.ranges.push_back(range);
    return true;
  };
  for (int y = 0; y < code.paddedSide && !corrupt; y += top) {
    for (int x = 0; x < code.paddedSide && !corrupt; x += top) {
      corrupt = !walk(x, y, maxLog2, minLog2, split, leaf);
    }
  }
  if (corrupt || splitAt != streams[kSplits].size() || rangeAt != streams[kScales].size() ||
      rangeAt != meanDeltas.size() || nonFlatAt != nonFlatCount) {
    return makeError("fractal tile has corrupt range streams");
  }
  if (code.hasResidual) {
    std::vector<std::uint32_t> bins(shape.sampleCount());
    if (Status s = coding::readPlanedResiduals(bytes.subspan(at), "fractal", bins); !s) {
      return s.error();
    }
    code.residual.resize(bins.size());
    for (std::size_t i = 0; i < bins.size(); ++i) code.residual[i] = coding::unzigzag(bins[i]);
  } else if (at != bytes.size()) {
    return makeError("fractal tile has {} trailing bytes", bytes.size() - at);
  }
  if (Status s = validate(code); !s) return s.error();
  return code;
}

}  // namespace tellus::fractal
