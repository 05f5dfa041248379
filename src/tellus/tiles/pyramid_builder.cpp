#include "tellus/tiles/pyramid_builder.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include <spdlog/spdlog.h>

#include "tellus/core/stopwatch.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/dem_source.hpp"
#include "tellus/tiles/tile_store.hpp"
#include "tellus/tiles/tile_store_writer.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

constexpr double kDefaultFloatQuantumM = 0.01;

struct EncodedTile {
  TileKey key;
  std::vector<std::byte> payload;
  TileStats stats;
};

// One band of level-0 rows [index * N, index * N + N], padded east to the pyramid's full
// width by repeating the last column, and south by repeating the last row.
struct Band {
  int index = 0;
  bool beyondData = false;  // every row is the last data row
  std::vector<float> heights;
  std::vector<EncodedTile> level0Tiles;
  std::vector<std::vector<float>> errors;  // [level][tile column], level >= 1
  Status status;
};

// A coarser level being assembled: tileSize + 1 rows of its samples for the current tile row.
struct LevelRows {
  int width = 0;  // samples per row: tilesX * N + 1
  std::vector<float> heights;
  std::vector<float> errors;  // per tile column
};

class Builder {
 public:
  Builder(DemSource& source, StoreMetadata metadata, const TileCodec& codec,
          TileStoreWriter& writer)
      : source_(source),
        metadata_(std::move(metadata)),
        layout_(metadata_.layout),
        codec_(codec),
        writer_(writer),
        n_(layout_.tileSize()),
        paddedWidth_(n_ * PyramidLayout::stride(layout_.levelCount() - 1) + 1),
        bandCount_(PyramidLayout::stride(layout_.levelCount() - 1)) {
    levels_.resize(std::size_t(layout_.levelCount()));
    for (int level = 1; level < layout_.levelCount(); ++level) {
      LevelRows& rows = levels_[std::size_t(level)];
      rows.width = layout_.tilesX(level) * n_ + 1;
      rows.heights.assign(std::size_t(rows.width) * std::size_t(n_ + 1), 0.0f);
      rows.errors.assign(std::size_t(layout_.tilesX(level)), 0.0f);
    }
  }

  Status run(BuildReport& report);

 private:
  Status readBand(Band& band);
  void encodeLevel0(Band& band) const;
  void measureErrors(Band& band) const;
  float bandError(const Band& band, int level, int tileX) const;
  Status consume(Band& band);
  Result<EncodedTile> encodeTile(TileKey key, const float* heights, std::size_t rowPitch, int step,
                                 float geometricError) const;
  Status append(const EncodedTile& tile);

  DemSource& source_;
  StoreMetadata metadata_;
  const PyramidLayout& layout_;
  const TileCodec& codec_;
  TileStoreWriter& writer_;
  const int n_;
  const int paddedWidth_;  // level-0 samples per band row
  const int bandCount_;    // bands needed to complete the top level
  std::vector<float> lastDataRow_;
  std::vector<LevelRows> levels_;
  std::vector<std::vector<float>> beyondDataErrors_;  // errors of a beyond-data band (all equal)
  std::uint64_t payloadBytes_ = 0;
  std::size_t tiles_ = 0;
  float minHeight_ = std::numeric_limits<float>::max();
  float maxHeight_ = std::numeric_limits<float>::lowest();
  // Largest |decoded - input| seen, in steps: the store's error when the codec bounds nothing.
  mutable std::atomic<std::int64_t> worstCodecSteps_{0};
};

Status Builder::readBand(Band& band) {
  const int rows = n_ + 1;
  const int width = source_.info().width, height = source_.info().height;
  band.heights.resize(std::size_t(rows) * std::size_t(paddedWidth_));
  const int firstRow = band.index * n_;
  band.beyondData = firstRow >= height;
  int dataRows = 0;
  if (!band.beyondData) {
    dataRows = std::min(rows, height - firstRow);
    std::vector<float> read(std::size_t(width) * std::size_t(dataRows));
    if (Status s = source_.readRows(firstRow, dataRows, read); !s) return s;
    for (int r = 0; r < dataRows; ++r) {
      float* dst = band.heights.data() + std::size_t(r) * std::size_t(paddedWidth_);
      const float* src = read.data() + std::size_t(r) * std::size_t(width);
      std::copy(src, src + width, dst);
      std::fill(dst + width, dst + paddedWidth_, src[width - 1]);
    }
    if (firstRow + dataRows == height) {
      const float* last =
          band.heights.data() + std::size_t(dataRows - 1) * std::size_t(paddedWidth_);
      lastDataRow_.assign(last, last + paddedWidth_);
    }
  }
  for (int r = dataRows; r < rows; ++r) {
    std::copy(lastDataRow_.begin(), lastDataRow_.end(),
              band.heights.begin() + std::ptrdiff_t(r) * paddedWidth_);
  }
  for (float v : band.heights) {
    if (!std::isfinite(v)) return makeError("internal error: void sample after void filling");
  }
  return {};
}

