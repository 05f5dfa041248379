#include "tellus/tiles/global_store_builder.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <tbb/enumerable_thread_specific.h>
#include <unistd.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <thread>

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
#include "tellus/tiles/global_build_plan.hpp"
#include "tellus/tiles/global_store.hpp"
#include "tellus/tiles/payload_spool.hpp"
#include "tellus/tiles/store_checksums.hpp"
#include "tellus/tiles/store_container.hpp"
#include "tellus/tiles/store_format.hpp"
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

// A tile being built: its samples (metres, on the quantum; NaN where no source has a value,
// until finish() makes them 0 m) and the largest deviation of its descendants' samples from its
// surface so far.
struct Node {
  GeoTileKey key;
  std::vector<float> heights;
  std::uint32_t uncovered = 0;  // samples no source covered (0 m in `heights` once finished)
  bool readBack = false;        // an update: the samples are the previous store's
  std::mutex mutex;
  float error = 0.0f;
  void raise(float e) {
    std::lock_guard lock(mutex);
    error = std::max(error, e);
  }
};

// Where a finished tile's payload is: in this rank's spool until the join copies it into the store.
struct SpooledTile {
  GeoTileKey key;
  std::uint64_t spoolOffset = 0;
  std::uint32_t bytes = 0;
  std::uint64_t hash = 0;
  TileStats stats;
};

// What each rank reports to the others after building its subtrees (exchanged as bytes).
struct RankTotals {
  float minHeightM = std::numeric_limits<float>::max();
  float maxHeightM = std::numeric_limits<float>::lowest();
  std::uint64_t uncovered = 0;
  std::uint64_t warped = 0, readBack = 0, rewritten = 0;  // tiles
};
struct SubtreeBytes {
  std::int32_t root = 0;  // index into roots_
  std::uint32_t pad = 0;
  std::uint64_t bytes = 0;
};
struct PhaseSeconds {
  double roots = 0.0, coarse = 0.0, subtrees = 0.0, join = 0.0, peakBytes = 0.0;
};
// One index record of the finished store, as the ranks send them to rank 0.
struct PlacedTile {
  std::int32_t depth = 0, x = 0, y = 0;
  std::uint32_t bytes = 0;
  std::uint64_t offset = 0, hash = 0;
  TileStats stats;
};

// The build, on every rank (global_build_plan.hpp says how the work and the file are split):
//   A. each rank warps the roots of its subtrees (depth S) and sends the others every second
//      sample of each (what the parent at S - 1 holds of it);
//   B. every rank makes the coarse tiles above S from those samples, warping only the quarters
//      no subtree covers (a point's value does not depend on the tile it is warped for, so this
//      equals warping the whole tile), and measures them against each other;
//   C. each rank builds its subtrees depth first, each tile measured against all its ancestors
//      (coarse ones included), encoded and appended to the rank's spool (in $TMPDIR);
//   D. the ranks exchange the coarse tiles' errors (maximum), their totals and each subtree's
//      size; every rank encodes the coarse tiles and places every tile in post-order;
//   E. each rank copies its tiles from its spool to their places in rank 0's temporary file;
//      rank 0 writes its coarse tiles, the metadata and the index, and renames it into place.
// Every rank reaches every exchange; a failure travels to the next one (agree()).
class GlobalBuilder {
 public:
  // `previous` (an update, may be null): the store these sources minus the new ones made;
  // `isNew[i]`: source i was not among its sources.
  GlobalBuilder(Ranks& ranks, std::vector<LatLonSource> sources, std::set<GeoTileKey> tiles,
                GlobalStoreMetadata metadata, const TileCodec& codec, std::optional<int> splitDepth,
                const GlobalStore* previous, std::vector<bool> isNew)
      : previous_(previous),
        isNew_(std::move(isNew)),
        ranks_(ranks),
        sources_(std::move(sources)),
        tiles_(std::move(tiles)),
        metadata_(std::move(metadata)),
        codec_(codec),
        n_(metadata_.tileCells),
        forcedSplitDepth_(splitDepth) {
    reuseCodedTiles_ = previous_ && previous_->metadata().producer == metadata_.producer;
  }

  // `writer` is rank 0's (null on the others); `temporaryPath` its file, which every rank writes
  // its tiles into. Each rank spools its tiles in the system's temporary folder (node-local).
  Status run(TileStoreWriter* writer, const fs::path& temporaryPath, GlobalBuildReport& report);

 private:
  LatLonWarper* warper();
  Status computePoles();
  std::vector<int> sourcesTouching(const GeoBounds& box, int depth) const;
  // The source samples GDAL's warper reads for `key`, per source it uses (it reads the part of
  // the source inside the tile at full resolution: a shallow tile over a fine source is a
  // large read), and the tile's own samples: the units of the build's progress.
  std::map<int, double> warpCosts(GeoTileKey key) const;
  double tileCost(GeoTileKey key) const;
  // Samples [i0, i0 + columns) x [j0, j0 + rows) of tile `key` (row-major into `out`, a
  // `stride`-wide tile-sized array): the sources' values on the quantum, NaN where none has one,
  // with the 180 E column and the pole rows as the store defines them.
  Status warpSamples(GeoTileKey key, int i0, int j0, int columns, int rows, std::span<float> out,
                     bool reportProgress);
  // NaN samples become 0 m; returns how many there were.
  std::uint32_t finish(std::vector<float>& heights) const;
  // An update: whether `key` must be warped again (no new source reaches it and the poles did not
  // move: the previous store holds its samples).
  bool mustWarp(GeoTileKey key) const;
  // A tile below the split: warped, or read back from the previous store when nothing changed it.
  Status obtain(Node& node);
  // An update: whether the tile differs from the previous store's (its bytes or its statistics).
  bool rewritten(GeoTileKey key, std::uint64_t hash, const TileStats& stats) const;
  float deviation(const Node& fine, const Node& coarse) const;
  void build(Node& node, std::vector<Node*> chain);
  Status warpRoots(std::vector<std::unique_ptr<Node>>& mine);
  Status makeCoarseTiles(const std::map<int, std::vector<float>>& rootQuarters);
  Result<std::vector<std::byte>> encode(const Node& node, TileStats& stats) const;
  Status spool(const Node& node);
  void fail(const Error& error);
  // Work done (source samples read and samples warped) on this rank; rank 0 shows the job's.
  void advance(std::uint64_t steps) {
    const std::uint64_t done = workDone_ += steps;
    if (progress_) progress_->set(done + othersDone_);
  }
  // Runs `work` (oneTBB's parallel loops) while a thread sends this rank's progress to rank 0
  // (rank 0: receives the others') every quarter second; then the step's last count.
  template <typename Work>
  void shareProgressDuring(Work&& work);
  const Node* coarse(GeoTileKey key) const {
    const auto it = coarse_.find(key);
    return it == coarse_.end() ? nullptr : it->second.get();
  }

