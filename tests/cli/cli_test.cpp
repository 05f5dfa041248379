// End-to-end tests of the tellus binary: real DEMs in, PNGs and GeoTIFFs out, and bad input
// rejected with one clear line, a non-zero exit and no output file.
#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>

#include <fmt/format.h>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/render/shading/terrain_shading.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

// Checks a rendered terrain image: its size, that it is not blank, and that the terrain (pixels
// unlike the sky) sits in the middle of the frame with sky above it.
void expectTerrainImage(const fs::path& file, int width, int height) {
  Result<RgbImage> image = readPng(file);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->width, width);
  EXPECT_EQ(image->height, height);
  EXPECT_GT(test::luminanceStdDev(*image), 8.0) << "the image is (nearly) blank";
  const glm::u8vec3 sky = skyColour8(ShadingParams{});
  const unsigned char background[3] = {sky.r, sky.g, sky.b};
  const test::ForegroundStats terrain = test::foregroundStats(*image, background);
  EXPECT_GT(terrain.fraction, 0.2);
  EXPECT_LT(terrain.fraction, 0.95);
  EXPECT_GT(terrain.centroidX, 0.3 * width);
  EXPECT_LT(terrain.centroidX, 0.7 * width);
  EXPECT_GT(terrain.minY, 0) << "sky expected along the top of the frame";
  EXPECT_GT(terrain.centroidY, 0.4 * height) << "terrain expected in the lower part";
}

TEST(Cli, EverySubcommandHasHelp) {
  for (const char* sub : {"", "info", "render", "generate", "demo", "build", "verify", "export",
                          "bench", "bench codecs", "renderers"}) {
    const RunResult result = runTellus(fmt::format("{} --help", sub));
    EXPECT_EQ(result.exitCode, 0) << sub;
    EXPECT_NE(result.output.find("--help"), std::string::npos) << sub;
  }
  EXPECT_NE(runTellus("render --help").output.find("--camera"), std::string::npos);
  EXPECT_NE(runTellus("").exitCode, 0);  // a subcommand is required
  const RunResult misspelt = runTellus("rendr x.hgt");
  EXPECT_NE(misspelt.exitCode, 0);
  EXPECT_NE(misspelt.output.find("unknown command 'rendr'"), std::string::npos) << misspelt.output;
  EXPECT_NE(runTellus("--version").output.find("tellus 0."), std::string::npos);
}

// Help a person can read: `tellus renderers` lists the renderers one per line (name, world,
// input, seed, description); `--algo`'s help names them without the descriptions; every usage
// error exits 2; a folder given as an input names the files to give instead.
TEST(Cli, RenderersAreListedOnePerLineAndUsageErrorsExitTwo) {
  const RunResult listed = runTellus("renderers");
  ASSERT_EQ(listed.exitCode, 0) << listed.output;
  for (const char* name : {"reference", "rings", "rag", "roam", "clipmaps", "gamer", "bdam", "giw", "spiral"}) {
    EXPECT_NE(listed.output.find(fmt::format("\n{} ", name)), std::string::npos) << name << "\n" << listed.output;
  }
  EXPECT_NE(listed.output.find("a global store"), std::string::npos);
  const RunResult help = runTellus("render --help");
  std::istringstream lines(help.output);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_LE(line.size(), 400u) << line;  // was one line of 2,788 characters
  }
  EXPECT_NE(help.output.find("tellus renderers"), std::string::npos);
  EXPECT_EQ(runTellus("render").exitCode, 2);                      // a missing argument (CLI11: 106)
  EXPECT_EQ(runTellus("render x.hgt --no-such-option").exitCode, 2);  // an unknown option
  EXPECT_EQ(runTellus("generate --size 1 -o x.tif").exitCode, 2);     // out of range
  TELLUS_REQUIRE_SHARED_DATA(data);
  const RunResult folder = runTellus(fmt::format("info {}", quoted(data / "srtm3-hgt-east-asia")));
  EXPECT_NE(folder.exitCode, 0);
  EXPECT_NE(folder.output.find("it is a folder; give the files in it: '"), std::string::npos) << folder.output;
  EXPECT_NE(folder.output.find("*.hgt' (20 files)"), std::string::npos) << folder.output;
}

