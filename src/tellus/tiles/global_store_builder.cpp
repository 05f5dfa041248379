#include "tellus/tiles/global_store_builder.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "tellus/core/stopwatch.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/core/scratch_folder.hpp"
#include "tellus/dem/decoded_heights_copy.hpp"
#include "tellus/dem/dem_source.hpp"
#include "tellus/dem/latlon_warper.hpp"
#include "tellus/tiles/global_store.hpp"
#include "tellus/tiles/pyramid_builder.hpp"
#include "tellus/tiles/tile_codec.hpp"
#include "tellus/tiles/tile_store_writer.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

// A source feeds the shallowest depth whose spacing is at most this much coarser than its own:
// ETOPO5 (5') lands on depth 3 (5.27' with 256-cell tiles) rather than depth 4 (2.64', four
// times the tiles for no detail).
constexpr double kNativeSpacingSlack = 1.1;
// More tiles than this is a mistake (a --max-depth far beyond the sources), not a build.
constexpr std::size_t kMaxTiles = 4'000'000;

bool intersects(const GeoBounds& a, const LatLonBox& b) {
  return a.westDeg < b.eastDeg && b.westDeg < a.eastDeg && a.southDeg < b.northDeg &&
         b.southDeg < a.northDeg;
}

// A tile being built: its samples (metres, on the quantum) and the largest deviation of its
// descendants' samples from its surface so far.
struct Node {
  GeoTileKey key;
  std::vector<float> heights;
  std::mutex mutex;
  float error = 0.0f;
  void raise(float e) {
    std::lock_guard lock(mutex);
    error = std::max(error, e);
  }
};

class GlobalBuilder {
 public:
  GlobalBuilder(std::vector<LatLonSource> sources, std::vector<int> depths,
                std::set<GeoTileKey> tiles, GlobalStoreMetadata metadata, const TileCodec& codec,
                TileStoreWriter& writer)
      : sources_(std::move(sources)),
        depths_(std::move(depths)),
        tiles_(std::move(tiles)),
        metadata_(std::move(metadata)),
        codec_(codec),
        writer_(writer),
        n_(metadata_.tileCells) {}

  Status run(GlobalBuildReport& report);

 private:
  LatLonWarper* warper();
  Status computePoles();
  std::vector<int> sourcesTouching(const GeoBounds& box, int depth) const;
  // The source samples GDAL's warper reads for `key`, per source it uses (it reads the part of
  // the source inside the tile at full resolution: a shallow tile over a fine source is a
  // large read), and the tile's own samples: the units of the build's progress.
  std::map<int, double> warpCosts(GeoTileKey key) const;
  double tileCost(GeoTileKey key) const;
  Status warpTile(GeoTileKey key, std::vector<float>& heights);
  float deviation(const Node& fine, const Node& coarse) const;
  void build(GeoTileKey key, std::vector<Node*> chain);
  Status encodeAndWrite(const Node& node);
  void fail(const Error& error);

  std::vector<LatLonSource> sources_;
  std::vector<int> depths_;  // each source's native depth
  std::set<GeoTileKey> tiles_;
  GlobalStoreMetadata metadata_;
  const TileCodec& codec_;
  TileStoreWriter& writer_;
  const int n_;
  tbb::enumerable_thread_specific<std::unique_ptr<LatLonWarper>> warpers_;
  std::unique_ptr<Progress> progress_;
  std::mutex writeMutex_;
  std::atomic<bool> failed_{false};
  Error failure_;
  std::atomic<std::uint64_t> uncovered_{0};
  const Stopwatch start_;
  std::uint64_t payloadBytes_ = 0;
  float minHeight_ = std::numeric_limits<float>::max();
  float maxHeight_ = std::numeric_limits<float>::lowest();
};

void GlobalBuilder::fail(const Error& error) {
  std::lock_guard lock(writeMutex_);
  if (!failed_) failure_ = error;
  failed_ = true;
}

LatLonWarper* GlobalBuilder::warper() {
  std::unique_ptr<LatLonWarper>& local = warpers_.local();
  if (!local) {
    Result<std::unique_ptr<LatLonWarper>> opened =
        LatLonWarper::open(sources_, metadata_.zeroYieldsToSeaFloor, metadata_.edgeBlendM);
    if (!opened) {
      fail(opened.error());
      return nullptr;
    }
    local = std::move(opened.value());
  }
  return local.get();
}