  const GlobalStore* previous_;
  // An update of a store written by this very Tellus: an unchanged tile's payload is copied.
  bool reuseCodedTiles_ = false;
  std::vector<bool> isNew_;
  Ranks& ranks_;
  std::vector<LatLonSource> sources_;
  std::set<GeoTileKey> tiles_;
  GlobalStoreMetadata metadata_;
  const TileCodec& codec_;
  const int n_;
  const std::optional<int> forcedSplitDepth_;
  int splitDepth_ = 0;
  std::vector<GeoTileKey> roots_;  // the subtrees' roots (depth S), in file order
  std::map<GeoTileKey, std::unique_ptr<Node>> coarse_;  // the tiles above S
  tbb::enumerable_thread_specific<std::unique_ptr<LatLonWarper>> warpers_;
  std::unique_ptr<Progress> progress_;  // rank 0's, for the whole job
  std::atomic<std::uint64_t> workDone_{0}, othersDone_{0};
  std::unique_ptr<PayloadSpool> spool_;
  std::mutex spoolMutex_;
  std::vector<SpooledTile> spooled_;
  std::atomic<bool> failed_{false};
  Error failure_;
  std::atomic<std::uint64_t> uncovered_{0};  // in this rank's subtrees
  std::atomic<std::uint64_t> warped_{0}, readBack_{0}, rewritten_{0};  // this rank's tiles
  RankTotals totals_;
};

void GlobalBuilder::fail(const Error& error) {
  std::lock_guard lock(spoolMutex_);
  if (!failed_) failure_ = error;
  failed_ = true;
}

template <typename Work>
void GlobalBuilder::shareProgressDuring(Work&& work) {
  // Rank 0 returns true once every other rank's last count has arrived.
  const auto share = [this](bool last) {
    if (ranks_.rank() != 0) {
      ranks_.sendProgress(workDone_, last);
      return true;
    }
    const Ranks::OthersProgress others = ranks_.progressOfOthers(last);
    othersDone_ = others.done;
    if (progress_) progress_->set(workDone_ + othersDone_);
    return others.allLast;
  };
  std::atomic<bool> finished{false};
  std::thread sharer;
  if (ranks_.size() > 1) {
    sharer = std::thread([&] {
      while (!finished) {
        for (int i = 0; i < 5 && !finished; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
        if (!finished) share(false);
      }
    });
  }
  work();
  finished = true;
  if (sharer.joinable()) sharer.join();
  if (ranks_.size() == 1) return;
  // The step's last counts; rank 0 keeps its bar moving while it waits for the others'.
  while (!share(true)) std::this_thread::sleep_for(std::chrono::milliseconds(50));
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

Status GlobalBuilder::warpSamples(GeoTileKey key, int i0, int j0, int columns, int rows,
                                  std::span<float> out, bool reportProgress) {
  LatLonWarper* w = warper();
  if (!w) return failure_;
  const GeoBounds tile = GlobalTiling::bounds(key);
  const double step = GlobalTiling::tileSizeDeg(key.depth) / n_;
  // Dyadic steps: these corners are exact, so every point is the one a whole tile would warp.
  const double west = tile.westDeg + i0 * step, north = tile.northDeg - j0 * step;
  const GeoBounds box{west, north - (rows - 1) * step, west + (columns - 1) * step, north};
  const std::size_t stride = std::size_t(n_ + 1);
  std::vector<float> region(std::size_t(columns) * std::size_t(rows), 0.0f);
  // Progress as each source's warp goes (a shallow tile over a fine source takes minutes).
  const std::map<int, double> costs = reportProgress ? warpCosts(key) : std::map<int, double>{};
  std::map<int, double> reported;
  const auto progress = [&](int source, double fraction) {
    const auto cost = costs.find(source);
    if (cost == costs.end()) return;
    const double due = cost->second * fraction;
    double& done = reported[source];
    if (due > done) {
      advance(std::uint64_t(due) - std::uint64_t(done));
      done = double(std::uint64_t(due));
    }
  };
  if (Status s = w->warp(west, north, step, columns, rows, sourcesTouching(box, key.depth), region,
                         progress);
      !s) {
    return s;
  }
  if (reportProgress) {
    advance(std::uint64_t(columns) * std::uint64_t(rows));
    for (const auto& [source, cost] : costs) {  // what GDAL's reports left out
      const double done = reported[source];
      if (cost > done) advance(std::uint64_t(cost) - std::uint64_t(done));
    }
  }
  if (key.x == GlobalTiling::tilesX(key.depth) - 1 && i0 + columns - 1 == n_) {
    // 180 E is 180 W: take the column the first tile of the row has.
    const GeoBounds westEdge{-180.0, box.southDeg, -180.0 + step, box.northDeg};
    std::vector<float> column(static_cast<std::size_t>(rows));
    if (Status s = w->warp(-180.0, north, step, 1, rows, sourcesTouching(westEdge, key.depth), column);
        !s) {
      return s;
    }
    for (int j = 0; j < rows; ++j) {
      region[std::size_t(j) * std::size_t(columns) + std::size_t(columns - 1)] = column[std::size_t(j)];
    }
  }
  if (key.y == 0 && j0 == 0) std::fill_n(region.begin(), columns, metadata_.northPoleM);
  if (key.y == GlobalTiling::tilesY(key.depth) - 1 && j0 + rows - 1 == n_) {
    std::fill_n(region.begin() + std::ptrdiff_t(columns) * (rows - 1), columns, metadata_.southPoleM);
  }
  const double q = metadata_.quantumM, inverse = 1.0 / q;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      const float h = region[std::size_t(j) * std::size_t(columns) + std::size_t(i)];
      // NaN stays NaN: finish() counts it.
      out[std::size_t(j0 + j) * stride + std::size_t(i0 + i)] =
          float(std::nearbyint(double(h) * inverse) * q);
    }
  }
  return {};
}

