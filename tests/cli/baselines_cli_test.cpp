// `tellus bench --algo all` with the survey baselines (seed 004): every renderer that can run on
// a store, once each, judged on one path, and the comparison chart and table written; ROAM, the
// clipmaps, GAMeR, BDAM and geometry image warping render stills; their options refuse nonsense;
// BDAM's patch file is made by `tellus build --bdam`, and a missing or corrupt one is refused.
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
  const RunResult built = runTellus(fmt::format("build {} -o {} --tile 64 --bdam --bdam-leaf 11",
                                               quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(store)));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  EXPECT_TRUE(fs::exists(dir / "n37e127.bdam"));
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
  EXPECT_EQ(algos, (std::vector<std::string>{"reference", "rings", "rag", "roam", "clipmaps", "gamer", "bdam", "giw"}));
  for (const nlohmann::json& a : report["algorithms"]) {
    // Geometry image warping has no error bound: its warped grid may leave a pixel's worth of
    // terrain edge uncovered; every other renderer is crack-free.
    if (a["algo"] != "giw") {
      EXPECT_EQ(a["summary"]["crack_pixels_total"], 0) << a["algo"];
    }
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

TEST(BaselinesCli, BenchAllLeavesOutBdamWithoutItsPatchFile) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string hgt = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const RunResult result = runTellus(fmt::format("bench {} --algo all --path flyover --frames 2 --warmup 0 --size 160x90 --json {}",
                                                 hgt, quoted(dir / "r.json")));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::ifstream in(dir / "r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  for (const nlohmann::json& a : report["algorithms"]) EXPECT_NE(a["algo"], "bdam");
  // Asked for by name, it says what is missing and how to make it.
  const RunResult bdam = runTellus(fmt::format("render {} --algo bdam -o {}", hgt, quoted(dir / "x.png")));
  EXPECT_NE(bdam.exitCode, 0);
  EXPECT_NE(bdam.output.find("tellus build"), std::string::npos) << bdam.output;
  // A corrupt patch file is refused with its name, never drawn.
  { std::ofstream(dir / "bad.bdam") << "TBDAMv1 and then nonsense"; }
  const RunResult corrupt = runTellus(fmt::format("render {} --algo bdam --bdam-patches {} -o {}", hgt,
                                                  quoted(dir / "bad.bdam"), quoted(dir / "x.png")));
  EXPECT_NE(corrupt.exitCode, 0);
  EXPECT_NE(corrupt.output.find("bad.bdam"), std::string::npos) << corrupt.output;
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST(BaselinesCli, RoamAndClipmapsRenderStillsAndRefuseNonsense) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string hgt = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const fs::path store = dir / "n37e127.tstore";
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --tile 64 --bdam --bdam-leaf 11", hgt, quoted(store))).exitCode, 0);
  for (const char* algo : {"roam", "clipmaps", "gamer", "bdam", "giw"}) {
    const RunResult still = runTellus(fmt::format("render {} --algo {} --shading lod --wireframe --size 320x180 -o {}",
                                                  quoted(store), algo, quoted(dir / (std::string(algo) + ".png"))));
    ASSERT_EQ(still.exitCode, 0) << still.output;
    EXPECT_TRUE(fs::exists(dir / (std::string(algo) + ".png")));
  }
  // Clipmaps read a tile store; a DEM alone is refused, as are sizes that are not 4m - 1.
  RunResult bad = runTellus(fmt::format("render {} --algo clipmaps -o {}", hgt, quoted(dir / "x.png")));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.output.find("tile store"), std::string::npos) << bad.output;
  bad = runTellus(fmt::format("render {} --algo clipmaps --clipmap-size 100 -o {}", quoted(store), quoted(dir / "x.png")));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.output.find("4m - 1"), std::string::npos) << bad.output;
  bad = runTellus(fmt::format("render {} --algo roam --roam-target -3 -o {}", hgt, quoted(dir / "x.png")));
  EXPECT_NE(bad.exitCode, 0);
  bad = runTellus(fmt::format("render {} --algo roam --roam-target nan -o {}", hgt, quoted(dir / "x.png")));
  EXPECT_NE(bad.exitCode, 0);
  for (const char* option : {"--gamer-depth 9", "--gamer-target 0", "--gamer-morph 1.5", "--bdam-target -1", "--bdam-cache 3",
                             "--giw-size 4", "--giw-uniform 2"}) {
    bad = runTellus(fmt::format("render {} --algo gamer {} -o {}", quoted(store), option, quoted(dir / "x.png")));
    EXPECT_NE(bad.exitCode, 0) << option;
  }
  bad = runTellus(fmt::format("build {} -o {} --bdam --bdam-leaf 40", hgt, quoted(dir / "y.tstore")));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

}  // namespace
}  // namespace tellus