Result<EncodedTile> Builder::encodeTile(TileKey key, const float* heights, std::size_t rowPitch,
                                        int step, float geometricError) const {
  const TileShape shape = layout_.tileShape();
  // Per-thread buffers: a tile's samples and, for lossy codecs, what they decode to.
  thread_local std::vector<std::int32_t> samples, decoded;
  samples.resize(shape.sampleCount());
  const double inverseQuantum = 1.0 / metadata_.quantumM;
  for (int j = 0; j <= n_; ++j) {
    const float* row = heights + std::size_t(j) * rowPitch;
    for (int i = 0; i <= n_; ++i) {
      const float h = row[std::size_t(i) * std::size_t(step)];
      const double q = std::nearbyint(double(h) * inverseQuantum);
      if (!(std::abs(q) < 2147483647.0)) {
        return makeError("height {} m does not fit the quantum of {} m", h, metadata_.quantumM);
      }
      samples[std::size_t(j) * std::size_t(n_ + 1) + std::size_t(i)] = std::int32_t(q);
    }
  }
  EncodedTile tile;
  tile.key = key;
  if (Status s = codec_.encode(samples, shape, tile.payload); !s) {
    return makeError("cannot encode {}: {}", TileStore::describe(key), s.error().message);
  }
  // A lossless codec stores the samples themselves (its round trip is what the codec tests
  // and `tellus verify` check). A lossy one is decoded here: the bounds must describe the
  // stored heights that renderers will draw, and an unbounded one's error is measured.
  const std::vector<std::int32_t>* stored = &samples;
  if (!codec_.lossless()) {
    decoded.resize(shape.sampleCount());
    if (Status s = codec_.decode(tile.payload, shape, decoded); !s) {
      return makeError("internal error: {} does not decode: {}", TileStore::describe(key),
                       s.error().message);
    }
    stored = &decoded;
  }
  if (!codec_.boundsError() && !codec_.lossless()) {
    std::int64_t worst = 0;
    for (std::size_t i = 0; i < decoded.size(); ++i) {
      worst = std::max(worst, std::abs(std::int64_t(decoded[i]) - std::int64_t(samples[i])));
    }
    std::int64_t seen = worstCodecSteps_.load();
    while (worst > seen && !worstCodecSteps_.compare_exchange_weak(seen, worst)) {
    }
  }
  const auto [lo, hi] = std::minmax_element(stored->begin(), stored->end());
  tile.stats = {float(*lo * metadata_.quantumM), float(*hi * metadata_.quantumM), geometricError};
  return tile;
}

void Builder::encodeLevel0(Band& band) const {
  if (band.index >= layout_.tilesY(0)) return;
  const int tiles = layout_.tilesX(0);
  band.level0Tiles.resize(std::size_t(tiles));
  std::vector<Status> failures{std::size_t(tiles)};
  tbb::parallel_for(0, tiles, [&](int tx) {
    Result<EncodedTile> tile =
        encodeTile({0, tx, band.index}, band.heights.data() + std::size_t(tx) * std::size_t(n_),
                   std::size_t(paddedWidth_), 1, 0.0f);
    if (tile)
      band.level0Tiles[std::size_t(tx)] = std::move(tile.value());
    else
      failures[std::size_t(tx)] = tile.error();
  });
  for (Status& s : failures) {
    if (!s) band.status = s;
  }
}

// Largest |h - I_L| over this band's part of level-L tile column tileX.
float Builder::bandError(const Band& band, int level, int tileX) const {
  const int s = PyramidLayout::stride(level);
  const float inv = 1.0f / float(s);
  const std::size_t pitch = std::size_t(paddedWidth_);
  const float* h = band.heights.data();
  float worst = 0.0f;
  for (int cy = 0; cy < n_ / s; ++cy) {
    const std::size_t y0 = std::size_t(cy * s);
    for (int cx = tileX * n_; cx < (tileX + 1) * n_; ++cx) {
      const std::size_t x0 = std::size_t(cx) * std::size_t(s);
      const float h00 = h[y0 * pitch + x0], h10 = h[y0 * pitch + x0 + std::size_t(s)];
      const float h01 = h[(y0 + std::size_t(s)) * pitch + x0];
      const float h11 = h[(y0 + std::size_t(s)) * pitch + x0 + std::size_t(s)];
      for (int j = 0; j <= s; ++j) {
        const float t = float(j) * inv;
        const float west = h00 + (h01 - h00) * t, east = h10 + (h11 - h10) * t;
        const float* row = h + (y0 + std::size_t(j)) * pitch + x0;
        for (int i = 0; i <= s; ++i) {
          const float surface = west + (east - west) * (float(i) * inv);
          worst = std::max(worst, std::abs(row[i] - surface));
        }
      }
    }
  }
  return worst;
}

