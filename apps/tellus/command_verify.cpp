// tellus verify: checks every tile of a store (checksum, decoding, min/max against the index).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <mutex>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "global_store_cli.hpp"
#include "stack_cli.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/georeference_check.hpp"

namespace tellus::cli {
namespace {

// Decodes one tile and checks it against its index record. Empty string when good.
std::string checkTile(const TileStore& store, const TileRecord& record) {
  std::vector<std::int32_t> samples(store.layout().tileShape().sampleCount());
  if (Status s = store.readTile(record.key, samples); !s) return s.error().message;
  const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
  const double q = store.metadata().quantumM;
  if (float(*lo * q) != record.stats.minHeightM || float(*hi * q) != record.stats.maxHeightM) {
    return fmt::format("'{}': {} decodes to heights {}..{} m but its index says {}..{} m",
                       store.path().string(), TileStore::describe(record.key), *lo * q, *hi * q,
                       record.stats.minHeightM, record.stats.maxHeightM);
  }
  return {};
}

}  // namespace

int checkEveryTile(const std::string& path, std::span<const TileRecord> records,
                   const std::function<std::string(const TileRecord&)>& check,
                   std::string_view checked) {
  std::vector<std::string> problems(records.size());
  Progress progress("verify", records.size());
  tbb::parallel_for(std::size_t(0), records.size(), [&](std::size_t i) {
    problems[i] = check(records[i]);
    progress.advance();
  });
  std::size_t bad = 0;
  for (const std::string& problem : problems) {
    if (problem.empty()) continue;
    fmt::print(stderr, "tellus: {}\n", problem);
    ++bad;
  }
  if (bad > 0) {
    fmt::print(stderr, "tellus: {}: {} of {} tiles are bad\n", path, bad, records.size());
    return 1;
  }
  fmt::print("{}: all {} tiles good{}\n", path, records.size(), checked);
  return 0;
}

Command addVerifyCommand(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* sub =
      app.add_subcommand("verify", "Check every tile of a store; exit 0 only if all are good");
  sub->add_option("store", *path, "The tile store (.tstore) or stack file (.tstack)")->required();
  return {sub,
          [path]() -> int {
            if (isStackFile(*path)) return verifyStackFile(*path);
            if (isGlobalStore(*path)) return verifyGlobalStore(*path);
            Result<std::shared_ptr<TileStore>> opened = TileStore::open(*path);
            if (!opened) return fail(opened.error());
            const TileStore& store = *opened.value();
            // The reader has checked every number; the CRS needs GDAL.
            const PyramidLayout& layout = store.layout();
            if (Status georef = checkGeoReference(store.metadata().georef, layout.dataWidth(),
                                                  layout.dataHeight());
                !georef) {
              return fail(makeError("'{}': the metadata's georeferencing is unusable: {}", *path,
                                    georef.error().message));
            }
            return checkEveryTile(*path, store.records(),
                                  [&](const TileRecord& r) { return checkTile(store, r); }, "");
          },
          [path] { return CommandFiles{{*path}, {}, {}}; }};
}

}  // namespace tellus::cli
