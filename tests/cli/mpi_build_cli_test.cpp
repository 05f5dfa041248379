// `mpirun -np N tellus build --global` (issue 47): the sharded build gives the very bytes of the
// one-process build for any number of ranks, says how many ranks built it, and a rank killed
// mid-build fails the whole job and leaves the previous store as it was. Open MPI's mpirun (from
// Debian's openmpi-bin, which make test installs) runs the ranks on this machine.
#include <fstream>

#include <gtest/gtest.h>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

bool haveMpirun() { return std::system("command -v mpirun >/dev/null 2>&1") == 0; }

std::string mpirun(int ranks) {
  // --oversubscribe: more ranks than cores; root may run it (the CI machine's user). A job that
  // hangs (ranks waiting on each other) fails the test within minutes instead of stalling CI.
  return fmt::format("timeout --kill-after=10 300 mpirun --allow-run-as-root --oversubscribe -np {} '{}'",
                     ranks, TELLUS_EXECUTABLE);
}

std::string fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// ETOPO5 with SRTM over Korea and SRTM's BIL over Guadeloupe (the antipode's other side).
std::string sourcesIn(const fs::path& data, int srtmTiles) {
  std::string args = quoted(data / "etopo5-global/etopo5_int16.tif");
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on " " + a temporary.
  for (int i = 0; i < srtmTiles; ++i) {
    args += ' ';
    args += quoted(test::koreaMosaicTiles(data)[std::size_t(i)]);
  }
  args += ' ';
  args += quoted(data / "srtm3-bil-guadeloupe/n16_w062_3arc_v2.bil");
  return args;
}

TEST(MpiBuildCli, AnyNumberOfRanksWritesTheSameBytes) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  if (!haveMpirun()) GTEST_SKIP() << "mpirun is absent (apt install openmpi-bin)";
  const fs::path dir = test::freshTestDir();
  const std::string sources = sourcesIn(data, 2);
  const RunResult alone = runTellus(fmt::format("build --global {} -o {}", sources, quoted(dir / "alone.tstore")));
  ASSERT_EQ(alone.exitCode, 0) << alone.output;
  EXPECT_NE(alone.output.find("on 1 rank"), std::string::npos) << alone.output;
  const std::string reference = fileBytes(dir / "alone.tstore");
  ASSERT_GT(reference.size(), 1000000u);
  for (const int ranks : {1, 2, 4, 7}) {
    const fs::path out = dir / fmt::format("ranks-{}.tstore", ranks);
    const RunResult r = runShell(fmt::format("{} build --global {} -o {}", mpirun(ranks), sources, quoted(out)));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(fmt::format("on {} rank", ranks)), std::string::npos) << r.output;
    // Rank 0 alone speaks: one summary line.
    EXPECT_EQ(r.output.find("global store,"), r.output.rfind("global store,")) << r.output;
    EXPECT_TRUE(fileBytes(out) == reference) << ranks << " ranks wrote other bytes";
  }
  const RunResult verified = runTellus(fmt::format("verify {}", quoted(dir / "ranks-7.tstore")));
  EXPECT_EQ(verified.exitCode, 0) << verified.output;
  // Nothing is left beside the stores: no spool, no partial file.
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().extension(), ".tstore") << entry.path();
  }
}