void Builder::measureErrors(Band& band) const {
  const int levels = layout_.levelCount();
  band.errors.assign(std::size_t(levels), {});
  if (band.beyondData && !beyondDataErrors_.empty()) {
    band.errors = beyondDataErrors_;  // identical content, identical errors
    return;
  }
  std::vector<std::pair<int, int>> jobs;  // (level, tile column)
  for (int level = 1; level < levels; ++level) {
    band.errors[std::size_t(level)].assign(std::size_t(layout_.tilesX(level)), 0.0f);
    for (int tx = 0; tx < layout_.tilesX(level); ++tx) jobs.emplace_back(level, tx);
  }
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t i) {
    const auto [level, tx] = jobs[i];
    band.errors[std::size_t(level)][std::size_t(tx)] = bandError(band, level, tx);
  });
}

Status Builder::append(const EncodedTile& tile) {
  payloadBytes_ += tile.payload.size();
  ++tiles_;
  return writer_.append(tile.key, tile.payload, tile.stats);
}

Status Builder::consume(Band& band) {
  if (!band.status) return band.status;
  if (band.beyondData && beyondDataErrors_.empty()) beyondDataErrors_ = band.errors;
  for (const EncodedTile& tile : band.level0Tiles) {
    minHeight_ = std::min(minHeight_, tile.stats.minHeightM);
    maxHeight_ = std::max(maxHeight_, tile.stats.maxHeightM);
    if (Status s = append(tile); !s) return s;
  }
  for (int level = 1; level < layout_.levelCount(); ++level) {
    const int s = PyramidLayout::stride(level);
    const int tileRow = band.index / s;
    if (tileRow >= layout_.tilesY(level)) continue;
    LevelRows& rows = levels_[std::size_t(level)];
    // This band's samples of the level: band rows 0, s, ..., N.
    const int firstRow = (band.index - tileRow * s) * (n_ / s);
    for (int k = 0; k <= n_ / s; ++k) {
      const float* src = band.heights.data() + std::size_t(k * s) * std::size_t(paddedWidth_);
      float* dst = rows.heights.data() + std::size_t(firstRow + k) * std::size_t(rows.width);
      for (int c = 0; c < rows.width; ++c) dst[c] = src[std::size_t(c) * std::size_t(s)];
    }
    for (std::size_t tx = 0; tx < rows.errors.size(); ++tx) {
      rows.errors[tx] = std::max(rows.errors[tx], band.errors[std::size_t(level)][tx]);
    }
    if ((band.index + 1) % s != 0) continue;
    // The level's tile row is complete: encode it on all cores, write it in order.
    const int tiles = layout_.tilesX(level);
    std::vector<Result<EncodedTile>> encoded(std::size_t(tiles), Error{});
    tbb::parallel_for(0, tiles, [&](int tx) {
      encoded[std::size_t(tx)] =
          encodeTile({level, tx, tileRow}, rows.heights.data() + std::size_t(tx) * std::size_t(n_),
                     std::size_t(rows.width), 1, rows.errors[std::size_t(tx)]);
    });
    for (Result<EncodedTile>& tile : encoded) {
      if (!tile) return tile.error();
      if (Status st = append(tile.value()); !st) return st;
    }
    std::fill(rows.errors.begin(), rows.errors.end(), 0.0f);
  }
  return {};
}