// The sources that can give values inside `box` at `depth`, finest first.
std::vector<int> GlobalBuilder::sourcesTouching(const GeoBounds& box, int depth) const {
  const double margin = GlobalTiling::tileSizeDeg(depth) / n_;
  const GeoBounds grown{box.westDeg - margin, box.southDeg - margin, box.eastDeg + margin,
                        box.northDeg + margin};
  std::vector<int> use;
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    if (intersects(grown, sources_[i].pixelBox)) use.push_back(int(i));
  }
  return use;
}

// The height every sample on a pole gets: the mean of the sources along it (one value per
// pole, so that the pole is one point on the ellipsoid).
Status GlobalBuilder::computePoles() {
  LatLonWarper* w = warper();
  if (!w) return failure_;
  constexpr int kColumns = 360;
  std::vector<float> row(kColumns);
  std::vector<int> all(sources_.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  for (const double lat : {90.0, -90.0}) {
    if (Status s = w->warp(-180.0, lat, 1.0, kColumns, 1, all, row); !s) return s;
    double sum = 0.0;
    int count = 0;
    for (float v : row) {
      if (std::isfinite(v)) sum += v, ++count;
    }
    const double q = metadata_.quantumM;
    const float pole = float(std::nearbyint((count > 0 ? sum / count : 0.0) / q) * q);
    (lat > 0 ? metadata_.northPoleM : metadata_.southPoleM) = pole;
  }
  return {};
}

std::map<int, double> GlobalBuilder::warpCosts(GeoTileKey key) const {
  const GeoBounds box = GlobalTiling::bounds(key);
  std::map<int, double> costs;
  for (int i : sourcesTouching(box, key.depth)) {
    const LatLonSource& source = sources_[std::size_t(i)];
    const LatLonBox& p = source.pixelBox;
    const double w = std::min(box.eastDeg, p.eastDeg) - std::max(box.westDeg, p.westDeg);
    const double h = std::min(box.northDeg, p.northDeg) - std::max(box.southDeg, p.southDeg);
    const double area = (p.eastDeg - p.westDeg) * (p.northDeg - p.southDeg);
    const double share = w > 0.0 && h > 0.0 && area > 0.0 ? std::min(1.0, w * h / area) : 0.0;
    costs[i] = share * double(source.width) * double(source.height);
  }
  return costs;
}

double GlobalBuilder::tileCost(GeoTileKey key) const {
  double cost = double(n_ + 1) * double(n_ + 1);
  for (const auto& [source, samples] : warpCosts(key)) cost += samples;
  return cost;
}

Status GlobalBuilder::warpTile(GeoTileKey key, std::vector<float>& heights) {
  LatLonWarper* w = warper();
  if (!w) return failure_;
  const GeoBounds box = GlobalTiling::bounds(key);
  const double step = GlobalTiling::tileSizeDeg(key.depth) / n_;
  const int side = n_ + 1;
  heights.assign(std::size_t(side) * std::size_t(side), 0.0f);
  const std::vector<int> use = sourcesTouching(box, key.depth);
  // Progress as each source's warp goes (a shallow tile over a fine source takes minutes).
  const std::map<int, double> costs = warpCosts(key);
  std::map<int, double> reported;
  const auto progress = [&](int source, double fraction) {
    const auto cost = costs.find(source);
    if (cost == costs.end()) return;
    const double due = cost->second * fraction;
    double& done = reported[source];
    if (due > done) {
      progress_->advance(std::uint64_t(due) - std::uint64_t(done));
      done = double(std::uint64_t(due));
    }
  };
  if (Status s = w->warp(box.westDeg, box.northDeg, step, side, side, use, heights, progress); !s) {
    return s;
  }
  progress_->advance(std::uint64_t(side) * std::uint64_t(side));
  for (const auto& [source, cost] : costs) {  // what GDAL's reports left out
    const double done = reported[source];
    if (cost > done) progress_->advance(std::uint64_t(cost) - std::uint64_t(done));
  }
  if (key.x == GlobalTiling::tilesX(key.depth) - 1) {
    // 180 E is 180 W: take the column the first tile of the row has.
    const GeoBounds west{-180.0, box.southDeg, -180.0 + step, box.northDeg};
    std::vector<float> column(static_cast<std::size_t>(side));
    if (Status s = w->warp(-180.0, box.northDeg, step, 1, side,
                           sourcesTouching(west, key.depth), column);
        !s) {
      return s;
    }
    for (int j = 0; j < side; ++j) heights[std::size_t(j) * side + std::size_t(n_)] = column[std::size_t(j)];
  }
  if (key.y == 0) std::fill_n(heights.begin(), side, metadata_.northPoleM);
  if (key.y == GlobalTiling::tilesY(key.depth) - 1) {
    std::fill_n(heights.begin() + std::ptrdiff_t(side) * n_, side, metadata_.southPoleM);
  }
  const double q = metadata_.quantumM, inverse = 1.0 / q;
  std::uint64_t uncovered = 0;
  for (float& h : heights) {
    if (!std::isfinite(h)) {
      h = 0.0f;
      ++uncovered;
    }
    h = float(std::nearbyint(double(h) * inverse) * q);
  }
  // Counted per stored sample (a point on a shared edge counts in each tile that holds it).
  uncovered_ += uncovered;
  return {};
}

// Largest |fine sample - coarse surface| over the fine tile's samples (the fine tile lies in
// the coarse one's footprint). The coarse surface is tileSurfaceAt()'s bilinear one, evaluated
// separably: per fine row, the coarse rows above and below are blended once over the columns
// the fine tile spans, then each sample blends two neighbours of that row (equal to
// tileSurfaceAt up to rounding; `tellus verify` recomputes it with a tolerance).
float GlobalBuilder::deviation(const Node& fine, const Node& coarse) const {
  const int shift = fine.key.depth - coarse.key.depth;
  const double scale = 1.0 / double(std::int64_t(1) << shift);
  const double originX = double(fine.key.x) * n_ * scale - double(coarse.key.x) * n_;
  const double originY = double(fine.key.y) * n_ * scale - double(coarse.key.y) * n_;
  const std::size_t row = std::size_t(n_ + 1);
  // Per column i of the fine tile: the coarse cell column it falls in and where in it.
  thread_local std::vector<int> cellOf;
  thread_local std::vector<double> fractionOf, blended;
  cellOf.resize(row);
  fractionOf.resize(row);
  for (int i = 0; i <= n_; ++i) {
    const double u = originX + i * scale;
    cellOf[std::size_t(i)] = std::clamp(int(std::floor(u)), 0, n_ - 1);
    fractionOf[std::size_t(i)] = u - cellOf[std::size_t(i)];
  }
  const int firstColumn = cellOf.front(), lastColumn = cellOf.back() + 1;
  blended.resize(std::size_t(lastColumn - firstColumn + 1));
  float worst = 0.0f;
  for (int j = 0; j <= n_; ++j) {
    const double v = originY + j * scale;
    const int v0 = std::clamp(int(std::floor(v)), 0, n_ - 1);
    const double fv = v - v0;
    const float* top = coarse.heights.data() + std::size_t(v0) * row;
    const float* bottom = top + row;
    for (int c = firstColumn; c <= lastColumn; ++c) {
      blended[std::size_t(c - firstColumn)] = top[c] + (double(bottom[c]) - top[c]) * fv;
    }
    const float* samples = fine.heights.data() + std::size_t(j) * row;
    for (std::size_t i = 0; i < row; ++i) {
      const double* b = blended.data() + (cellOf[i] - firstColumn);
      const double surface = b[0] + (b[1] - b[0]) * fractionOf[i];
      worst = std::max(worst, float(std::abs(double(samples[i]) - surface)));
    }
  }
  return worst;
}

Status GlobalBuilder::encodeAndWrite(const Node& node) {
  const TileShape shape{n_ + 1, n_ + 1};
  std::vector<std::int32_t> samples(shape.sampleCount());
  const double inverse = 1.0 / metadata_.quantumM;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double q = std::nearbyint(double(node.heights[i]) * inverse);
    if (!(std::abs(q) < 2147483647.0)) {
      return makeError("height {} m does not fit the quantum of {} m", node.heights[i],
                       metadata_.quantumM);
    }
    samples[i] = std::int32_t(q);
  }
  std::vector<std::byte> payload;
  if (Status s = codec_.encode(samples, shape, payload); !s) {
    return makeError("cannot encode {}: {}", GlobalStore::describe(node.key), s.error().message);
  }
  // A lossless codec stores the samples themselves (its round trip is what the codec tests and
  // `tellus verify` check); a lossy one is decoded so that the bounds describe what is stored.
  std::vector<std::int32_t> decoded;
  if (!codec_.lossless()) {
    decoded.resize(shape.sampleCount());
    if (Status s = codec_.decode(payload, shape, decoded); !s) {
      return makeError("internal error: {} does not decode: {}", GlobalStore::describe(node.key),
                       s.error().message);
    }
  }
  const std::vector<std::int32_t>& stored = codec_.lossless() ? samples : decoded;
  const auto [lo, hi] = std::minmax_element(stored.begin(), stored.end());
  const TileStats stats{float(*lo * metadata_.quantumM), float(*hi * metadata_.quantumM),
                        node.error};
  std::lock_guard lock(writeMutex_);
  minHeight_ = std::min(minHeight_, stats.minHeightM);
  maxHeight_ = std::max(maxHeight_, stats.maxHeightM);
  payloadBytes_ += payload.size();
  return writer_.append(GlobalStore::toTileKey(node.key), payload, stats);
}