TEST(MpiBuildCli, AKilledRankFailsTheJobAndKeepsThePreviousStore) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  if (!haveMpirun()) GTEST_SKIP() << "mpirun is absent (apt install openmpi-bin)";
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "earth.tstore";
  {
    std::ofstream previous(store, std::ios::binary);
    previous << "the previous store";
  }
  // Rank 1 is killed as soon as rank 0 has opened the store's partial file (seconds before the
  // end).
  const std::string script = fmt::format(
      "cd {dir} && {mpirun} build --global {sources} -o {out} > run.log 2>&1 & job=$!; "
      "for i in $(seq 400); do ls {dir}/.earth.tstore.tellus-partial-* >/dev/null 2>&1 && break; sleep 0.05; done; "
      "kill -KILL $(pgrep -P $job | sort -n | sed -n 2p); wait $job; rc=$?; cat {dir}/run.log; exit $rc",
      fmt::arg("dir", quoted(dir)),
      // mpirun itself, not under timeout: the ranks are its children (the job ends either way).
      fmt::arg("mpirun", fmt::format("mpirun --allow-run-as-root --oversubscribe -np 2 '{}'", TELLUS_EXECUTABLE)),
      fmt::arg("sources", sourcesIn(data, 8)),
      fmt::arg("out", quoted(store)));
  const RunResult r = runShell(script);
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("signal 9"), std::string::npos) << r.output;
  EXPECT_EQ(fileBytes(store), "the previous store");
  // The next build of the store removes what the killed one left beside it (the partial file;
  // the ranks' spools in $TMPDIR go with the next scratch folder made there).
  fs::remove(dir / "run.log");
  const RunResult again = runTellus(fmt::format("build --global {} -o {}", sourcesIn(data, 1), quoted(store)));
  ASSERT_EQ(again.exitCode, 0) << again.output;
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tellus-"), std::string::npos) << entry.path();
  }
}

// `build --global --update`: one more SRTM tile added to a store on 2 ranks, the count of tiles
// rewritten printed, and the same bytes as a build of all the sources.
TEST(MpiBuildCli, AnUpdateRewritesOnlyWhatTheNewTileReaches) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  if (!haveMpirun()) GTEST_SKIP() << "mpirun is absent (apt install openmpi-bin)";
  const fs::path dir = test::freshTestDir();
  const std::vector<fs::path> korea = test::koreaMosaicTiles(data);
  const fs::path etopo = data / "etopo5-global/etopo5_int16.tif";
  const RunResult first = runTellus(fmt::format("build --global {} {} -o {}", quoted(etopo),
                                                quoted(korea[0]), quoted(dir / "before.tstore")));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  const RunResult update = runShell(fmt::format("{} build --global --update {} {} -o {}", mpirun(2),
                                                quoted(dir / "before.tstore"), quoted(korea[1]),
                                                quoted(dir / "after.tstore")));
  ASSERT_EQ(update.exitCode, 0) << update.output;
  const std::size_t at = update.output.find("tiles rewritten of ");
  ASSERT_NE(at, std::string::npos) << update.output;
  const std::size_t rewritten = std::stoul(update.output.substr(update.output.rfind(": ", at) + 2));
  const std::size_t tiles = std::stoul(update.output.substr(at + std::string("tiles rewritten of ").size()));
  EXPECT_GT(rewritten, 0u);
  EXPECT_LT(rewritten, tiles / 2) << update.output;
  // The store lists its sources finest first: the SRTM tile, then ETOPO5; then the new one.
  const RunResult full = runTellus(fmt::format("build --global {} {} {} -o {}", quoted(korea[0]), quoted(etopo),
                                               quoted(korea[1]), quoted(dir / "full.tstore")));
  ASSERT_EQ(full.exitCode, 0) << full.output;
  EXPECT_TRUE(fileBytes(dir / "after.tstore") == fileBytes(dir / "full.tstore"));
  // Over the store it reads, or with options of its own: refused, nothing written.
  const RunResult over = runTellus(fmt::format("build --global --update {} {} -o {}", quoted(dir / "before.tstore"),
                                               quoted(korea[2]), quoted(dir / "before.tstore")));
  EXPECT_NE(over.exitCode, 0);
  const RunResult options = runTellus(fmt::format("build --global --update {} --tile 128 {} -o {}",
                                                  quoted(dir / "before.tstore"), quoted(korea[2]), quoted(dir / "x.tstore")));
  EXPECT_NE(options.exitCode, 0);
  EXPECT_NE(options.output.find("leave out --tile"), std::string::npos) << options.output;
  EXPECT_FALSE(fs::exists(dir / "x.tstore"));
}

}  // namespace
}  // namespace tellus
