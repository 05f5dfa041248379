// tellus verify: checks every tile of a store (checksum, decoding, min/max against the index).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <mutex>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "global_store_cli.hpp"
#include "stack_cli.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/dem/georeference_check.hpp"
#include "tellus/tiles/store_consistency.hpp"

namespace tellus::cli {
namespace {

// Decodes one tile and checks it against its index record; keeps its edges for the checks
// between tiles. Empty string when good.
std::string checkTile(const TileStore& store, const TileRecord& record, StoreConsistency& consistency) {
  std::vector<std::int32_t> samples(store.layout().tileShape().sampleCount());
  if (Status s = store.readTile(record.key, samples); !s) return s.error().message;
  consistency.addTile(record, samples);
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
                   std::string_view checked, const ByteSource& source,
                   const std::function<std::vector<std::string>()>& acrossTiles) {
  std::vector<std::string> problems(records.size());
  Progress progress("verify", records.size());
  std::atomic<std::size_t> checkedTiles{0};
  std::atomic<bool> dead{false};
  std::mutex deadMutex;
  std::string deadProblem;
  tbb::parallel_for(std::size_t(0), records.size(), [&](std::size_t i) {
    if (dead) return;
    problems[i] = check(records[i]);
    if (!problems[i].empty() && source.failing()) {
      std::lock_guard lock(deadMutex);
      if (!dead.exchange(true)) deadProblem = problems[i];
      return;
    }
    ++checkedTiles;
    progress.advance();
  });
  if (dead) {
    fmt::print(stderr, "tellus: {}\n", deadProblem);
    fmt::print(stderr, "tellus: {}: verify stopped after {} of {} tiles: the source stopped "
               "answering\n", path, checkedTiles.load(), records.size());
    return 1;
  }
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
  if (acrossTiles) {
    const std::vector<std::string> disagreements = acrossTiles();
    for (const std::string& problem : disagreements) fmt::print(stderr, "tellus: {}\n", problem);
    if (!disagreements.empty()) {
      fmt::print(stderr, "tellus: {}: tiles disagree with their neighbours or parents (first {} "
                 "shown): the store was rearranged or rewritten\n",
                 path, disagreements.size());
      return 1;
    }
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
            // The input read once (classified()); the store opens from what was read.
            DemInputOptions input;
            input.inputs = {*path};
            const TerrainInputKind kind = input.classified().kind;
            if (kind == TerrainInputKind::Stacks) return verifyStackFile(*path);
            if (kind == TerrainInputKind::GlobalStore) return verifyGlobalStore(input);
            // The reader has checked every number; openTileStore the CRS (GDAL).
            Result<std::shared_ptr<TileStore>> opened = openTileStore(input);
            if (!opened) return fail(opened.error());
            const TileStore& store = *opened.value();
            StoreConsistency consistency(store);
            const std::string checked =
                consistency.toleranceSteps()
                    ? std::string(" (checksums, index, shared edges, nesting)")
                    : std::string(" (checksums, index; the codec bounds no error, so edges and "
                                  "nesting are not compared)");
            return checkEveryTile(
                *path, store.records(),
                [&](const TileRecord& r) { return checkTile(store, r, consistency); }, checked,
                store.source(), [&] { return consistency.check(20); });
          },
          [path] { return CommandFiles{{*path}, {}, {}}; }};
}

}  // namespace tellus::cli