// The renderers' options from one schema: render, bench and view print the same groups of
// --<family>-* options (the rings' included, once only in view), every flag `tellus renderers
// --options` lists is in each, and the bench's JSON records each run's values.
std::string rendererOptionGroups(const std::string& help) {
  const std::size_t first = help.find("\nRings options:");
  if (first == std::string::npos) return {};
  const std::size_t end = help.find("\nSubcommands:", first);
  std::string groups = help.substr(first, end == std::string::npos ? std::string::npos : end - first);
  while (!groups.empty() && groups.back() == '\n') groups.pop_back();
  return groups;
}

TEST(Cli, RenderBenchAndViewTakeTheSameRendererOptions) {
  const RunResult render = runTellus("render --help");
  const RunResult bench = runTellus("bench --help");
  const RunResult view = runTellus("view --help");
  const std::string groups = rendererOptionGroups(render.output);
  ASSERT_FALSE(groups.empty()) << render.output;
  EXPECT_EQ(rendererOptionGroups(bench.output), groups);
  EXPECT_EQ(rendererOptionGroups(view.output), groups);
  const RunResult listed = runTellus("renderers --options");
  ASSERT_EQ(listed.exitCode, 0) << listed.output;
  std::istringstream lines(listed.output);
  int flags = 0;
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with("  --")) continue;
    const std::string flag = line.substr(2, line.find(' ', 2) - 2);
    EXPECT_NE(groups.find("  " + flag), std::string::npos) << flag;
    ++flags;
  }
  EXPECT_GE(flags, 50);
  for (const char* rings : {"--rings-count", "--rings-gpu-slots", "--patch-cells"})
    EXPECT_NE(groups.find(rings), std::string::npos) << rings;
}

TEST(Cli, BenchRecordsEveryOptionOfEachRenderer) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const RunResult result = runTellus(fmt::format(
      "bench {} --algo rag,roam --rag-coarse 40 --roam-target 2.5 --frames 2 --warmup 0 "
      "--size 96x64 --json {}",
      quoted(data / "srtm3-hgt-east-asia" / "N37E127.hgt"), quoted(dir / "r.json")));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::ifstream in(dir / "r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& rag = report["algorithms"][0]["options"];
  EXPECT_EQ(rag["rag-coarse"], 40);
  EXPECT_EQ(rag["rag-passes"], 7);  // a default is recorded too
  EXPECT_EQ(rag["rag-no-clip"], false);
  EXPECT_DOUBLE_EQ(report["algorithms"][1]["options"]["roam-target"].get<double>(), 2.5);
  EXPECT_FALSE(report["algorithms"][1]["options"].contains("rag-coarse"));
  // ROAM's own stages, reported by name.
  EXPECT_TRUE(report["algorithms"][1]["summary"].contains("mesh_build_ms_median"));
  EXPECT_TRUE(report["algorithms"][1]["frames"][0].contains("lod_refine_ms"));
}

// The rings' options once lived only in `tellus view`: bench takes them now, and they reach
// the renderer (with one ring there is no coarser ring: every patch is drawn at the finest
// level, more triangles than the default's rings).
TEST(Cli, BenchPassesTheRingsOptionsToTheRenderer) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "n37.tstore";
  ASSERT_EQ(runTellus(fmt::format("build {} -o {}", quoted(data / "srtm3-hgt-east-asia" / "N37E127.hgt"),
                                  quoted(store)))
                .exitCode,
            0);
  std::map<int, double> triangles;
  for (int rings : {0, 1}) {
    const fs::path json = dir / fmt::format("r{}.json", rings);
    const RunResult result = runTellus(fmt::format(
        "bench {} --algo rings --rings-count {} --settle --path orbit --frames 2 --warmup 0 "
        "--size 96x64 --json {}",
        quoted(store), rings, quoted(json)));
    ASSERT_EQ(result.exitCode, 0) << result.output;
    std::ifstream in(json);
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["algorithms"][0]["options"]["rings-count"], rings);
    triangles[rings] = report["algorithms"][0]["summary"]["triangles_median"].get<double>();
  }
  EXPECT_GT(triangles[1], triangles[0]);
}

