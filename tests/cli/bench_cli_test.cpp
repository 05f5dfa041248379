// tellus bench (renderers along a camera path): the report's JSON, CSV, plots and table, and
// bad arguments.
#include <fstream>
#include <optional>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

TEST(BenchCli, ReferenceAlongAnOrbitWithQualityWritesEveryReport) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string input = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const RunResult result = runTellus(fmt::format(
      "bench {} --algo reference --path orbit --frames 4 --warmup 1 --size 320x180 --quality "
      "--error-images --json {} --csv {} --plots {}",
      input, quoted(dir / "r.json"), quoted(dir / "r.csv"), quoted(dir / "plots")));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  for (const char* column : {"frame ms", "Mtris/s", "SSE p95", "SSE p99", "cracks", "reference"}) {
    EXPECT_NE(result.output.find(column), std::string::npos) << column << ":\n" << result.output;
  }
  std::ifstream in(dir / "r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_FALSE(report["machine"]["gl_renderer"].get<std::string>().empty());
  EXPECT_FALSE(report["machine"]["cpu"].get<std::string>().empty());
  ASSERT_EQ(report["algorithms"].size(), 1u);
  const nlohmann::json& summary = report["algorithms"][0]["summary"];
  for (const char* key :
       {"frame_ms_median", "frame_ms_p99", "cpu_lod_ms_median", "cpu_thread_ms_median",
        "cpu_thread_ms_p99", "gpu_waits_median", "gpu_waits_max", "triangles_median", "mtris_per_s",
        "sse_px_mean", "sse_px_p95", "sse_px_p99", "sse_px_max", "crack_pixels_total"}) {
    EXPECT_TRUE(summary.contains(key)) << key;
  }
  EXPECT_EQ(summary["crack_pixels_total"].get<int>(), 0);
  EXPECT_LT(summary["sse_px_p95"].get<double>(), 0.5);
  EXPECT_EQ(summary["triangles_median"].get<double>(), 2.0 * 1200 * 1200);
  EXPECT_EQ(report["algorithms"][0]["frames"].size(), 4u);

  std::ifstream csv(dir / "r.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("algo,frame,frame_ms,cpu_lod_ms,cpu_submit_ms,gpu_ms,triangles", 0), 0u);
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 4);
  for (const char* png :
       {"frame_time.png", "triangles.png", "cpu.png", "error_histogram.png", "contact_sheet.png",
        "frame-reference-0000.png", "error-reference-0003.png"}) {
    EXPECT_TRUE(fs::exists(dir / "plots" / png)) << png;
  }
}

// Seed 000's Table 1 rows on a store of N37E127 in one run, with quality: no cracks, far fewer
// triangles than the reference, streaming counters in the report; and a still from the rings.
TEST(BenchCli, RingsVariantsOnAStoreReportTableOneColumns) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "n37e127.tstore";
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --tile 64",
                                  quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(store)))
                .exitCode,
            0);
  const RunResult result = runTellus(fmt::format(
      "bench {} --algo reference,rings,rings-noculling,rings-brute,rings-brute-noculling "
      "--path flyover --frames 4 --warmup 1 --size 320x180 --quality --json {}",
      quoted(store), quoted(dir / "r.json")));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  for (const char* column : {"FPS min", "FPS med", "FPS max", "misses", "rings-brute-noculling"}) {
    EXPECT_NE(result.output.find(column), std::string::npos) << column << ":\n" << result.output;
  }
  std::ifstream in(dir / "r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report["algorithms"].size(), 5u);
  const nlohmann::json& reference = report["algorithms"][0]["summary"];
  const nlohmann::json& rings = report["algorithms"][1]["summary"];
  EXPECT_EQ(report["algorithms"][1]["algo"], "rings");
  EXPECT_EQ(rings["crack_pixels_total"], 0);
  EXPECT_LT(rings["triangles_median"].get<double>(),
            reference["triangles_median"].get<double>() / 4.0);
  EXPECT_GT(rings["cache_misses_total"].get<double>(), 0.0);
  EXPECT_GT(rings["fps_max"].get<double>(), 0.0);
  for (std::size_t i = 1; i < 5; ++i) {
    EXPECT_EQ(report["algorithms"][i]["summary"]["crack_pixels_total"], 0)
        << report["algorithms"][i]["algo"];
  }

  const RunResult still =
      runTellus(fmt::format("render {} --algo rings --shading lod "
                            "--wireframe --size 320x180 -o {}",
                            quoted(store), quoted(dir / "rings.png")));
  ASSERT_EQ(still.exitCode, 0) << still.output;
  EXPECT_TRUE(fs::exists(dir / "rings.png"));
}

