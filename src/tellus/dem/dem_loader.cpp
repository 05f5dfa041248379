#include "tellus/dem/dem_loader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "tellus/core/memory_budget.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/dem_source.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

constexpr int kRowsPerRead = 256;

// Reads every row of `source` into grid.heights, with a progress line.
Status readAllRows(DemSource& source, HeightGrid& grid) {
  Progress progress("read", std::uint64_t(grid.height));
  for (int row = 0; row < grid.height; row += kRowsPerRead) {
    const int count = std::min(kRowsPerRead, grid.height - row);
    const std::size_t first = std::size_t(row) * std::size_t(grid.width);
    std::span<float> rows(grid.heights.data() + first,
                          std::size_t(count) * std::size_t(grid.width));
    if (Status s = source.readRows(row, count, rows); !s) return s;
    progress.advance(std::uint64_t(count));
  }
  return {};
}

}  // namespace

Result<HeightGrid> loadDem(const std::vector<fs::path>& inputs, const DemLoadOptions& options) {
  Result<std::unique_ptr<DemSource>> opened = DemSource::open(inputs, options);
  if (!opened) return opened.error();
  DemSource& source = *opened.value();
  const DemSourceInfo& info = source.info();

  const double samples = double(info.width) * double(info.height);
  const std::string subject =
      fmt::format("'{}' ({} x {} samples)", info.name, info.width, info.height);
  const char* wayOut =
      "a tile store streams from disk: build one with 'tellus build' and read a coarser --level "
      "of it or render it with --algo rings";
  if (Status fits = checkMemoryFor(
          "loading " + subject, samples * (kGridBytesPerSample + options.callerBytesPerSample), wayOut);
      !fits) {
    return fits.error();
  }
  HeightGrid grid(info.width, info.height);
  grid.spacingXM = info.spacingXM;
  grid.spacingYM = info.spacingYM;
  grid.georef = info.georef;
  if (Status s = readAllRows(source, grid); !s) return s.error();
  const bool hasVoids =
      std::any_of(grid.heights.begin(), grid.heights.end(), [](float v) { return std::isnan(v); });
  if (hasVoids) {
    // The grid is in memory anyway, so the filled copy is too.
    if (Status fits = checkMemoryFor("filling the voids of " + subject,
                                     samples * kVoidFillBytesPerSample, wayOut);
        !fits) {
      return fits.error();
    }
    Result<std::size_t> filled =
        source.fillVoids(fs::temp_directory_path(), std::numeric_limits<std::size_t>::max());
    if (!filled) return filled.error();
    grid.filledVoidCount = filled.value();
    if (Status s = readAllRows(source, grid); !s) return s.error();
  }
  return grid;
}

}  // namespace tellus