TEST(Cli, InfoDescribesAnSrtmTile) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const RunResult result =
      runTellus("info " + quoted(data / "srtm3-hgt-east-asia" / "N37E127.hgt"));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  for (const char* expected : {"1201 x 1201 samples", "WGS 84 (geographic)", "73.6", "92.4",
                               "min -15.00 m, max 1456.00 m", "5 (filled"}) {
    EXPECT_NE(result.output.find(expected), std::string::npos) << expected << "\n" << result.output;
  }
}

TEST(Cli, InfoGlNamesTheRenderer) {
  const RunResult result = runTellus("info --gl");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("renderer:"), std::string::npos);
  EXPECT_NE(result.output.find("4.5"), std::string::npos);
  EXPECT_NE(result.output.find("max texture size:"), std::string::npos);
}

TEST(Cli, WindowContextUnderXvfbRendersLikeHeadless) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed";
  const fs::path dir = test::freshTestDir();
  const auto runUnderXvfb = [](const std::string& arguments) {
    return runShell(fmt::format("xvfb-run -a '{}' {}", TELLUS_EXECUTABLE, arguments));
  };
  const RunResult info = runUnderXvfb("info --gl --context window");
  ASSERT_EQ(info.exitCode, 0) << info.output;
  EXPECT_NE(info.output.find("GLFW window"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("4.5"), std::string::npos) << info.output;

  // The same picture through a GLFW window's context as through headless EGL.
  ASSERT_EQ(runTellus(fmt::format("generate -o {} --size 65", quoted(dir / "t.tif"))).exitCode, 0);
  const std::string render = fmt::format("render {} --size 160x120 -o ", quoted(dir / "t.tif"));
  ASSERT_EQ(runTellus(render + quoted(dir / "egl.png")).exitCode, 0);
  const RunResult window = runUnderXvfb(render + quoted(dir / "glfw.png") + " --context window");
  ASSERT_EQ(window.exitCode, 0) << window.output;
  Result<RgbImage> egl = readPng(dir / "egl.png"), glfw = readPng(dir / "glfw.png");
  ASSERT_TRUE(egl && glfw);
  EXPECT_EQ(egl->pixels, glfw->pixels);
}

TEST(Cli, RendersAnSrtmTile) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path out = test::freshTestDir() / "n37e127.png";
  const RunResult result = runTellus(fmt::format(
      "render {} -o {}", quoted(data / "srtm3-hgt-east-asia" / "N37E127.hgt"), quoted(out)));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  expectTerrainImage(out, 1280, 720);
}

TEST(Cli, RendersTheKoreaMosaicObliquelyWithLandAndSea) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path out = test::freshTestDir() / "korea.png";
  const RunResult result = runTellus(fmt::format("render {} -o {} --size 1280x720 --view oblique",
                                                 koreaArguments(data), quoted(out)));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  Result<RgbImage> image = readPng(out);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 1280);
  EXPECT_EQ(image->height, 720);
  // The lower half shows sea (blue dominant) and land (green dominant), so a coastline.
  int sea = 0, land = 0, total = 0;
  for (int y = 360; y < 720; ++y) {
    for (int x = 0; x < 1280; ++x) {
      const std::uint8_t* p = image->at(x, y);
      sea += p[2] > p[1] + 10 && p[2] > p[0] + 10;
      land += p[1] > p[2] + 5 && p[1] >= p[0];
      ++total;
    }
  }
  EXPECT_GT(sea, total / 10) << "no sea in the Korea view";
  EXPECT_GT(land, total / 10) << "no land in the Korea view";
  fs::copy_file(out, test::testOutputDir() / "korea-oblique.png",
                fs::copy_options::overwrite_existing);
}

TEST(Cli, RendersFromAnExplicitCamera) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path out = test::freshTestDir() / "camera.png";
  // From 3 km above the middle of the tile, looking down north-east.
  const RunResult result = runTellus(
      fmt::format("render {} -o {} --size 320x240 --camera 44000,55000,3000,45,-35,50 --wireframe",
                  quoted(data / "srtm3-hgt-east-asia" / "N37E127.hgt"), quoted(out)));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  Result<RgbImage> image = readPng(out);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 320);
  EXPECT_GT(test::luminanceStdDev(*image), 8.0);
}