Status Builder::run(BuildReport& report) {
  Progress progress("build", std::uint64_t(bandCount_));
  int nextBand = 0;
  Status failure;
  std::atomic<bool> failed{false};
  const auto tokens = std::size_t(tbb::this_task_arena::max_concurrency()) + 1;
  tbb::parallel_pipeline(
      tokens, tbb::make_filter<void, std::shared_ptr<Band>>(
                  tbb::filter_mode::serial_in_order,
                  [&](tbb::flow_control& control) -> std::shared_ptr<Band> {
                    if (nextBand >= bandCount_ || failed) {
                      control.stop();
                      return nullptr;
                    }
                    auto band = std::make_shared<Band>();
                    band->index = nextBand++;
                    band->status = readBand(*band);
                    return band;
                  }) &
                  tbb::make_filter<std::shared_ptr<Band>, std::shared_ptr<Band>>(
                      tbb::filter_mode::parallel,
                      [&](std::shared_ptr<Band> band) {
                        if (band->status && !failed) {
                          encodeLevel0(*band);
                          measureErrors(*band);
                        }
                        return band;
                      }) &
                  tbb::make_filter<std::shared_ptr<Band>, void>(
                      tbb::filter_mode::serial_in_order, [&](std::shared_ptr<Band> band) {
                        if (failed) return;
                        if (Status s = consume(*band); !s) {
                          failure = s;
                          failed = true;
                        }
                        progress.advance();
                      }));
  if (failed) return failure;
  metadata_.minHeightM = minHeight_;
  metadata_.maxHeightM = maxHeight_;
  metadata_.filledVoidCount = source_.filledVoidCount();  // every sample has been read
  if (!codec_.boundsError()) metadata_.maxErrorM += double(worstCodecSteps_) * metadata_.quantumM;
  if (Status s = writer_.finish(metadata_); !s) return s;
  report.metadata = metadata_;
  report.tiles = tiles_;
  report.payloadBytes = payloadBytes_;
  report.decodedBytes = std::uint64_t(tiles_) * layout_.tileShape().sampleCount() * 4;
  return {};
}

// Picks the quantum and the codec's error bound in steps; fills metadata fields.
Status chooseQuantisation(const BuildOptions& options, const DemSourceInfo& info,
                          const TileCodec& codecKind, StoreMetadata& m) {
  const double step = info.heightStepM;
  if (options.quantumM &&
      !(*options.quantumM >= kMinQuantumM && *options.quantumM <= kMaxQuantumM)) {
    return makeError("--quantum must be from {} to {} metres, got {}", kMinQuantumM, kMaxQuantumM,
                     *options.quantumM);
  }
  m.quantumM = options.quantumM ? *options.quantumM : (step > 0.0 ? step : kDefaultFloatQuantumM);
  // Exact when every input height is a whole number of quanta.
  const double ratio = step / m.quantumM;
  const bool exact = step > 0.0 && std::abs(ratio - std::round(ratio)) < 1e-9 && ratio >= 1.0;
  const double roundingM = exact ? 0.0 : 0.5 * m.quantumM;
  if (codecKind.lossless()) {
    if (options.maxErrorM) {
      return makeError("--max-error applies to the lossy codecs (bounded, lerc, fractal), not '{}'",
                       codecKind.name());
    }
    m.maxErrorSteps = 0;
    m.maxErrorM = roundingM;
    return {};
  }
  if (!codecKind.boundsError()) {
    // The fractal codec without residual: the build measures the error it leaves.
    m.maxErrorSteps = 0;
    m.maxErrorMeasured = true;
    m.maxErrorM = roundingM;
    return {};
  }
  Result<LossyErrorBudget> budget = lossyErrorBudget(
      options.maxErrorM.value_or(kDefaultLossyMaxErrorM), m.quantumM, roundingM);
  if (!budget) return budget.error();
  m.maxErrorSteps = budget->steps;
  m.maxErrorM = budget->maxErrorM;
  return {};
}

}  // namespace

Result<LossyErrorBudget> lossyErrorBudget(double maxErrorM, double quantumM, double roundingM) {
  if (!(std::isfinite(maxErrorM) && maxErrorM >= 0.0)) {
    return makeError("--max-error must be a non-negative number of metres, got {}", maxErrorM);
  }
  const double steps = std::floor((maxErrorM - roundingM) / quantumM + 1e-9);
  if (steps < 0.0) {
    return makeError("--max-error {} m is below the rounding error of the quantum ({} m)",
                     maxErrorM, roundingM);
  }
  if (steps > 1e9) return makeError("--max-error {} m is absurdly large", maxErrorM);
  return LossyErrorBudget{std::uint32_t(steps), steps * quantumM + roundingM};
}

