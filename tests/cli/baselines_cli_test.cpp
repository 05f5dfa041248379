// `tellus bench --algo all` with the survey baselines (seed 004): every renderer that can run on
// a store, once each, judged on one path, and the comparison chart and table written; ROAM and
// the clipmaps render stills; their options refuse nonsense.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

TEST(BaselinesCli, BenchAllOnAStoreWritesTheComparison) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "n37e127.tstore";
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --tile 64",
                                  quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(store)))
                .exitCode,
            0);
  const RunResult result = runTellus(fmt::format(
      "bench {} --algo all --path flyover --frames 4 --warmup 1 --size 320x180 --quality --json {} --plots {}",
      quoted(store), quoted(dir / "r.json"), quoted(dir / "plots")));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::ifstream in(dir / "r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  std::vector<std::string> algos;
  for (const nlohmann::json& a : report["algorithms"]) algos.push_back(a["algo"]);
  // One row per algorithm: no seed-table variants (rings-brute..., rag-right), nothing for the
  // globe or material stacks.
  EXPECT_EQ(algos, (std::vector<std::string>{"reference", "rings", "rag", "roam", "clipmaps"}));
  for (const nlohmann::json& a : report["algorithms"]) {
    EXPECT_EQ(a["summary"]["crack_pixels_total"], 0) << a["algo"];
  }
  const nlohmann::json& roam = report["algorithms"][3]["summary"];
  EXPECT_TRUE(roam.contains("lod_priority_ms_median"));
  EXPECT_TRUE(roam.contains("lod_refine_ms_median"));
  EXPECT_TRUE(report["algorithms"][4]["summary"].contains("texture_update_ms_median"));
  EXPECT_TRUE(fs::exists(dir / "plots" / "comparison.png"));
  std::ifstream table(dir / "plots" / "comparison.md");
  const std::string text((std::istreambuf_iterator<char>(table)), std::istreambuf_iterator<char>());
  for (const std::string& algo : algos) EXPECT_NE(text.find("| " + algo + " |"), std::string::npos) << algo;
}

TEST(BaselinesCli, RoamAndClipmapsRenderStillsAndRefuseNonsense) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string hgt = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const fs::path store = dir / "n37e127.tstore";
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --tile 64", hgt, quoted(store))).exitCode, 0);
  for (const char* algo : {"roam", "clipmaps"}) {
    const RunResult still = runTellus(fmt::format("render {} --algo {} --shading lod --wireframe --size 320x180 -o {}",
                                                  quoted(store), algo, quoted(dir / (std::string(algo) + ".png"))));
    ASSERT_EQ(still.exitCode, 0) << still.output;
    EXPECT_TRUE(fs::exists(dir / (std::string(algo) + ".png")));
  }
  // Clipmaps read a tile store; a DEM alone is refused, as are sizes that are not 2^k - 1.
  RunResult bad = runTellus(fmt::format("render {} --algo clipmaps -o {}", hgt, quoted(dir / "x.png")));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.output.find("tile store"), std::string::npos) << bad.output;
  bad = runTellus(fmt::format("render {} --algo clipmaps --clipmap-size 100 -o {}", quoted(store), quoted(dir / "x.png")));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.output.find("2^k - 1"), std::string::npos) << bad.output;
  bad = runTellus(fmt::format("render {} --algo roam --roam-target -3 -o {}", hgt, quoted(dir / "x.png")));
  EXPECT_NE(bad.exitCode, 0);
  bad = runTellus(fmt::format("render {} --algo roam --roam-target nan -o {}", hgt, quoted(dir / "x.png")));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

}  // namespace
}  // namespace tellus