TEST(Cli, GeneratesADeterministicGeoTiff) {
  const fs::path dir = test::freshTestDir();
  for (const char* name : {"a.tif", "b.tif"}) {
    const RunResult result =
        runTellus(fmt::format("generate -o {} --size 129 --seed 4", quoted(dir / name)));
    ASSERT_EQ(result.exitCode, 0) << result.output;
  }
  const RunResult info = runTellus("info " + quoted(dir / "a.tif"));
  ASSERT_EQ(info.exitCode, 0) << info.output;
  EXPECT_NE(info.output.find("129 x 129 samples"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("UTM zone 33N"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("30.0"), std::string::npos) << info.output;  // 30 m / UTM scale factor
  Result<HeightGrid> a = loadDem({dir / "a.tif"});
  Result<HeightGrid> b = loadDem({dir / "b.tif"});
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->heights, b->heights);
}

// generate --planet: a whole-globe latitude/longitude grid that build --global takes as its
// global source; a size outside the planet's range is refused without output.
TEST(Cli, GeneratesAPlanetForGlobalStores) {
  const fs::path dir = test::freshTestDir();
  const RunResult made =
      runTellus(fmt::format("generate --planet --size 256 -o {}", quoted(dir / "planet.tif")));
  ASSERT_EQ(made.exitCode, 0) << made.output;
  Result<HeightGrid> planet = loadDem({dir / "planet.tif"});
  ASSERT_TRUE(planet);
  EXPECT_EQ(planet->width, 256);
  EXPECT_EQ(planet->height, 128);
  EXPECT_TRUE(planet->georef.isGeographic);
  const RunResult built = runTellus(fmt::format("build --global {} -o {}",
                                                quoted(dir / "planet.tif"),
                                                quoted(dir / "planet.tstore")));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  EXPECT_EQ(built.output.find("no source covers the whole globe"), std::string::npos)
      << built.output;
  const RunResult tooSmall =
      runTellus(fmt::format("generate --planet --size 8 -o {}", quoted(dir / "small.tif")));
  EXPECT_NE(tooSmall.exitCode, 0);
  EXPECT_NE(tooSmall.output.find("samples around the equator"), std::string::npos)
      << tooSmall.output;
  EXPECT_FALSE(fs::exists(dir / "small.tif"));
}

// The showcase end to end on a small terrain: the store, the same view from each renderer lit
// and with its error, the benchmark of them all (`--algo all`) with its charts and comparison, the terrain on a procedural
// planet (a global store, stills from orbit and near the ground, a descent benchmark), and the
// pages with the tables.
TEST(Cli, DemoComparesTheRenderersAndWritesThePages) {
  const fs::path dir = test::freshTestDir() / "demo";
  const RunResult result = runTellus(
      fmt::format("demo -o {} --terrain-size 257 --size 320x180 --bench-frames 4 --bench-size "
                  "192x108 --planet-size 512 --video-frames 5",
                  quoted(dir)));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  for (const char* file : {"index.html", "index.md", "terrain.tif", "bench/bench.json"})
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  // The flythroughs, each a playable H.264 video of its frames, shown first on the page.
  for (const char* file : {"flight-flat.mp4", "flight-descent.mp4"}) {
    auto info = test::probeVideo(dir / file);
    EXPECT_EQ(info["error"], "") << file;
    EXPECT_EQ(info["codec_name"], "h264") << file;
    EXPECT_EQ(info["nb_read_frames"], "5") << file;
  }
  {
    std::ifstream html(dir / "index.html");
    const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
    EXPECT_NE(page.find("<video src=\"flight-flat.mp4\""), std::string::npos);
    EXPECT_LT(page.find("<video src=\"flight-descent.mp4\""), page.find("Every renderer, one view"));
  }
  EXPECT_TRUE(fs::is_directory(dir / "terrain.tstore") || fs::is_regular_file(dir / "terrain.tstore"));
  for (const char* algo : {"reference", "rings", "rag", "roam", "clipmaps", "gamer", "bdam", "giw"}) {
    for (const char* suffix : {"", "-sse"}) {
      const std::string file = fmt::format("{}-oblique{}.png", algo, suffix);
      Result<RgbImage> image = readPng(dir / file);
      ASSERT_TRUE(image) << file;
      EXPECT_EQ(image->width, 320);
      EXPECT_GT(test::luminanceStdDev(*image), 3.0) << file;
    }
  }
  for (const char* file : {"overview.png", "low-altitude.png", "wireframe-peak.png",
                           "bench/frame_time.png", "bench/popping.png", "bench/error_histogram.png",
                           "bench/comparison.png"}) {
    EXPECT_TRUE(readPng(dir / file)) << file;
  }
  std::ifstream index(dir / "index.md");
  const std::string text((std::istreambuf_iterator<char>(index)), std::istreambuf_iterator<char>());
  for (const char* part : {"| reference |", "| rings |", "| rag |", "| roam |", "| clipmaps |", "| gamer |",
                           "| bdam |", "| giw |",
                           "popping p99 px", "SSE p99 px", "crack pixels", "bench/popping.png",
                           "bench/comparison.png"}) {
    EXPECT_NE(text.find(part), std::string::npos) << part << "\n" << text;
  }
  // The table carries the benchmark's own figures.
  std::ifstream reportFile(dir / "bench/bench.json");
  const nlohmann::json report = nlohmann::json::parse(reportFile);
  ASSERT_EQ(report["algorithms"].size(), 8u);
  for (const auto& algo : report["algorithms"]) {
    // Geometry image warping gives no bound (it may leave a few pixels of terrain edge open).
    if (algo["algo"] != "giw") {
      EXPECT_EQ(algo["summary"]["crack_pixels_total"].get<std::uint64_t>(), 0u) << algo["algo"];
    }
    EXPECT_TRUE(algo["summary"].contains("pop_px_p99"));
  }
  // The globe: a planet with continents and oceans from orbit (blue and not), the terrain from
  // near the ground with the sky above it, and the globe reference crack-free down to it.
  Result<RgbImage> orbit = readPng(dir / "globe-orbit.png");
  Result<RgbImage> near = readPng(dir / "globe-terrain.png");
  ASSERT_TRUE(orbit && near);
  EXPECT_GT(test::luminanceStdDev(*orbit), 10.0);
  EXPECT_GT(test::luminanceStdDev(*near), 5.0);
  const auto pixel = [](const RgbImage& image, int x, int y) {
    const std::size_t i = (std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3;
    return std::array<int, 3>{image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]};
  };
  const std::array<int, 3> sky = pixel(*near, 160, 2);
  EXPECT_GT(sky[2], sky[0] + 30) << "blue sky at the top";
  std::ifstream globeFile(dir / "globe-bench/bench.json");
  const nlohmann::json globe = nlohmann::json::parse(globeFile);
  ASSERT_EQ(globe["algorithms"].size(), 3u);  // globe-reference, ringo, spiral
  EXPECT_EQ(globe["path"], "descent");
  // The truth is the store at its deepest depth; the reference draws the store's finest tiles
  // wherever a shallower one would show, so it scores well under a pixel against it. RINGO
  // down the same descent: no crack, within the 2 px.
  EXPECT_EQ(globe["algorithms"][0]["summary"]["crack_pixels_total"].get<std::uint64_t>(), 0u);
  EXPECT_LT(globe["algorithms"][0]["summary"]["sse_px_p99"].get<double>(), 0.5);
  EXPECT_EQ(globe["algorithms"][1]["algo"], "ringo");
  EXPECT_EQ(globe["algorithms"][1]["summary"]["crack_pixels_total"].get<std::uint64_t>(), 0u);
  EXPECT_LT(globe["algorithms"][1]["summary"]["sse_px_p99"].get<double>(), 2.0);
  // The spiral globe down the same descent: no crack.
  EXPECT_EQ(globe["algorithms"][2]["algo"], "spiral");
  EXPECT_EQ(globe["algorithms"][2]["summary"]["crack_pixels_total"].get<std::uint64_t>(), 0u);
  // RINGO draws the same view as the globe reference, nearly the same pixels.
  Result<RgbImage> ringo = readPng(dir / "globe-terrain-ringo.png");
  ASSERT_TRUE(ringo);
  EXPECT_LT(test::meanDifference(*ringo, *near), 12.0);
  for (const char* part : {"## The globe", "globe-orbit.png", "globe-terrain.png",
                           "globe-terrain-ringo.png", "ringo:",
                           "| globe-reference |", "| ringo |", "globe-bench/frame_time.png"}) {
    EXPECT_NE(text.find(part), std::string::npos) << part;
  }
}

struct BadInput {
  const char* name;
  std::string arguments;  // {out} is replaced by the output path, {dir} by the test folder
  const char* messagePart;
};

TEST(Cli, BadInputFailsCleanlyWithoutOutput) {
  const fs::path dir = test::freshTestDir();
  std::FILE* garbage = std::fopen((dir / "garbage.tif").c_str(), "wb");
  ASSERT_NE(garbage, nullptr);
  std::fputs("II*\0 definitely not a GeoTIFF", garbage);
  std::fclose(garbage);
  const std::string gen = quoted(dir / "small.tif");
  ASSERT_EQ(runTellus(fmt::format("generate -o {} --size 33", gen)).exitCode, 0);

  const std::vector<BadInput> cases = {
      {"missing input", "render {dir}/missing.hgt -o {out}", "no such file"},
      {"corrupt raster", "render {dir}/garbage.tif -o {out}", "cannot read"},
      {"bad camera", "render " + gen + " -o {out} --camera 1,2,3", "camera"},
      {"camera not numbers", "render " + gen + " -o {out} --camera a,b,c,d,e,f", "not a number"},
      {"bad size", "render " + gen + " -o {out} --size 12x", "image size"},
      {"unknown view", "render " + gen + " -o {out} --view sideways", "sideways"},
      {"unknown encoding", "render " + gen + " -o {out} --encoding jpeg", "jpeg"},
      {"output folder missing", "render " + gen + " -o {dir}/nowhere/out.png", "does not exist"},
      {"output is a folder", "render " + gen + " -o {dir}", "is a folder"},
      {"generate into missing folder", "generate -o {dir}/nowhere/t.tif --size 33",
       "does not exist"},
      {"info on nothing", "info", "give DEM files"},
      {"globe renderer with a flat camera",
       "render " + gen + " -o {out} --algo globe-reference --camera 0,0,100,0,0,60",
       "draws on the globe"},
      {"geo camera beyond the pole",
       "render " + gen + " -o {out} --algo globe-reference --geo-camera 91,0,1000,0,0,60",
       "latitude"},
      {"geo camera for a flat renderer", "render " + gen + " -o {out} --geo-camera 0,0,1000,0,0,60",
       "globe renderers"},
      {"globe renderer on a projected DEM", "render " + gen + " -o {out} --algo globe-reference",
       "latitude/longitude"},
      {"missing geoid",
       "render " + gen + " -o {out} --algo globe-reference --geoid {dir}/none.gtx", "none.gtx"},
      {"globe renderer in bench on a projected DEM",
       "bench " + gen + " --algo globe-reference --frames 2", "latitude/longitude"},
      {"globe renderer in the viewer on a projected DEM",
       "view " + gen + " --algo globe-reference --frames 2", "latitude/longitude"},
  };
  for (const BadInput& c : cases) {
    std::string args = c.arguments;
    const fs::path out = dir / "out.png";
    for (auto [key, value] : {std::pair{"{out}", quoted(out)}, std::pair{"{dir}", dir.string()}}) {
      for (size_t at = args.find(key); at != std::string::npos; at = args.find(key))
        args.replace(at, 5, value);
    }
    const RunResult result = runTellus(args);
    EXPECT_NE(result.exitCode, 0) << c.name;
    EXPECT_NE(result.output.find(c.messagePart), std::string::npos)
        << c.name << ": " << result.output;
    EXPECT_FALSE(fs::exists(out)) << c.name << " left an output file";
  }
  // Nothing but the inputs is left in the folder: no partial or temporary files.
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir))
    left.push_back(entry.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"garbage.tif", "small.tif"}));
}

}  // namespace
}  // namespace tellus
