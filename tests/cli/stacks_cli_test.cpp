// Material stacks (seed 003) end to end: a generated DEM becomes a .tstack with caves, overhangs
// and arches, tellus info describes it, tellus verify passes it and fails a damaged copy, and
// wrong uses say what is wrong.
#include <fstream>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"
#include "tellus/core/rgb_image.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

TEST(StacksCli, BuildInfoVerifyAndRefusals) {
  const fs::path dir = test::freshTestDir();
  const fs::path dem = dir / "hills.tif", stacks = dir / "hills.tstack";
  ASSERT_EQ(runTellus(fmt::format("generate --size 129 --spacing 3 --relief 120 -o {}", quoted(dem))).exitCode, 0);
  const RunResult built = runTellus(fmt::format("stacks build {} -o {} --seed 3", quoted(dem), quoted(stacks)));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  EXPECT_NE(built.output.find("129 x 129 stacks at 3 m, 9 levels"), std::string::npos) << built.output;
  const RunResult info = runTellus(fmt::format("info {}", quoted(stacks)));
  ASSERT_EQ(info.exitCode, 0) << info.output;
  EXPECT_NE(info.output.find("material stacks, 129 x 129 stacks"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("level 8: 1 x 1 stacks"), std::string::npos) << info.output;
  const RunResult verified = runTellus(fmt::format("verify {}", quoted(stacks)));
  ASSERT_EQ(verified.exitCode, 0) << verified.output;
  EXPECT_NE(verified.output.find("all 9 levels good"), std::string::npos);
  // The same seed, the same file; without features, three layers at most a stack.
  const fs::path again = dir / "again.tstack", plain = dir / "plain.tstack";
  ASSERT_EQ(runTellus(fmt::format("stacks build {} -o {} --seed 3", quoted(dem), quoted(again))).exitCode, 0);
  std::ifstream a(stacks, std::ios::binary), b(again, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}));
  ASSERT_EQ(runTellus(fmt::format("stacks build {} -o {} --features none", quoted(dem), quoted(plain))).exitCode, 0);
  const RunResult plainInfo = runTellus(fmt::format("info {}", quoted(plain)));
  EXPECT_NE(plainInfo.output.find("up to"), std::string::npos);

  // A damaged copy fails verify with the level named.
  std::string bytes;
  {
    std::ifstream in(stacks, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 0x40);
  std::ofstream(dir / "bad.tstack", std::ios::binary) << bytes;
  const RunResult bad = runTellus(fmt::format("verify {}", quoted(dir / "bad.tstack")));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.output.find("corrupt"), std::string::npos) << bad.output;

  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("stacks build {} -o {}", quoted(dem), quoted(dir / "x.tif")), "must end in .tstack"},
      {fmt::format("stacks build {} -o {}", quoted(dir / "missing.tif"), quoted(dir / "x.tstack")), "missing.tif"},
      {fmt::format("stacks build {} -o {} --features tunnels", quoted(dem), quoted(dir / "x.tstack")), "tunnels"},
      {fmt::format("verify {}", quoted(dem)), "hills.tif"},
      {"stacks", "subcommand"},
  };
  for (const auto& [arguments, expected] : cases) {
    const RunResult r = runTellus(arguments);
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "x.tstack"));
}