// The fractal codec end to end on a real DEM: a store without residual records its measured
// error, bench codecs reports both fractal rows and the convergence, and seed 000's "Base
// incremental" row runs beside the base on that store; a lossless store is refused for it.
TEST(BenchCli, FractalStoreAndBaseIncremental) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "fractal.tstore";
  const std::string hgt = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  RunResult built = runTellus(fmt::format("build {} -o {} --codec fractal", hgt, quoted(store)));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  const RunResult info = runTellus(fmt::format("info {}", quoted(store)));
  EXPECT_NE(info.output.find("no bound; the largest error the build measured"), std::string::npos)
      << info.output;

  const RunResult bench = runTellus(
      fmt::format("bench {} --algo rings,rings-incremental --path flyover --frames 4 --warmup 1 "
                  "--size 320x180 --json {}",
                  quoted(store), quoted(dir / "t1.json")));
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  EXPECT_NE(bench.output.find("rings-incremental"), std::string::npos) << bench.output;

  const RunResult codecs = runTellus(fmt::format(
      "bench codecs {} --repeat 1 --convergence 4 --json {}", hgt, quoted(dir / "c.json")));
  ASSERT_EQ(codecs.exitCode, 0) << codecs.output;
  std::ifstream in(dir / "c.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  int fractalRows = 0;
  for (const nlohmann::json& row : report["entries"]) {
    if (row["name"].get<std::string>().starts_with("fractal")) {
      ++fractalRows;
      EXPECT_LT(row["bytes_per_tile"].get<double>(), 40000.0) << row["name"];
    }
    if (row["name"] == "fractal+residual (1 m)") {
      EXPECT_LE(row["max_abs_error_m"].get<double>(), 1.0);
    }
  }
  EXPECT_EQ(fractalRows, 2);
  ASSERT_EQ(report["fractal_convergence"].size(), 4u);
  EXPECT_GT(report["fractal_convergence"][0]["rmse_m"].get<double>(),
            report["fractal_convergence"][3]["rmse_m"].get<double>());

  const fs::path lossless = dir / "zstd.tstore";
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --tile 64", hgt, quoted(lossless))).exitCode, 0);
  const RunResult refused = runTellus(fmt::format("render {} --algo rings-incremental -o {}",
                                                  quoted(lossless), quoted(dir / "x.png")));
  EXPECT_NE(refused.exitCode, 0);
  EXPECT_NE(refused.output.find("--codec fractal"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// bench codecs --codecs runs only the chosen rows, and the fractal range options reach the
// codec: a 4 -> 2 quadtree that splits ranges worse than 10 m changes the fractal rows.
TEST(BenchCli, CodecsRunsTheChosenRowsWithTheFractalRangeOptions) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string hgt = quoted(data / "srtm3-hgt-east-asia/N37E128.hgt");
  const auto run = [&](const std::string& extra, const fs::path& json) {
    const RunResult result =
        runTellus(fmt::format("-q bench codecs {} --repeat 1 --convergence 2 --no-gpu --json {} {}",
                              hgt, quoted(json), extra));
    EXPECT_EQ(result.exitCode, 0) << result.output;
    std::ifstream in(json);
    return std::make_pair(result.output, nlohmann::json::parse(in));
  };
  const auto [plainOutput, plain] = run("--codecs fractal", dir / "plain.json");
  const auto [splitOutput, split] =
      run("--codecs zstd,fractal --fractal-range 2 --fractal-levels 2 --fractal-split 10",
          dir / "split.json");
  std::vector<std::string> names;
  for (const nlohmann::json& row : split["entries"]) names.push_back(row["name"]);
  EXPECT_EQ(names,
            (std::vector<std::string>{"zstd", "fractal (no bound)", "fractal+residual (1 m)"}));
  ASSERT_EQ(plain["entries"].size(), 2u);
  const nlohmann::json& fixed = plain["entries"][0];
  const nlohmann::json& quadtree = split["entries"][1];
  EXPECT_GT(quadtree["bytes"].get<double>(), fixed["bytes"].get<double>());    // splits cost bytes
  EXPECT_LT(quadtree["rmse_m"].get<double>(), fixed["rmse_m"].get<double>());  // and pay off
  EXPECT_NE(splitOutput.find("4x4 ranges split to 2x2 above 10 m"), std::string::npos)
      << splitOutput;
  EXPECT_NE(plainOutput.find("(4x4 ranges, no residual)"), std::string::npos) << plainOutput;

  const RunResult unknown = runTellus(fmt::format("bench codecs {} --codecs fractal,png", hgt));
  EXPECT_NE(unknown.exitCode, 0);
  EXPECT_NE(unknown.output.find("unknown row 'png'"), std::string::npos) << unknown.output;
}

TEST(BenchCli, BadArgumentsFailCleanly) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string input = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("bench {} --algo no-such-renderer --frames 2 --json {}", input, quoted(dir / "x.json")),
       "unknown renderer 'no-such-renderer'"},
      {fmt::format("bench {} --path spiral --frames 2 --json {}", input, quoted(dir / "x.json")),
       "unknown camera path 'spiral'"},
      {fmt::format("bench {} --path {} --frames 2", input, quoted(dir / "missing.json")),
       "missing.json': no such file"},
      {fmt::format("bench {} --frames 2 --json {}/nowhere/x.json", input, dir.string()),
       "does not exist"},
      {"bench --frames 2", "give a DEM or tile store"},
      {fmt::format("bench {} --frames 2 --error-images", input), "needs --quality and --plots"},
      {fmt::format("bench {} --algo rings --frames 2", input), "streams from a tile store"},
      {fmt::format("render {} --algo rings -o {}", input, quoted(dir / "x.png")),
       "streams from a tile store"},
  };
  for (const auto& [arguments, message] : cases) {
    const RunResult result = runTellus(arguments);
    EXPECT_NE(result.exitCode, 0) << arguments;
    EXPECT_NE(result.output.find(message), std::string::npos) << arguments << ":\n"
                                                              << result.output;
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

// --vary: one renderer once per value of its option, every run against the same reference,
// each reported under its value with the options it ran with; the others run once.
TEST(BenchCli, VaryRunsARendererOncePerValue) {
  const fs::path dir = test::freshTestDir();
  const fs::path dem = dir / "hills.tif";
  ASSERT_EQ(runTellus(fmt::format("generate --size 257 --spacing 30 --relief 600 -o {}", quoted(dem))).exitCode, 0);
  const RunResult result = runTellus(fmt::format(
      "bench {} --algo reference,roam --vary roam-target=8,0.5 --path flyover --frames 4 "
      "--warmup 1 --size 320x180 --quality --json {}",
      quoted(dem), quoted(dir / "r.json")));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("roam[roam-target=8]"), std::string::npos) << result.output;
  std::ifstream in(dir / "r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& runs = report["algorithms"];
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0]["algo"], "reference");
  EXPECT_EQ(runs[1]["algo"], "roam[roam-target=8]");
  EXPECT_EQ(runs[2]["algo"], "roam[roam-target=0.5]");
  EXPECT_EQ(runs[1]["options"]["roam-target"], 8.0);
  EXPECT_EQ(runs[2]["options"]["roam-target"], 0.5);
  // The option took effect: the finer target draws more triangles and errs less.
  const nlohmann::json& coarse = runs[1]["summary"];
  const nlohmann::json& fine = runs[2]["summary"];
  EXPECT_GT(fine["triangles_median"].get<double>(), 1.5 * coarse["triangles_median"].get<double>());
  EXPECT_LT(fine["sse_px_p99"].get<double>(), coarse["sse_px_p99"].get<double>());

  const std::vector<std::pair<std::string, std::string>> refused = {
      {"roam-target", "give OPTION=V1,V2"},
      {"roam-target=", "no values"},
      {"roam-target=1,1", "given twice"},
      {"roam-target=-3", "roam-target"},
      {"rag-pixels=1,2", "no renderer of --algo has an option 'rag-pixels'"},
  };
  for (const auto& [vary, message] : refused) {
    const RunResult bad = runTellus(fmt::format("bench {} --algo roam --vary {} --frames 2 --json {}",
                                                quoted(dem), vary, quoted(dir / "x.json")));
    EXPECT_NE(bad.exitCode, 0) << vary;
    EXPECT_NE(bad.output.find(message), std::string::npos) << vary << ":\n" << bad.output;
    EXPECT_FALSE(fs::exists(dir / "x.json")) << vary;
  }
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