void GlobalBuilder::build(GeoTileKey key, std::vector<Node*> chain) {
  if (failed_) return;
  Node node;
  node.key = key;
  if (Status s = warpTile(key, node.heights); !s) return fail(s.error());
  for (Node* ancestor : chain) ancestor->raise(deviation(node, *ancestor));
  std::vector<GeoTileKey> children;
  for (const GeoTileKey& child : GlobalTiling::children(key)) {
    if (tiles_.count(child)) children.push_back(child);
  }
  chain.push_back(&node);
  tbb::parallel_for(std::size_t(0), children.size(),
                    [&](std::size_t i) { build(children[i], chain); });
  if (failed_) return;
  if (Status s = encodeAndWrite(node); !s) return fail(s.error());
}

Status GlobalBuilder::run(GlobalBuildReport& report) {
  double work = 0.0, sourceSamples = 0.0;
  for (const GeoTileKey& key : tiles_) {
    const double cost = tileCost(key);
    work += cost;
    sourceSamples += cost - double(n_ + 1) * double(n_ + 1);
  }
  if (sourceSamples > 1e9) {
    spdlog::info("build --global: {} tiles; GDAL's warper reads about {:.3g} source samples in "
                 "all (each depth reads the sources at full resolution: lower --max-depth to "
                 "read less)",
                 tiles_.size(), sourceSamples);
  }
  progress_ = std::make_unique<Progress>("build --global (samples warped)", std::uint64_t(work));
  if (Status s = computePoles(); !s) return s;
  tbb::parallel_for(0, 2, [&](int x) { build({0, x, 0}, {}); });
  progress_.reset();
  if (failed_) return failure_;
  // Sources that gave no height at all (every value nodata, NaN or infinite): a store of 0 m
  // would be nonsense, and such a source is a mistake even beside good ones.
  std::vector<std::string> empty;
  std::uint64_t finite = 0;
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    std::uint64_t values = 0;
    for (const std::unique_ptr<LatLonWarper>& w : warpers_) {
      if (w) values += w->finiteValuesFrom(int(i));
    }
    finite += values;
    if (values == 0) empty.push_back(sources_[i].path.string());
  }
  if (finite == 0) {
    return makeError("no source has a valid height: every sample of {} is nodata, NaN or "
                     "infinite; nothing was written",
                     fmt::join(empty, ", "));
  }
  for (const std::string& source : empty) {
    spdlog::warn("'{}' gave no valid height where the store reads it (nodata, NaN or infinite "
                 "values, or hidden by a finer source)",
                 source);
  }
  metadata_.minHeightM = minHeight_;
  metadata_.maxHeightM = maxHeight_;
  metadata_.uncoveredSamples = uncovered_;
  metadata_.buildSeconds =
      start_.elapsedS();
  metadata_.tilesPerDepth.assign(std::size_t(metadata_.deepestDepth + 1), 0);
  for (const GeoTileKey& key : tiles_) ++metadata_.tilesPerDepth[std::size_t(key.depth)];
  if (Status s = writer_.finishWithMetadata(globalMetadataToJson(metadata_)); !s) return s;
  report.metadata = metadata_;
  report.tiles = tiles_.size();
  report.payloadBytes = payloadBytes_;
  report.decodedBytes = std::uint64_t(tiles_.size()) * std::uint64_t(n_ + 1) * (n_ + 1) * 4;
  return {};
}

}  // namespace

