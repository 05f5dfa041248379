#include "tellus/export/geographic_pyramid.hpp"

#include <sys/statvfs.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <optional>

#include <tbb/parallel_for.h>

#include "tellus/core/geodesy.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/export/quantized_mesh_tile_builder.hpp"

namespace tellus {
namespace fs = std::filesystem;

double cesiumGeometricErrorM(int level) {
  const double levelZero = wgs84::kSemiMajorAxisM * 2.0 * std::numbers::pi * 0.25 / (65.0 * 2.0);
  return std::ldexp(levelZero, -level);
}

namespace {

// Tiles of `level` that touch the data's box; every tile of the levels up to `globeLevels`.
GeographicTileRange tilesCovering(const LonLatBox& box, int level, int globeLevels) {
  if (level <= std::max(globeLevels, 0)) return {0, 0, (2 << level) - 1, (1 << level) - 1};
  const double extent = quantizedMeshTileExtentDeg(level);
  const int tilesX = 2 << level, tilesY = 1 << level;
  auto index = [&](double value, double origin, int count) {
    return std::clamp(int(std::floor((value - origin) / extent)), 0, count - 1);
  };
  return {index(box.westDeg, -180.0, tilesX), index(box.southDeg, -90.0, tilesY),
          index(box.eastDeg, -180.0, tilesX), index(box.northDeg, -90.0, tilesY)};
}

}  // namespace

bool GeographicPyramid::isLeaf(int level, int x, int y) const {
  if (level >= maxLevel) return true;
  const GeographicTileRange& below = ranges[std::size_t(level + 1)];
  return below.x1 < 2 * x || below.x0 > 2 * x + 1 || below.y1 < 2 * y || below.y0 > 2 * y + 1;
}

double GeographicPyramid::tileBoundM(int level, int x, int y) const {
  const bool earlyLeaf = level < maxLevel && isLeaf(level, x, y);
  return kTileBoundShare * cesiumGeometricErrorM(earlyLeaf ? level + kLeafRefinementLevels : level);
}

std::array<double, 4> GeographicPyramid::edgeBoundsM(int level, int x, int y) const {
  const double own = tileBoundM(level, x, y);
  const int columns = 2 << level, rows = 1 << level;
  const GeographicTileRange& range = ranges[std::size_t(level)];
  const auto across = [&](int nx, int ny) {
    nx = (nx + columns) % columns;
    if (ny < 0 || ny >= rows || !range.contains(nx, ny)) return own;
    return std::min(own, tileBoundM(level, nx, ny));
  };
  return {across(x - 1, y), across(x + 1, y), across(x, y - 1), across(x, y + 1)};
}

Result<GeographicPyramid> planGeographicPyramid(const LonLatSampler& source, const std::string& storeName,
                                                const GeographicPyramidOptions& options) {
  if (options.tileSamples < 3 || options.tileSamples > 1025) {
    return makeError("tile lattice of {} samples a side: it must be 3 to 1025", options.tileSamples);
  }
  if (options.maxLevel > 20) {
    return makeError("level {} is beyond 20 (tiles of 15 cm)", options.maxLevel);
  }
  if (options.globeLevels < 0 || options.globeLevels > 8) {
    return makeError("--globe-levels {} would write {} tiles of the whole globe; give 0 to 8",
                     options.globeLevels,
                     2 * ((std::uint64_t(1) << (2 * std::clamp(options.globeLevels, 0, 30) + 2)) - 1) / 3);
  }
  GeographicPyramid pyramid;
  pyramid.dataBox = source.bounds();
  const int n = options.tileSamples;
  while (pyramid.naturalMaxLevel < 20 &&
         quantizedMeshTileExtentDeg(pyramid.naturalMaxLevel) / (n - 1) > source.spacingDeg()) {
    ++pyramid.naturalMaxLevel;
  }
  // Levels finer than the data add tiles without detail (clients refine the finest level by
  // themselves); two beyond it are allowed, for lattices that sample between the samples.
  if (options.maxLevel > pyramid.naturalMaxLevel + kExtraPyramidLevels) {
    return makeError("--max-level {} is {} levels finer than '{}' needs (level {} already has a "
                     "lattice as fine as its samples): its tiles would add no detail; give at "
                     "most {}",
                     options.maxLevel, options.maxLevel - pyramid.naturalMaxLevel, storeName,
                     pyramid.naturalMaxLevel, pyramid.naturalMaxLevel + kExtraPyramidLevels);
  }
  pyramid.maxLevel = options.maxLevel < 0 ? pyramid.naturalMaxLevel : options.maxLevel;
  for (int level = 0; level <= pyramid.maxLevel; ++level) {
    pyramid.ranges.push_back(tilesCovering(pyramid.dataBox, level, options.globeLevels));
    pyramid.tiles += pyramid.ranges.back().count();
  }
  return pyramid;
}

PyramidLevelReport summarizeLevel(int level, const std::vector<PyramidTileResult>& tiles) {
  PyramidLevelReport report;
  report.level = level;
  report.geometricErrorM = cesiumGeometricErrorM(level);
  report.tiles = tiles.size();
  for (const PyramidTileResult& r : tiles) {
    report.bytes += r.bytes;
    report.triangles += r.stats.triangles;
    report.truthSamples += r.stats.truthSamples;
    report.truthStride = std::max(report.truthStride, r.stats.truthStride);
    report.maxErrorM = std::max(report.maxErrorM, r.stats.maxErrorM);
  }
  return report;
}

Status checkFilesFit(const fs::path& folder, std::uint64_t files, const std::string& what,
                     const std::string& advice) {
  fs::path parent = fs::absolute(folder).lexically_normal();
  if (parent.filename().empty()) parent = parent.parent_path();
  parent = parent.parent_path();
  struct statvfs disk {};
  if (::statvfs(parent.c_str(), &disk) != 0) return {};  // unknown: no refusal
  const double block = double(std::max<unsigned long>(disk.f_frsize, 512));
  const double needBytes = double(files) * block;
  const double freeBytes = double(disk.f_bavail) * double(disk.f_frsize);
  const bool inodesKnown = disk.f_files > 0;
  if (needBytes > freeBytes || (inodesKnown && double(files) > double(disk.f_favail))) {
    return makeError("{} is {} files: at least {} and {} files on disk, more than the {} and {} "
                     "files free in '{}'; {}",
                     what, files, formatByteCount(needBytes), files, formatByteCount(freeBytes),
                     inodesKnown ? std::to_string(disk.f_favail) : std::string("unknown"),
                     parent.string(), advice);
  }
  return {};
}

Status forEachPyramidTile(const GeographicPyramid& pyramid, int level,
                          const std::function<Status(int x, int y)>& build,
                          const std::function<void()>& done) {
  const GeographicTileRange& range = pyramid.ranges.at(std::size_t(level));
  const auto columns = std::uint64_t(range.x1 - range.x0 + 1);
  std::mutex errorMutex;
  std::optional<Error> firstError;
  std::atomic<bool> failed{false};
  tbb::parallel_for(std::uint64_t(0), range.count(), [&](std::uint64_t k) {
    if (failed.load()) return;  // the export has failed: stop early
    const int x = range.x0 + int(k % columns);
    const int y = range.y0 + int(k / columns);
    if (Status s = build(x, y); !s) {
      std::lock_guard lock(errorMutex);
      if (!firstError) firstError = s.error();
      failed = true;
      return;
    }
    if (done) done();
  });
  if (firstError) return *firstError;
  return {};
}

}  // namespace tellus