// Issue 44: no renderer makes its render thread wait for the GPU inside its frames (prepare and
// draw; gl/gpu_wait.hpp counts every read-back, glFinish, unready query and fence wait). The
// bench reports gpu_waits per frame and its median and max per renderer. Every renderer of the
// list, flat, stack and globe, along a short path: none waits after the warm-up.
TEST(BenchCli, RenderersDoNotWaitForTheGpuInTheirFrames) {
  const fs::path dir = test::freshTestDir();
  const fs::path dem = dir / "hills.tif", store = dir / "hills.tstore", stacks = dir / "hills.tstack";
  ASSERT_EQ(runTellus(fmt::format("generate --size 257 --spacing 30 --relief 600 -o {}", quoted(dem))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --tile 64 --bdam", quoted(dem), quoted(store))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("stacks build {} -o {} --seed 3", quoted(dem), quoted(stacks))).exitCode, 0);
  std::vector<std::pair<fs::path, std::string>> benches = {{store, "flyover"}, {stacks, "flyover"}};
  if (const std::optional<fs::path> data = test::sharedDataDir()) {
    const fs::path earth = dir / "earth.tstore";
    ASSERT_EQ(runTellus(fmt::format("build --global {} -o {}",
                                    quoted(*data / "etopo5-global/etopo5_int16.tif"), quoted(earth)))
                  .exitCode,
              0);
    benches.emplace_back(earth, "descent");
  }
  std::set<std::string> measured;
  for (const auto& [input, path] : benches) {
    const fs::path json = dir / (input.stem().string() + input.extension().string() + ".json");
    const RunResult result = runTellus(
        fmt::format("bench {} --algo all --path {} --frames 5 --warmup 2 --size 320x180 --json {}",
                    quoted(input), path, quoted(json)));
    ASSERT_EQ(result.exitCode, 0) << result.output;
    EXPECT_NE(result.output.find("waits"), std::string::npos) << result.output;
    std::ifstream in(json);
    const nlohmann::json report = nlohmann::json::parse(in);
    for (const nlohmann::json& run : report["algorithms"]) {
      const std::string algo = run["algo"];
      measured.insert(algo);
      for (const nlohmann::json& frame : run["frames"]) ASSERT_TRUE(frame.contains("gpu_waits")) << algo;
      const double median = run["summary"]["gpu_waits_median"], max = run["summary"]["gpu_waits_max"];
      EXPECT_EQ(max, 0.0) << algo << " waited for the GPU (median " << median << ") along "
                          << path << " on " << input.filename();
    }
  }
  for (const char* algo : {"reference", "rings", "rag", "roam", "clipmaps", "gamer", "bdam", "giw",
                           "stacks-full", "stacks"}) {
    EXPECT_TRUE(measured.count(algo)) << algo << " was not benched";
  }
}

}  // namespace
}  // namespace tellus