Result<BuildReport> buildPyramid(const std::vector<fs::path>& inputs, const fs::path& output,
                                 const BuildOptions& options) {
  const Stopwatch start;
  if (Status s = checkOutputWritable(output); !s) return s.error();
  for (const fs::path& input : inputs) {
    std::error_code ec;
    if (fs::equivalent(input, output, ec)) {
      return makeError("the output '{}' is also an input; write the store elsewhere",
                       output.string());
    }
  }
  if (options.zstdLevel < 1 || options.zstdLevel > 22) {
    return makeError("--zstd-level must be from 1 to 22, got {}", options.zstdLevel);
  }
  // An instance to validate the name and options; the real one needs the error bound. The
  // fractal codec adds its residual layer exactly when a bound is asked for.
  FractalOptions fractal = options.fractal;
  fractal.residual = options.maxErrorM.has_value();
  Result<std::unique_ptr<TileCodec>> probe = makeCodec(
      options.codec, {.maxErrorSteps = 1, .zstdLevel = options.zstdLevel, .fractal = fractal});
  if (!probe) return probe.error();

  DemSource::setReadCacheLimit(kBuildReadCacheBytes);
  Result<std::unique_ptr<DemSource>> opened = DemSource::open(inputs, options.dem);
  if (!opened) return opened.error();
  DemSource& source = *opened.value();
  const DemSourceInfo& info = source.info();

  Result<PyramidLayout> layout = PyramidLayout::create(info.width, info.height, options.tileSize);
  if (!layout) return layout.error();
  if (PyramidLayout::stride(layout->levelCount() - 1) > options.tileSize) {
    // Exact errors need each coarse cell within one band of level-0 rows: 2^(levels-1) <= N.
    int smallest = options.tileSize;
    while (smallest < PyramidLayout::kMaxTileSize) {
      smallest *= 2;
      Result<PyramidLayout> bigger = PyramidLayout::create(info.width, info.height, smallest);
      if (bigger && PyramidLayout::stride(bigger->levelCount() - 1) <= smallest) break;
    }
    return makeError("'{}' ({}x{} samples) is too large for --tile {}: use --tile {} or larger",
                     info.name, info.width, info.height, options.tileSize, smallest);
  }

  // The build streams, but its bands grow with the input's width: a few bands of level-0 rows
  // in flight plus one band per coarser level (pyramid_builder.hpp).
  {
    const double paddedWidth =
        double(options.tileSize) * PyramidLayout::stride(layout->levelCount() - 1) + 1.0;
    const double bandBytes = double(options.tileSize + 1) * paddedWidth * sizeof(float);
    if (Status fits = checkMemoryFor(
            fmt::format("building from '{}' ({} samples wide)", info.name, info.width),
            bandBytes * double(tbb::this_task_arena::max_concurrency() + 1 + layout->levelCount()) +
                double(kBuildReadCacheBytes),
            "its bands grow with the width: cut the input into narrower pieces");
        !fits) {
      return fits.error();
    }
  }
  StoreMetadata metadata;
  metadata.layout = layout.value();
  metadata.codec = options.codec;
  metadata.zstdLevel = options.zstdLevel;
  metadata.spacingXM = info.spacingXM;
  metadata.spacingYM = info.spacingYM;
  metadata.georef = info.georef;
  for (const fs::path& p : inputs) metadata.sources.push_back(p.string());
  metadata.producer = "tellus " TELLUS_VERSION;
  {
    // Lossless-ness does not depend on the bound for raw/zstd; for bounded/lerc probe with 1.
    if (Status s = chooseQuantisation(options, info, *probe.value(), metadata); !s) {
      return s.error();
    }
  }
  // BuildOptions gives the fractal thresholds in metres; the codec works in steps.
  fractal.splitRmseSteps = options.fractal.splitRmseSteps / metadata.quantumM;
  fractal.flatRmseSteps = options.fractal.flatRmseSteps / metadata.quantumM;
  Result<std::unique_ptr<TileCodec>> codec =
      makeCodec(options.codec, {.maxErrorSteps = metadata.maxErrorSteps,
                                .zstdLevel = options.zstdLevel,
                                .fractal = fractal});
  if (!codec) return codec.error();

  // Voids are filled as the bands meet them; when they are too many or too large for that,
  // the first attempt stops, the whole raster is filled and the build starts again.
  source.fillVoidsOnRead();
  BuildReport report;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt == 1) {
      spdlog::info("'{}' has too many voids to fill block by block: filling the whole raster",
                   info.name);
      const fs::path folder = output.has_parent_path() ? output.parent_path() : fs::path(".");
      Result<std::size_t> voids = source.fillVoids(folder);
      if (!voids) return voids.error();
    }
    Result<std::unique_ptr<TileStoreWriter>> writer =
        TileStoreWriter::create(output, codec.value()->id());
    if (!writer) return writer.error();
    Builder builder(source, metadata, *codec.value(), *writer.value());
    Status built = builder.run(report);
    if (built) break;
    if (attempt == 1 || !source.voidFillingOnReadGaveUp()) return built.error();
  }
  std::error_code ec;
  report.fileBytes = fs::file_size(output, ec);
  report.seconds = start.elapsedS();
  return report;
}

}  // namespace tellus