std::uint32_t GlobalBuilder::finish(std::vector<float>& heights) const {
  std::uint32_t uncovered = 0;
  for (float& h : heights) {
    if (!std::isfinite(h)) {
      h = 0.0f;
      ++uncovered;
    }
  }
  return uncovered;
}

bool GlobalBuilder::mustWarp(GeoTileKey key) const {
  if (!previous_ || !previous_->find(key)) return true;
  const GlobalStoreMetadata& before = previous_->metadata();
  if (key.y == 0 && before.northPoleM != metadata_.northPoleM) return true;
  if (key.y == GlobalTiling::tilesY(key.depth) - 1 && before.southPoleM != metadata_.southPoleM) {
    return true;
  }
  const auto anyNew = [&](const GeoBounds& box) {
    for (int i : sourcesTouching(box, key.depth)) {
      if (isNew_[std::size_t(i)]) return true;
    }
    return false;
  };
  const GeoBounds box = GlobalTiling::bounds(key);
  if (anyNew(box)) return true;
  // The eastern column of the last tile of a row is warped at 180 W (warpSamples).
  const double step = GlobalTiling::tileSizeDeg(key.depth) / n_;
  return key.x == GlobalTiling::tilesX(key.depth) - 1 &&
         anyNew({-180.0, box.southDeg, -180.0 + step, box.northDeg});
}

Status GlobalBuilder::obtain(Node& node) {
  node.heights.assign(std::size_t(n_ + 1) * std::size_t(n_ + 1), 0.0f);
  if (mustWarp(node.key)) {
    if (Status s = warpSamples(node.key, 0, 0, n_ + 1, n_ + 1, node.heights, true); !s) return s;
    node.uncovered = finish(node.heights);
    ++warped_;
    return {};
  }
  // The samples the warp would give again, bit for bit (the same sources reach the tile, and
  // the store's metres are the quantised warp), and the count of those no source covered.
  if (Status s = previous_->readTileMetres(node.key, node.heights); !s) return s;
  node.uncovered = previous_->find(node.key)->stats.uncoveredSamples;
  node.readBack = true;
  advance(std::uint64_t(tileCost(node.key)));
  ++readBack_;
  return {};
}