// tellus stacks edit: a sphere carved and one filled, the file still verifies and differs, the
// input kept when -o is given; bad spheres, materials and missing modes refused, nothing written.
TEST(StacksCli, EditCarvesAndFillsAtomically) {
  const fs::path dir = test::freshTestDir();
  const fs::path dem = dir / "hills.tif", stacks = dir / "hills.tstack", copy = dir / "copy.tstack";
  ASSERT_EQ(runTellus(fmt::format("generate --size 65 --spacing 2 --relief 60 -o {}", quoted(dem))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("-q stacks build {} -o {} --features none", quoted(dem), quoted(stacks))).exitCode, 0);
  const auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string before = bytes(stacks);
  // The surface lies 8 m above the base at its lowest: carve a ball at 10 m.
  const RunResult carved = runTellus(fmt::format("stacks edit {} --sphere 64,64,10,6 --remove -o {}",
                                                 quoted(stacks), quoted(copy)));
  ASSERT_EQ(carved.exitCode, 0) << carved.output;
  EXPECT_NE(carved.output.find("carved"), std::string::npos) << carved.output;
  EXPECT_EQ(bytes(stacks), before);  // -o: the input untouched
  EXPECT_NE(bytes(copy), before);
  EXPECT_EQ(runTellus(fmt::format("verify {}", quoted(copy))).exitCode, 0);
  // In place, a boulder of rock.
  const RunResult filled = runTellus(fmt::format("stacks edit {} --sphere 30,40,60,5 --add rock", quoted(copy)));
  ASSERT_EQ(filled.exitCode, 0) << filled.output;
  EXPECT_EQ(runTellus(fmt::format("verify {}", quoted(copy))).exitCode, 0);
  const std::string edited = bytes(copy);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("stacks edit {} --sphere 1,2,3 --remove", quoted(copy)), "expected 4"},
      {fmt::format("stacks edit {} --sphere 1,2,nan,4 --remove", quoted(copy)), "not a number"},
      {fmt::format("stacks edit {} --sphere 30,40,60,0 --remove", quoted(copy)), "radius must be positive"},
      {fmt::format("stacks edit {} --sphere 9999,40,60,5 --remove", quoted(copy)), "misses the terrain"},
      {fmt::format("stacks edit {} --sphere 30,40,60,5 --add lava", quoted(copy)), "unknown material"},
      {fmt::format("stacks edit {} --sphere 30,40,60,5", quoted(copy)), "--add MATERIAL or --remove"},
      {fmt::format("stacks edit {} --sphere 30,40,60,5 --remove -o {}", quoted(copy), quoted(dir / "x.png")), "must end in .tstack"},
      {fmt::format("stacks edit {} --sphere 30,40,60,5 --remove", quoted(dem)), "hills.tif"},
  };
  for (const auto& [arguments, expected] : cases) {
    const RunResult r = runTellus(arguments);
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
  }
  EXPECT_EQ(bytes(copy), edited);  // refused edits write nothing
}