int nativeDepth(double spacingDeg, int tileCells, int maxDepth) {
  int depth = 0;
  while (depth < maxDepth &&
         GlobalTiling::tileSizeDeg(depth) / tileCells > spacingDeg * kNativeSpacingSlack) {
    ++depth;
  }
  return depth;
}

Result<GlobalBuildReport> buildGlobalStore(const std::vector<fs::path>& inputs,
                                           const fs::path& output,
                                           const GlobalBuildOptions& options) {
  const Stopwatch start;
  if (inputs.empty()) return makeError("build --global: give at least one source");
  if (Status s = checkOutputWritable(output); !s) return s.error();
  for (const fs::path& input : inputs) {
    std::error_code ec;
    if (fs::equivalent(input, output, ec)) {
      return makeError("the output '{}' is also an input; write the store elsewhere",
                       output.string());
    }
  }
  const int n = options.tileCells;
  if (n < 16 || n > PyramidLayout::kMaxTileSize || (n & (n - 1)) != 0) {
    return makeError("--tile must be a power of two from 16 to {}, got {}",
                     PyramidLayout::kMaxTileSize, n);
  }
  if (options.maxDepth < 0 || options.maxDepth > GlobalTiling::kMaxDepth) {
    return makeError("--max-depth must be from 0 to {}, got {}", GlobalTiling::kMaxDepth,
                     options.maxDepth);
  }
  if (!(options.quantumM >= kMinQuantumM && options.quantumM <= kMaxQuantumM)) {
    return makeError("--quantum must be from {} to {} metres, got {}", kMinQuantumM,
                     kMaxQuantumM, options.quantumM);
  }
  if (options.zstdLevel < 1 || options.zstdLevel > 22) {
    return makeError("--zstd-level must be from 1 to 22, got {}", options.zstdLevel);
  }

  // Sources, finest first (ties: the order given).
  std::vector<LatLonSource> sources;
  for (const fs::path& input : inputs) {
    Result<LatLonSource> source = describeLatLonSource(input, options.rgbEncoding);
    if (!source) return source.error();
    sources.push_back(std::move(source.value()));
  }
  const bool anyEncoded = std::any_of(sources.begin(), sources.end(), [](const LatLonSource& s) {
    return s.encoding != HeightEncoding::Plain;
  });
  if (options.rgbEncoding != HeightEncoding::Plain && !anyEncoded) {
    return makeError("--encoding {}: none of the sources is an 8-bit RGB image to decode",
                     heightEncodingName(options.rgbEncoding));
  }
  // RGB-encoded sources: GDAL's warper cannot decode their colours, so each is decoded once
  // into a Float32 copy in a private scratch folder beside the output (removed on return; that
  // of a killed build by the next one there).
  std::optional<ScratchFolder> scratch;
  if (anyEncoded) {
    Result<ScratchFolder> made =
        ScratchFolder::create(output.has_parent_path() ? output.parent_path() : fs::path("."));
    if (!made) return made.error();
    scratch.emplace(std::move(made.value()));
    for (std::size_t i = 0; i < sources.size(); ++i) {
      LatLonSource& s = sources[i];
      if (s.encoding == HeightEncoding::Plain) continue;
      s.readPath = scratch->path() / fmt::format("decoded-{}.tif", i);
      if (Status decoded = writeDecodedHeightsCopy(s.path, s.encoding, s.readPath); !decoded) {
        return decoded.error();
      }
    }
  }
  std::stable_sort(sources.begin(), sources.end(),
                   [](const LatLonSource& a, const LatLonSource& b) {
                     return a.spacingDeg < b.spacingDeg * (1.0 - 1e-6);
                   });
  if (std::none_of(sources.begin(), sources.end(),
                   [](const LatLonSource& s) { return s.coversGlobe; })) {
    spdlog::warn("no source covers the whole globe: samples outside every source are stored at "
                 "0 m (add a global source such as ETOPO5)");
  }

  // The sparse tile set: every tile a source reaches at a depth it feeds.
  GlobalStoreMetadata metadata;
  metadata.tileCells = n;
  std::vector<int> depths;
  std::set<GeoTileKey> tiles{{0, 0, 0}, {0, 1, 0}};
  for (const LatLonSource& s : sources) {
    const int depth = nativeDepth(s.spacingDeg, n, options.maxDepth);
    depths.push_back(depth);
    metadata.deepestDepth = std::max(metadata.deepestDepth, depth);
    // The samples' box, shrunk a hair so that a source ending on a tile edge does not claim the
    // tile beyond it.
    const double eps = 1e-9 * 360.0;
    const GeoBounds box{std::max(-180.0, s.sampleBox.westDeg) + eps,
                        std::max(-90.0, s.sampleBox.southDeg) + eps,
                        std::min(180.0, s.sampleBox.eastDeg) - eps,
                        std::min(90.0, s.sampleBox.northDeg) - eps};
    metadata.sources.push_back({s.path.string(), box, s.spacingDeg, depth});
    for (int d = 0; d <= depth; ++d) {
      Result<std::vector<GeoTileKey>> covering = GlobalTiling::tilesCovering(d, box, kMaxTiles);
      if (!covering) return makeError("'{}': {}", s.path.string(), covering.error().message);
      tiles.insert(covering->begin(), covering->end());
      if (tiles.size() > kMaxTiles) {
        return makeError("the sources need more than {} tiles: lower --max-depth", kMaxTiles);
      }
    }
  }

  // Codec and quantum: warped heights are not whole metres, so rounding to the quantum costs
  // up to half a step; a lossy codec adds its bound.
  metadata.codec = options.codec;
  metadata.zstdLevel = options.zstdLevel;
  metadata.zeroYieldsToSeaFloor = options.zeroYieldsToSeaFloor;
  if (!(options.edgeBlendM >= 0.0 && options.edgeBlendM <= kMaxEdgeBlendM)) {
    return makeError("the edge blending band is {} m: give 0 to {} m", options.edgeBlendM,
                     kMaxEdgeBlendM);
  }
  metadata.edgeBlendM = options.edgeBlendM;
  metadata.quantumM = options.quantumM;
  metadata.producer = "tellus " TELLUS_VERSION;
  Result<std::unique_ptr<TileCodec>> probe =
      makeCodec(options.codec, {.maxErrorSteps = 1, .zstdLevel = options.zstdLevel});
  if (!probe) return probe.error();
  const double rounding = 0.5 * options.quantumM;
  if (!probe.value()->lossless()) {
    // A global store's tiles share their edges and nest in their parents bit for bit (the
    // streaming globe renderers stitch on that; verify checks it); independently coded lossy
    // tiles do not.
    return makeError("--global stores are lossless (raw or zstd): tiles coded by '{}' would "
                     "not share their edges and parent samples exactly; use --codec zstd",
                     options.codec);
  }
  if (options.maxErrorM) {
    return makeError("--max-error applies to the lossy codecs of flat stores, not '{}'", options.codec);
  }
  metadata.maxErrorM = rounding;
  FractalOptions fractal;
  fractal.residual = true;
  Result<std::unique_ptr<TileCodec>> codec = makeCodec(
      options.codec,
      {.maxErrorSteps = metadata.maxErrorSteps, .zstdLevel = options.zstdLevel, .fractal = fractal});
  if (!codec) return codec.error();

  DemSource::setReadCacheLimit(kBuildReadCacheBytes);
  Result<std::unique_ptr<TileStoreWriter>> writer =
      TileStoreWriter::create(output, codec.value()->id());
  if (!writer) return writer.error();
  GlobalBuildReport report;
  GlobalBuilder builder(std::move(sources), std::move(depths), std::move(tiles), metadata,
                        *codec.value(), *writer.value());
  if (Status s = builder.run(report); !s) return s.error();
  std::error_code ec;
  report.fileBytes = fs::file_size(output, ec);
  report.seconds = start.elapsedS();
  return report;
}

}  // namespace tellus