bool GlobalBuilder::rewritten(GeoTileKey key, std::uint64_t hash, const TileStats& stats) const {
  if (!previous_) return true;
  const TileRecord* before = previous_->find(key);
  return !before || before->payloadHash != hash || before->stats.minHeightM != stats.minHeightM ||
         before->stats.maxHeightM != stats.maxHeightM ||
         before->stats.geometricErrorM != stats.geometricErrorM ||
         before->stats.uncoveredSamples != stats.uncoveredSamples;
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

Result<std::vector<std::byte>> GlobalBuilder::encode(const Node& node, TileStats& stats) const {
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
  // Global stores are lossless (buildGlobalStore refuses lossy codecs): the samples are stored.
  const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
  stats = TileStats{float(*lo * metadata_.quantumM), float(*hi * metadata_.quantumM), node.error,
                    node.uncovered};
  return payload;
}

Status GlobalBuilder::spool(const Node& node) {
  TileStats stats;
  Result<std::vector<std::byte>> payload = std::vector<std::byte>();
  const TileRecord* before = node.readBack ? previous_->find(node.key) : nullptr;
  if (before && before->stats.geometricErrorM == node.error && reuseCodedTiles_) {
    // The previous store's samples, error and count: its payload is what encoding would give
    // again (the same Tellus wrote it, so the same codec), without the cost of encoding.
    if (Status s = readCheckedPayload(previous_->source(), *before, GlobalStore::describe(node.key),
                                      payload.value());
        !s) {
      return s;
    }
    stats = before->stats;
  } else {
    payload = encode(node, stats);
  }
  if (!payload) return payload.error();
  Result<std::uint64_t> at = spool_->append(payload.value());
  if (!at) return at.error();
  const std::uint64_t hash = store_format::payloadChecksum(payload.value(), GlobalStore::toTileKey(node.key));
  if (rewritten(node.key, hash, stats)) ++rewritten_;
  std::lock_guard lock(spoolMutex_);
  totals_.minHeightM = std::min(totals_.minHeightM, stats.minHeightM);
  totals_.maxHeightM = std::max(totals_.maxHeightM, stats.maxHeightM);
  spooled_.push_back({node.key, at.value(), std::uint32_t(payload->size()), hash, stats});
  return {};
}

// `node` holds its finished samples; `chain` its ancestors, root first.
void GlobalBuilder::build(Node& node, std::vector<Node*> chain) {
  if (failed_) return;
  for (Node* ancestor : chain) ancestor->raise(deviation(node, *ancestor));
  std::vector<GeoTileKey> children;
  for (const GeoTileKey& child : GlobalTiling::children(node.key)) {
    if (tiles_.count(child)) children.push_back(child);
  }
  chain.push_back(&node);
  tbb::parallel_for(std::size_t(0), children.size(), [&](std::size_t i) {
    if (failed_) return;
    Node child;
    child.key = children[i];
    if (Status s = obtain(child); !s) return fail(s.error());
    uncovered_ += child.uncovered;
    build(child, chain);
  });
  if (failed_) return;
  if (Status s = spool(node); !s) return fail(s.error());
}

Status GlobalBuilder::warpRoots(std::vector<std::unique_ptr<Node>>& mine) {
  tbb::parallel_for(std::size_t(0), mine.size(), [&](std::size_t i) {
    if (failed_) return;
    Node& node = *mine[i];
    node.heights.assign(std::size_t(n_ + 1) * std::size_t(n_ + 1), 0.0f);
    // Roots are warped even in an update: the tiles above them need their uncovered samples.
    if (Status s = warpSamples(node.key, 0, 0, n_ + 1, n_ + 1, node.heights, true); !s) {
      fail(s.error());
    }
    ++warped_;
  });
  return failed_ ? Status(failure_) : Status();
}

// Every second sample of a tile, (n/2 + 1)^2 of them: what its parent holds of it.
std::vector<float> everySecondSample(const std::vector<float>& heights, int n) {
  const int half = n / 2;
  std::vector<float> quarter;
  quarter.reserve(std::size_t(half + 1) * std::size_t(half + 1));
  for (int j = 0; j <= half; ++j) {
    for (int i = 0; i <= half; ++i) quarter.push_back(heights[std::size_t(2 * j) * std::size_t(n + 1) + std::size_t(2 * i)]);
  }
  return quarter;
}

Status GlobalBuilder::makeCoarseTiles(const std::map<int, std::vector<float>>& rootQuarters) {
  const int half = n_ / 2;
  const std::size_t stride = std::size_t(n_ + 1);
  for (int depth = splitDepth_ - 1; depth >= 0; --depth) {
    std::vector<Node*> level;
    for (auto& [key, node] : coarse_) {
      if (key.depth == depth) level.push_back(node.get());
    }
    tbb::parallel_for(std::size_t(0), level.size(), [&](std::size_t t) {
      if (failed_) return;
      Node& node = *level[t];
      node.heights.assign(stride * stride, 0.0f);
      const std::vector<GeoTileKey> children = GlobalTiling::children(node.key);
      for (int q = 0; q < 4; ++q) {
        const GeoTileKey child = children[std::size_t(q)];
        const int i0 = (q % 2) * half, j0 = (q / 2) * half;
        const std::vector<float>* quarter = nullptr;
        std::vector<float> fromCoarse;
        if (child.depth == splitDepth_) {
          const auto root = std::lower_bound(roots_.begin(), roots_.end(), child, postOrderLess);
          if (root != roots_.end() && *root == child) {
            quarter = &rootQuarters.at(int(root - roots_.begin()));
          }
        } else if (const Node* c = coarse(child)) {
          fromCoarse = everySecondSample(c->heights, n_);
          quarter = &fromCoarse;
        }
        if (quarter) {
          for (int j = 0; j <= half; ++j) {
            std::copy_n(quarter->begin() + std::ptrdiff_t(j) * (half + 1), half + 1,
                        node.heights.begin() + std::ptrdiff_t(std::size_t(j0 + j) * stride + std::size_t(i0)));
          }
        } else if (Status s = warpSamples(node.key, i0, j0, half + 1, half + 1, node.heights, false); !s) {
          return fail(s.error());
        }
      }
    });
    if (failed_) return failure_;
  }
  // The coarse samples are complete: NaN becomes 0 m (counted once, by rank 0), then each coarse
  // tile is measured against the coarse tiles above it.
  std::uint64_t uncovered = 0;
  for (auto& [key, node] : coarse_) {
    node->uncovered = finish(node->heights);
    uncovered += node->uncovered;
  }
  if (ranks_.rank() == 0) uncovered_ += uncovered;
  std::vector<Node*> all;
  for (auto& [key, node] : coarse_) all.push_back(node.get());
  tbb::parallel_for(std::size_t(0), all.size(), [&](std::size_t t) {
    for (int d = 0; d < all[t]->key.depth; ++d) {
      Node* ancestor = coarse_.at(ancestorAt(all[t]->key, d)).get();
      ancestor->raise(deviation(*all[t], *ancestor));
    }
  });
  return {};
}

template <typename T>
std::span<const std::byte> bytesOf(const std::vector<T>& values) {
  return std::as_bytes(std::span(values));
}

Status GlobalBuilder::run(TileStoreWriter* writer, const fs::path& temporaryPath,
                          GlobalBuildReport& report) {
  const int rank = ranks_.rank(), rankCount = ranks_.size();
  // The split and the deal (every rank computes the same).
  std::vector<TileWork> work;
  for (const GeoTileKey& key : tiles_) work.push_back({key, tileCost(key)});
  splitDepth_ = forcedSplitDepth_ ? std::clamp(*forcedSplitDepth_, 0, metadata_.deepestDepth)
                                  : chooseSplitDepth(work, rankCount);
  for (const GeoTileKey& key : tiles_) {
    if (key.depth == splitDepth_) roots_.push_back(key);
    if (key.depth < splitDepth_) coarse_.emplace(key, std::make_unique<Node>()).first->second->key = key;
  }
  std::sort(roots_.begin(), roots_.end(), postOrderLess);
  std::vector<double> subtreeCost(roots_.size(), 0.0);
  double sourceSamples = 0.0;
  for (const TileWork& tile : work) {
    if (tile.key.depth < splitDepth_) continue;  // made from their children's samples
    sourceSamples += tile.cost - double(n_ + 1) * double(n_ + 1);
    const GeoTileKey root = ancestorAt(tile.key, splitDepth_);
    const auto at = std::lower_bound(roots_.begin(), roots_.end(), root, postOrderLess);
    subtreeCost[std::size_t(at - roots_.begin())] += tile.cost;
  }
  const std::vector<int> owner = dealContiguous(subtreeCost, rankCount);
  std::vector<std::unique_ptr<Node>> mine;
  std::vector<int> mineIndex;
  for (std::size_t r = 0; r < roots_.size(); ++r) {
    if (owner[r] != rank) continue;
    mine.push_back(std::make_unique<Node>());
    mine.back()->key = roots_[r];
    mineIndex.push_back(int(r));
  }
  const double totalWork = std::accumulate(subtreeCost.begin(), subtreeCost.end(), 0.0);
  if (rank == 0) {
    // The largest subtree bounds how finely the work divides (docs/scale.md's model).
    const double largest = subtreeCost.empty() ? 0.0 : *std::max_element(subtreeCost.begin(), subtreeCost.end());
    spdlog::info("build --global: {} tiles, {} subtrees from depth {} on {} rank{}; the largest "
                 "subtree is {:.1f} % of the work",
                 tiles_.size(), roots_.size(), splitDepth_, rankCount, rankCount > 1 ? "s" : "",
                 100.0 * largest / std::max(1.0, std::accumulate(subtreeCost.begin(), subtreeCost.end(), 0.0)));
    if (sourceSamples > 1e9) {
      spdlog::info("build --global: GDAL's warper reads about {:.3g} source samples in all (each "
                   "depth from {} down reads the sources at full resolution: lower --max-depth to "
                   "read less)",
                   sourceSamples, splitDepth_);
    }
    progress_ = std::make_unique<Progress>(
        rankCount > 1 ? fmt::format("build --global (samples warped, {} ranks)", rankCount)
                      : std::string("build --global (samples warped)"),
        std::uint64_t(totalWork));
  }
  // Each step's seconds on this rank: roots, coarse tiles, subtrees, join (exchanges and copies).
  PhaseSeconds phases;
  Stopwatch phase;

  // A: the poles, this rank's roots, and what the coarse tiles need of every root.
  Status local = computePoles();
  if (local) {
    Result<std::unique_ptr<PayloadSpool>> made = PayloadSpool::create();
    if (made) spool_ = std::move(made.value());
    else local = made.error();
  }
  if (local) shareProgressDuring([&] { local = warpRoots(mine); });
  else shareProgressDuring([] {});
  if (Status s = agree(ranks_, local); !s) return s;
  phases.roots = phase.elapsedS();
  phase.restart();
  std::vector<std::byte> sent;
  for (std::size_t k = 0; k < mine.size(); ++k) {
    const std::int32_t index = mineIndex[k];
    const std::vector<float> quarter = everySecondSample(mine[k]->heights, n_);
    const auto* p = reinterpret_cast<const std::byte*>(&index);
    sent.insert(sent.end(), p, p + sizeof(index));
    const std::span<const std::byte> q = bytesOf(quarter);
    sent.insert(sent.end(), q.begin(), q.end());
  }
  Result<std::vector<std::vector<std::byte>>> received = ranks_.allGather(sent);
  if (!received) return received.error();
  std::map<int, std::vector<float>> rootQuarters;
  const std::size_t quarterCount = std::size_t(n_ / 2 + 1) * std::size_t(n_ / 2 + 1);
  for (const std::vector<std::byte>& part : received.value()) {
    for (std::size_t at = 0; at < part.size(); at += sizeof(std::int32_t) + quarterCount * sizeof(float)) {
      std::int32_t index = 0;
      std::memcpy(&index, part.data() + at, sizeof(index));
      std::vector<float>& quarter = rootQuarters[index];
      quarter.resize(quarterCount);
      std::memcpy(quarter.data(), part.data() + at + sizeof(index), quarterCount * sizeof(float));
    }
  }
  received->clear();

  // B: the coarse tiles, on every rank.
  local = makeCoarseTiles(rootQuarters);
  rootQuarters.clear();
  if (Status s = agree(ranks_, local); !s) return s;
  phases.coarse = phase.elapsedS();
  phase.restart();

  // C: this rank's subtrees.
  shareProgressDuring([&] {
    tbb::parallel_for(std::size_t(0), mine.size(), [&](std::size_t k) {
      Node& root = *mine[k];
      root.uncovered = finish(root.heights);
      uncovered_ += root.uncovered;
      std::vector<Node*> chain;
      for (int d = 0; d < splitDepth_; ++d) chain.push_back(coarse_.at(ancestorAt(root.key, d)).get());
      build(root, chain);
    });
  });
  mine.clear();
  progress_.reset();
  if (Status s = agree(ranks_, failed_ ? Status(failure_) : Status()); !s) return s;
  phases.subtrees = phase.elapsedS();
  phase.restart();

  // D: the coarse errors (each rank raised them from its own subtrees), the totals, each
  // subtree's bytes.
  std::vector<float> errors;
  for (auto& [key, node] : coarse_) errors.push_back(node->error);
  Result<std::vector<float>> allErrors = allGatherValues<float>(ranks_, errors);
  if (!allErrors) return allErrors.error();
  for (std::size_t k = 0; k < allErrors->size(); ++k) {
    float& error = errors[k % errors.size()];  // each rank sent one value per coarse tile
    error = std::max(error, (*allErrors)[k]);
  }
  {
    std::size_t k = 0;
    for (auto& [key, node] : coarse_) node->error = errors[k++];
  }
  totals_.uncovered = uncovered_;
  totals_.warped = warped_;
  totals_.readBack = readBack_;
  totals_.rewritten = rewritten_;
  const std::vector<RankTotals> mineTotals{totals_};
  Result<std::vector<RankTotals>> allTotals = allGatherValues<RankTotals>(ranks_, mineTotals);
  if (!allTotals) return allTotals.error();
  std::map<GeoTileKey, std::vector<SpooledTile>> bySubtree;
  for (const SpooledTile& tile : spooled_) bySubtree[ancestorAt(tile.key, splitDepth_)].push_back(tile);
  std::vector<SubtreeBytes> sizes;
  for (auto& [root, tiles] : bySubtree) {
    std::sort(tiles.begin(), tiles.end(), [](const SpooledTile& a, const SpooledTile& b) { return postOrderLess(a.key, b.key); });
    SubtreeBytes size;
    size.root = std::int32_t(std::lower_bound(roots_.begin(), roots_.end(), root, postOrderLess) - roots_.begin());
    for (const SpooledTile& tile : tiles) size.bytes += tile.bytes;
    sizes.push_back(size);
  }
  Result<std::vector<SubtreeBytes>> allSizes = allGatherValues<SubtreeBytes>(ranks_, sizes);
  if (!allSizes) return allSizes.error();
  std::vector<std::uint64_t> subtreeBytes(roots_.size(), 0);
  for (const SubtreeBytes& size : allSizes.value()) subtreeBytes[std::size_t(size.root)] = size.bytes;
  std::vector<std::uint64_t> finiteFrom(sources_.size(), 0);
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    for (const std::unique_ptr<LatLonWarper>& w : warpers_) {
      if (w) finiteFrom[i] += w->finiteValuesFrom(int(i));
    }
  }
  Result<std::vector<std::uint64_t>> allFinite = allGatherValues<std::uint64_t>(ranks_, finiteFrom);
  if (!allFinite) return allFinite.error();

  // The coarse tiles' payloads (every rank makes the same) and every tile's place, in post-order.
  std::map<GeoTileKey, std::vector<std::byte>> coarsePayloads;
  std::map<GeoTileKey, TileStats> coarseStats;
  for (auto& [key, node] : coarse_) {
    Result<std::vector<std::byte>> payload = encode(*node, coarseStats[key]);
    if (!payload) return payload.error();  // the same on every rank
    if (rewritten(key, store_format::payloadChecksum(payload.value(), GlobalStore::toTileKey(key)),
                  coarseStats[key])) {
      ++report.tilesRewritten;  // counted once: every rank makes the same
    }
    coarsePayloads[key] = std::move(payload.value());
  }
  std::vector<GeoTileKey> top(roots_);
  for (auto& [key, node] : coarse_) top.push_back(key);
  std::sort(top.begin(), top.end(), postOrderLess);
  std::uint64_t offset = store_format::kHeaderBytes;
  std::map<GeoTileKey, std::uint64_t> placeOf;  // coarse tiles' and subtrees' first bytes
  for (const GeoTileKey& key : top) {
    placeOf[key] = offset;
    if (key.depth < splitDepth_) {
      offset += coarsePayloads[key].size();
    } else {
      offset += subtreeBytes[std::size_t(std::lower_bound(roots_.begin(), roots_.end(), key, postOrderLess) - roots_.begin())];
    }
  }
  const std::uint64_t payloadEnd = offset;

  // E: each rank copies its tiles into rank 0's temporary file; rank 0 adds the coarse tiles.
  std::vector<PlacedTile> placed;
  local = {};
  const int fd = ::open(temporaryPath.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) {
    local = makeError("cannot open '{}' to write this rank's tiles: {} (the ranks must share "
                      "the output's file system)", temporaryPath.string(), std::strerror(errno));
  }
  for (const auto& [root, tiles] : bySubtree) {
    std::uint64_t at = placeOf.at(root);
    for (const SpooledTile& tile : tiles) {
      if (local) local = spool_->copyTo(tile.spoolOffset, tile.bytes, fd, at, temporaryPath.string());
      placed.push_back({tile.key.depth, tile.key.x, tile.key.y, tile.bytes, at, tile.hash, tile.stats});
      at += tile.bytes;
    }
  }
  if (rank == 0) {
    for (const auto& [key, payload] : coarsePayloads) {
      if (local) local = writeAllAt(fd, payload, placeOf.at(key), temporaryPath.string());
      placed.push_back({key.depth, key.x, key.y, std::uint32_t(payload.size()), placeOf.at(key),
                        store_format::payloadChecksum(payload, GlobalStore::toTileKey(key)),
                        coarseStats[key]});
    }
  }
  if (fd >= 0) {
    if (local && ::fsync(fd) != 0) local = makeError("cannot flush '{}': {}", temporaryPath.string(), std::strerror(errno));
    ::close(fd);
  }
  spool_.reset();
  if (Status s = agree(ranks_, local); !s) return s;
  Result<std::vector<PlacedTile>> index = allGatherValues<PlacedTile>(ranks_, placed);
  if (!index) return index.error();
  placed.clear();

  // Sources that gave no height at all (every value nodata, NaN or infinite): a store of 0 m
  // would be nonsense, and such a source is a mistake even beside good ones.
  std::vector<std::string> empty;
  std::uint64_t finite = 0;
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    std::uint64_t values = 0;
    for (std::size_t k = i; k < allFinite->size(); k += sources_.size()) values += (*allFinite)[k];
    finite += values;
    if (values == 0) empty.push_back(sources_[i].path.string());
  }
  if (finite == 0) {
    return makeError("no source has a valid height: every sample of {} is nodata, NaN or "
                     "infinite; nothing was written",
                     fmt::join(empty, ", "));
  }
  if (rank == 0) {
    for (const std::string& source : empty) {
      spdlog::warn("'{}' gave no valid height where the store reads it (nodata, NaN or infinite "
                   "values, or hidden by a finer source)",
                   source);
    }
  }
  RankTotals total;
  for (const RankTotals& t : allTotals.value()) {
    total.minHeightM = std::min(total.minHeightM, t.minHeightM);
    total.maxHeightM = std::max(total.maxHeightM, t.maxHeightM);
    total.uncovered += t.uncovered;
    report.tilesWarped += t.warped;
    report.tilesReadBack += t.readBack;
    report.tilesRewritten += t.rewritten;
  }
  for (const auto& [key, stats] : coarseStats) {
    total.minHeightM = std::min(total.minHeightM, stats.minHeightM);
    total.maxHeightM = std::max(total.maxHeightM, stats.maxHeightM);
  }
  metadata_.minHeightM = total.minHeightM;
  metadata_.maxHeightM = total.maxHeightM;
  metadata_.uncoveredSamples = total.uncovered;
  metadata_.tilesPerDepth.assign(std::size_t(metadata_.deepestDepth + 1), 0);
  for (const GeoTileKey& key : tiles_) ++metadata_.tilesPerDepth[std::size_t(key.depth)];
  if (index->size() != tiles_.size()) {
    local = makeError("internal error: the ranks placed {} tiles, the store has {}", index->size(), tiles_.size());
  } else if (rank == 0) {
    std::vector<TileRecord> records;
    records.reserve(index->size());
    for (const PlacedTile& t : index.value()) {
      records.push_back({GlobalStore::toTileKey({t.depth, t.x, t.y}), t.offset, t.bytes, t.hash, t.stats});
    }
    local = writer->placeWrittenTiles(records, payloadEnd);
    if (local) local = writer->finishWithMetadata(globalMetadataToJson(metadata_));
  }
  if (Status s = agree(ranks_, local); !s) return s;
  phases.join = phase.elapsedS();
  // Each rank's figures, for the report: its steps' seconds and its peak memory.
  struct rusage usage {};
  ::getrusage(RUSAGE_SELF, &usage);
  phases.peakBytes = double(usage.ru_maxrss) * 1024.0;
  const std::vector<PhaseSeconds> minePhases{phases};
  Result<std::vector<PhaseSeconds>> allPhases = allGatherValues<PhaseSeconds>(ranks_, minePhases);
  if (!allPhases) return allPhases.error();
  for (const PhaseSeconds& p : allPhases.value()) {
    report.perRank.push_back({p.roots, p.coarse, p.subtrees, p.join, std::uint64_t(p.peakBytes)});
  }
  report.indexBytes = std::uint64_t(tiles_.size()) * store_format::kIndexRecordBytes;
  report.metadata = metadata_;
  report.tiles = tiles_.size();
  report.payloadBytes = payloadEnd - store_format::kHeaderBytes;
  report.decodedBytes = std::uint64_t(tiles_.size()) * std::uint64_t(n_ + 1) * (n_ + 1) * 4;
  report.splitDepth = splitDepth_;
  report.subtrees = roots_.size();
  report.ranks = rankCount;
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