// The quadrangulation pipeline and the stacks-full renderer end to end on a small steep
// terrain: tellus stacks quad (CPU and GPU agree, the whole mesh is closed), render and bench
// (the ground truth judged against itself: no crack, no error), and the refusals.
TEST(StacksCli, QuadRenderAndBench) {
  const fs::path dir = test::freshTestDir();
  const fs::path dem = dir / "steep.tif", stacks = dir / "steep.tstack";
  ASSERT_EQ(runTellus(fmt::format("generate --size 97 --spacing 2 --relief 3000 --seed 5 -o {}", quoted(dem))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("-q stacks build {} -o {}", quoted(dem), quoted(stacks))).exitCode, 0);

  const RunResult quad = runTellus(fmt::format("stacks quad {} --node-cells 9 --json {}", quoted(stacks),
                                               quoted(dir / "quad.json")));
  ASSERT_EQ(quad.exitCode, 0) << quad.output;
  EXPECT_NE(quad.output.find("equal to the CPU reference's counts"), std::string::npos) << quad.output;
  std::ifstream in(dir / "quad.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["node_cells"], 9);
  EXPECT_GT(report["cpu"]["quads"].get<int>(), 1000);
  EXPECT_EQ(report["cpu"]["unbalanced_edges"], 0);  // every node: a closed surface
  EXPECT_EQ(report["gpu"]["equal_to_cpu"], true);
  EXPECT_GT(report["gpu"]["ms_per_node"]["total"].get<double>(), 0.0);
  EXPECT_GT(report["cpu"]["surface_materials"][2].get<double>(), 0.05);  // grass shows

  const fs::path png = dir / "steep.png";
  const RunResult rendered =
      runTellus(fmt::format("-q render {} --view oblique --size 320x200 -o {}", quoted(stacks), quoted(png)));
  ASSERT_EQ(rendered.exitCode, 0) << rendered.output;
  Result<RgbImage> image = readPng(png);
  ASSERT_TRUE(image);
  EXPECT_GT(test::luminanceStdDev(image.value()), 5.0);
  // The wireframe overlay and the LOD shading change the picture.
  for (const char* look : {"--wireframe", "--shading lod"}) {
    const fs::path other = dir / "other.png";
    ASSERT_EQ(runTellus(fmt::format("-q render {} --view oblique --size 320x200 {} -o {}", quoted(stacks),
                                    look, quoted(other))).exitCode, 0) << look;
    Result<RgbImage> changed = readPng(other);
    ASSERT_TRUE(changed);
    EXPECT_GT(test::meanDifference(image.value(), changed.value()), 2.0) << look;
  }

  const RunResult bench = runTellus(fmt::format("-q bench {} --algo stacks-full,stacks --path orbit --frames 3 "
                                                "--warmup 0 --size 320x200 --quality --stack-node-cells 9 --json {}",
                                                quoted(stacks), quoted(dir / "bench.json")));
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  std::ifstream benchIn(dir / "bench.json");
  const nlohmann::json benchReport = nlohmann::json::parse(benchIn);
  const nlohmann::json& summary = benchReport["algorithms"][0]["summary"];
  EXPECT_EQ(benchReport["algorithms"][0]["algo"], "stacks-full");
  EXPECT_EQ(summary["crack_pixels_total"], 0);
  // The octree renderer: no crack either, judged against stacks-full.
  EXPECT_EQ(benchReport["algorithms"][1]["algo"], "stacks");
  EXPECT_EQ(benchReport["algorithms"][1]["summary"]["crack_pixels_total"], 0);

  // Brush strokes while flying: the octree renderer remakes what they touch, crack-free against
  // a ground truth made again after each stroke.
  const RunResult edits = runTellus(fmt::format("bench {} --algo stacks --frames 12 --warmup 0 --size 320x200 "
                                                "--quality --stack-edits 6 --json {}",
                                                quoted(stacks), quoted(dir / "edits.json")));
  ASSERT_EQ(edits.exitCode, 0) << edits.output;
  EXPECT_NE(edits.output.find("brush strokes; stroke to updated mesh"), std::string::npos) << edits.output;
  EXPECT_NE(edits.output.find("0 crack pixels in the frames with a stroke"), std::string::npos) << edits.output;
  std::ifstream editsIn(dir / "edits.json");
  EXPECT_EQ(nlohmann::json::parse(editsIn)["algorithms"][0]["summary"]["crack_pixels_total"], 0);

  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("bench {} --stack-edits 3", quoted(dem)), "give a .tstack"},
      {fmt::format("bench {} --algo stacks --stack-edits -1", quoted(stacks)), "stack-edits"},
      {fmt::format("bench {} --algo stacks --stack-morph-frames -2", quoted(stacks)), "stack-morph-frames"},
      {fmt::format("bench {} --algo stacks --stack-morph-frames many", quoted(stacks)), "stack-morph-frames"},
      {fmt::format("bench {} --algo stacks --stack-seam-band -1", quoted(stacks)), "stack-seam-band"},
      {fmt::format("render {} --algo reference -o {}", quoted(stacks), quoted(dir / "x.png")), "holds material stacks"},
      {fmt::format("render {} --algo stacks-full -o {}", quoted(dem), quoted(dir / "x.png")), "draws material stacks"},
      {fmt::format("stacks quad {} --no-cpu --no-gpu", quoted(stacks)), "nothing to run"},
      {fmt::format("stacks quad {} --level 40", quoted(stacks)), "level"},
      {fmt::format("stacks quad {} --filter median", quoted(stacks)), "median"},
      {fmt::format("stacks quad {} --node-cells 2", quoted(stacks)), "node-cells"},
      {fmt::format("stacks quad {}", quoted(dem)), "steep.tif"},
  };
  for (const auto& [arguments, expected] : cases) {
    const RunResult r = runTellus(arguments);
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
    // One line says what is wrong (the parser adds a pointer to --help after it).
    EXPECT_NE(r.output.substr(0, r.output.find('\n')).find(expected), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace tellus
