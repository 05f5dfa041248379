// RAG (seed 004) end to end on N37E127: stills of both variants, a quality run beside the
// reference (no cracks, the default settings' error and triangle budget), bad --rag-* values.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"
#include "tellus/core/rgb_image.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

TEST(RagCli, RendersBothVariantsAndTheirErrorView) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string input = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  for (const char* algo : {"rag", "rag-right"}) {
    for (const char* shading : {"lit", "sse"}) {
      SCOPED_TRACE(::testing::Message() << algo << ", " << shading);
      const fs::path png = dir / fmt::format("{}-{}.png", algo, shading);
      const RunResult result =
          runTellus(fmt::format("render {} -o {} --algo {} --shading {} --view oblique "
                                "--size 320x180",
                                input, quoted(png), algo, shading));
      ASSERT_EQ(result.exitCode, 0) << result.output;
      Result<RgbImage> image = readPng(png);
      ASSERT_TRUE(image.ok());
      EXPECT_EQ(image->width, 320);
      EXPECT_GT(test::luminanceStdDev(*image), 5.0) << "a blank image";
    }
  }
}

TEST(RagCli, QualityRunBesideTheReferenceHasNoCracks) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string input = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const RunResult result = runTellus(fmt::format(
      "bench {} --algo reference,rag,rag-right --path flyover --frames 8 --warmup 1 "
      "--size 480x270 --quality --json {}",
      input, quoted(dir / "r.json")));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::ifstream in(dir / "r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report["algorithms"].size(), 3u);
  const nlohmann::json& reference = report["algorithms"][0]["summary"];
  for (int i = 1; i < 3; ++i) {
    const nlohmann::json& run = report["algorithms"][std::size_t(i)];
    SCOPED_TRACE(run["algo"].get<std::string>());
    const nlohmann::json& summary = run["summary"];
    EXPECT_EQ(summary["crack_pixels_total"].get<int>(), 0);
    EXPECT_LT(summary["triangles_median"].get<double>(),
              reference["triangles_median"].get<double>() / 10.0);
  }
  // The defaults (80 x 80 vertices, 6 passes, 0.5 px) keep rag's error small.
  const nlohmann::json& rag = report["algorithms"][1]["summary"];
  EXPECT_LT(rag["sse_px_p99"].get<double>(), 3.0);
}

TEST(RagCli, RefusesNonsenseParameters) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string input = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  for (const char* bad : {"--rag-passes 9", "--rag-pixels 0", "--rag-coarse 1",
                          "--rag-depth-detail 2", "--rag-height-diff -1", "--rag-edge-px -1"}) {
    SCOPED_TRACE(bad);
    const RunResult result = runTellus(fmt::format("render {} -o {} --algo rag {}", input,
                                                   quoted(dir / "x.png"), bad));
    EXPECT_NE(result.exitCode, 0);
    EXPECT_NE(result.output.find("--rag-"), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(dir / "x.png"));
  }
}

}  // namespace
}  // namespace tellus