namespace {

// What every rank works from: the sources, finest first, the sparse tile set, the metadata and
// the codec, all checked before any rank starts.
struct GlobalBuildPlan {
  std::vector<LatLonSource> sources;
  std::set<GeoTileKey> tiles;
  GlobalStoreMetadata metadata;
  std::unique_ptr<TileCodec> codec;
  std::optional<ScratchFolder> scratch;  // decoded copies of RGB-encoded sources
  std::vector<bool> isNew;               // per source: new in an update
};

Result<GlobalBuildPlan> planGlobalBuild(const std::vector<fs::path>& inputs,
                                        const fs::path& output,
                                        const GlobalBuildOptions& options) {
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
  // Described in parallel: a planet has thousands of sources, each a file to open.
  std::vector<std::optional<Result<LatLonSource>>> described(inputs.size());
  tbb::parallel_for(std::size_t(0), inputs.size(), [&](std::size_t i) {
    described[i] = describeLatLonSource(inputs[i], options.rgbEncoding);
  });
  std::vector<LatLonSource> sources;
  for (std::optional<Result<LatLonSource>>& source : described) {
    if (!*source) return source->error();  // the first bad one in the order given
    sources.push_back(std::move(source->value()));
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
  // Finest first, ties in the order given; an update's new sources keep their mark.
  std::vector<std::size_t> order(sources.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return sources[a].spacingDeg < sources[b].spacingDeg * (1.0 - 1e-6);
  });
  std::vector<LatLonSource> sorted;
  std::vector<bool> isNew;
  for (std::size_t i : order) {
    sorted.push_back(std::move(sources[i]));
    isNew.push_back(options.update && i >= options.update->newFrom);
  }
  sources = std::move(sorted);
  if (std::none_of(sources.begin(), sources.end(),
                   [](const LatLonSource& s) { return s.coversGlobe; })) {
    spdlog::warn("no source covers the whole globe: samples outside every source are stored at "
                 "0 m (add a global source such as ETOPO5)");
  }

  // The sparse tile set: every tile a source reaches at a depth it feeds.
  GlobalStoreMetadata metadata;
  metadata.tileCells = n;
  std::set<GeoTileKey> tiles{{0, 0, 0}, {0, 1, 0}};
  for (const LatLonSource& s : sources) {
    const int depth = nativeDepth(s.spacingDeg, n, options.maxDepth);
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

  GlobalBuildPlan plan;
  plan.isNew = std::move(isNew);
  plan.sources = std::move(sources);
  plan.tiles = std::move(tiles);
  plan.metadata = std::move(metadata);
  plan.codec = std::move(codec.value());
  plan.scratch = std::move(scratch);
  return plan;
}

// An update's previous store, checked against the plan: built from the inputs before the new
// ones, with the same options, and recording its tiles' uncovered samples.
Result<std::shared_ptr<GlobalStore>> openPreviousStore(const GlobalBuildOptions& options,
                                                       const GlobalBuildPlan& plan,
                                                       const std::vector<fs::path>& inputs,
                                                       const fs::path& output) {
  const GlobalBuildOptions::Update& update = *options.update;
  const std::string name = update.previous.string();
  std::error_code ec;
  if (fs::equivalent(update.previous, output, ec)) {
    return makeError("--update writes a new store: give -o another path than '{}' (an output "
                     "never replaces what the build reads)", name);
  }
  Result<std::shared_ptr<GlobalStore>> opened = GlobalStore::open(update.previous);
  if (!opened) return opened.error();
  const GlobalStoreMetadata& m = opened.value()->metadata();
  const auto differs = [&](const std::string& what, const std::string& before, const std::string& now) {
    return makeError("'{}' was built with {} {}, the update asks for {}: an update keeps the "
                     "store's options", name, what, before, now);
  };
  if (m.tileCells != options.tileCells) return differs("--tile", fmt::format("{}", m.tileCells), fmt::format("{}", options.tileCells));
  if (m.codec != options.codec) return differs("--codec", m.codec, options.codec);
  if (m.zstdLevel != options.zstdLevel) return differs("--zstd-level", fmt::format("{}", m.zstdLevel), fmt::format("{}", options.zstdLevel));
  if (m.quantumM != options.quantumM) return differs("--quantum", fmt::format("{}", m.quantumM), fmt::format("{}", options.quantumM));
  if (m.zeroYieldsToSeaFloor != options.zeroYieldsToSeaFloor) {
    return differs("--zero-is-land", m.zeroYieldsToSeaFloor ? "off" : "on", options.zeroYieldsToSeaFloor ? "off" : "on");
  }
  if (m.edgeBlendM != options.edgeBlendM) return differs("--blend-edges", fmt::format("{}", m.edgeBlendM), fmt::format("{}", options.edgeBlendM));
  if (update.newFrom != m.sources.size() || update.newFrom >= inputs.size()) {
    return makeError("internal error: an update of '{}' needs its {} sources, then the new ones",
                     name, m.sources.size());
  }
  for (std::size_t i = 0; i < update.newFrom; ++i) {
    if (inputs[i].string() != m.sources[i].path) {
      return makeError("internal error: source {} of the update is '{}', '{}' lists '{}'", i,
                       inputs[i].string(), name, m.sources[i].path);
    }
    // The depth it feeds now (from --max-depth) must be the depth it fed then.
    for (const GlobalStoreSource& now : plan.metadata.sources) {
      if (now.path == m.sources[i].path && now.depth != m.sources[i].depth) {
        return makeError("'{}' fed depth {} of '{}' and would feed depth {} now: give the "
                         "--max-depth it was built with", now.path, m.sources[i].depth, name, now.depth);
      }
    }
  }
  std::uint64_t counted = 0;
  for (const TileRecord& record : opened.value()->records()) counted += record.stats.uncoveredSamples;
  if (counted != m.uncoveredSamples) {
    return makeError("'{}' does not record its tiles' uncovered samples (it was built by an "
                     "older Tellus): build it anew once, then update it", name);
  }
  return opened;
}

}  // namespace

Result<GlobalBuildReport> buildGlobalStore(const std::vector<fs::path>& inputs,
                                           const fs::path& output,
                                           const GlobalBuildOptions& options, Ranks* ranks) {
  const Stopwatch start;
  SingleRank single;
  Ranks& job = ranks ? *ranks : single;
  // Every rank plans the same build; a rank that cannot (a file it cannot read) stops them all.
  Result<GlobalBuildPlan> plan = planGlobalBuild(inputs, output, options);
  std::shared_ptr<GlobalStore> previous;
  Status planned = plan ? Status() : Status(plan.error());
  if (planned && options.update) {
    Result<std::shared_ptr<GlobalStore>> opened = openPreviousStore(options, *plan, inputs, output);
    if (opened) previous = std::move(opened.value());
    else planned = opened.error();
  }
  if (Status s = agree(job, planned); !s) return s.error();

  DemSource::setReadCacheLimit(kBuildReadCacheBytes);
  // Rank 0 owns the temporary file every rank writes its tiles into.
  std::unique_ptr<TileStoreWriter> writer;
  Status created;
  if (job.rank() == 0) {
    Result<std::unique_ptr<TileStoreWriter>> made =
        TileStoreWriter::create(output, plan->codec->id());
    if (made) writer = std::move(made.value());
    else created = made.error();
  }
  if (Status s = agree(job, created); !s) return s.error();
  const std::string named = writer ? writer->temporaryPath().string() : std::string();
  Result<std::vector<std::vector<std::byte>>> names =
      job.allGather(std::as_bytes(std::span(named.data(), named.size())));
  if (!names) return names.error();
  const std::vector<std::byte>& first = names->front();
  const fs::path temporary(std::string(reinterpret_cast<const char*>(first.data()), first.size()));

  GlobalBuildReport report;
  GlobalBuilder builder(job, std::move(plan->sources), std::move(plan->tiles),
                        std::move(plan->metadata), *plan->codec, options.splitDepth,
                        previous.get(), std::move(plan->isNew));
  if (Status s = builder.run(writer.get(), temporary, report); !s) return s.error();
  std::error_code ec;
  report.fileBytes = fs::file_size(output, ec);
  report.seconds = start.elapsedS();
  return report;
}

}  // namespace tellus
