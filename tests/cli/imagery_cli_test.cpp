// Imagery draped on the flat renderers (issue 46, item 1): `--imagery` in render and bench over
// a store built from a real SRTM tile, with Blue Marble (a JPEG with a world file, no CRS) and a
// pattern in Web Mercator warped onto the store's latitude/longitude grid; the pyramids cached
// beside the store; the bench's imagery figures within their budgets; bad requests refused with
// the file named and nothing written (also for stack terrain, which has no height field).
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/imagery_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/core/rgb_image.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

// Seoul's SRTM tile (N37 E127) as a store in `dir`.
fs::path seoulStore(const fs::path& data, const fs::path& dir) {
  const fs::path store = dir / "seoul.tstore";
  const RunResult built =
      runTellus(fmt::format("build {} -o {}", quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(store)));
  EXPECT_EQ(built.exitCode, 0) << built.output;
  return store;
}

// A bright pattern in Web Mercator over the tile's south-west quarter (127.0..127.5 E,
// 37.0..37.4 N): squares of 32 texels, pure red or pure green.
fs::path mercatorPattern(const fs::path& dir) {
  const fs::path tif = dir / "pattern3857.tif";
  // 127.0 E = 14137575 m, 37.4 N = 4494810 m; 300 m texels: 185 x 189 texels.
  test::TestImage image{.width = 185, .height = 189, .west = 14137575.0, .north = 4494810.0, .texelSize = 300.0,
                        .epsg = 3857, .texel = [](int x, int y) {
                          return ((x / 32 + y / 32) % 2) ? std::array<std::uint8_t, 4>{230, 10, 10, 255}
                                                         : std::array<std::uint8_t, 4>{10, 230, 10, 255};
                        }};
  test::writeTestImage(image, tif);
  return tif;
}

TEST(ImageryCli, RenderDrapesBlueMarbleAndAMercatorImageOverAStore) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = seoulStore(data, dir);
  const fs::path pattern = mercatorPattern(dir);
  const fs::path blueMarble = data / "bluemarble8k-global/BlueMarbleAlbedo.jpg";
  // Straight down on the tile: its south-west quarter shows the pattern.
  const std::string camera = "--camera 55000,55000,160000,0,-89.9,40 --size 320x180";
  const RunResult tint = runTellus(fmt::format("render {} --algo rings {} -o {}", quoted(store), camera,
                                               quoted(dir / "tint.png")));
  ASSERT_EQ(tint.exitCode, 0) << tint.output;
  const RunResult draped = runTellus(fmt::format("render {} --algo rings {} --imagery {} {} -o {}", quoted(store),
                                                 camera, quoted(blueMarble), quoted(pattern),
                                                 quoted(dir / "draped.png")));
  ASSERT_EQ(draped.exitCode, 0) << draped.output;
  // Both pyramids were built once, beside the store.
  int pyramids = 0;
  for (const auto& entry : fs::directory_iterator(dir / "seoul.tstore.imagery")) {
    pyramids += entry.path().extension() == ".timagery" ? 1 : 0;
  }
  EXPECT_EQ(pyramids, 2);
  Result<RgbImage> image = readPng(dir / "draped.png");
  ASSERT_TRUE(image) << image.error().message;
  // The pattern's quarter: lit red and green squares; the tint has neither.
  int red = 0, green = 0;
  for (int y = 110; y < 170; ++y) {
    for (int x = 80; x < 140; ++x) {
      const std::uint8_t* p = image->at(x, y);
      // Lit and hazed: the dominant channel leads the others by far.
      red += p[0] > p[1] + 80 && p[0] > p[2] + 80 ? 1 : 0;
      green += p[1] > p[0] + 80 && p[1] > p[2] + 80 ? 1 : 0;
    }
  }
  EXPECT_GT(red, 1000) << "the pattern's red squares are missing";
  EXPECT_GT(green, 1000) << "the pattern's green squares are missing";
  // The north-east quarter shows Blue Marble, not the tint: the two images differ there.
  Result<RgbImage> plain = readPng(dir / "tint.png");
  ASSERT_TRUE(plain);
  double difference = 0.0;
  for (int y = 20; y < 80; ++y) {
    for (int x = 170; x < 230; ++x) {
      for (int c = 0; c < 3; ++c) difference += std::abs(int(image->at(x, y)[c]) - int(plain->at(x, y)[c]));
    }
  }
  EXPECT_GT(difference / (60.0 * 60.0 * 3.0), 10.0);
  // A second render reuses the cached pyramids.
  const RunResult again = runTellus(fmt::format("render {} --algo rings {} --imagery {} {} -o {}", quoted(store),
                                                camera, quoted(blueMarble), quoted(pattern),
                                                quoted(dir / "again.png")));
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_EQ(again.output.find("building the imagery pyramid"), std::string::npos) << again.output;
}

TEST(ImageryCli, BenchReportsImageryWithinItsBudgets) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = seoulStore(data, dir);
  const fs::path pattern = mercatorPattern(dir);
  const fs::path report = dir / "bench.json";
  const RunResult r = runTellus(fmt::format(
      "bench {} --algo rings,roam --path flyover --frames 8 --warmup 1 --size 256x144 --imagery {} "
      "--imagery-uploads 2 --imagery-budget 4 --json {}",
      quoted(store), quoted(pattern), quoted(report)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(report));
  ASSERT_EQ(json["algorithms"].size(), 2u);
  for (const auto& algorithm : json["algorithms"]) {
    const auto& s = algorithm["summary"];
    ASSERT_TRUE(s.contains("imagery_budget_bytes")) << algorithm["algo"];
    EXPECT_LE(s["imagery_budget_bytes"].get<double>(), 4.0 * 1024 * 1024);
    EXPECT_LE(s["imagery_resident_bytes_max"].get<double>(), s["imagery_budget_bytes"].get<double>());
    EXPECT_LE(s["imagery_uploads_max"].get<int>(), 2);
    EXPECT_GT(s["imagery_texel_px_p50"].get<double>(), 0.0);
    for (const auto& frame : algorithm["frames"]) {
      EXPECT_LE(frame["imagery_uploads"].get<int>(), 2);
      EXPECT_EQ(frame["gpu_waits"].get<int>(), 0) << "the imagery's feedback made the frame wait";
    }
  }
}

TEST(ImageryCli, RefusesWhatCannotBeDraped) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = seoulStore(data, dir);
  const fs::path landsat = data / "landsat9-kanto/landsat9_kanto_z12_3857.tif";
  const fs::path out = dir / "out.png";
  // The Kanto scene lies nowhere near Seoul.
  RunResult r = runTellus(fmt::format("render {} --algo rings --imagery {} -o {}", quoted(store), quoted(landsat),
                                      quoted(out)));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("does not overlap"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("landsat9_kanto"), std::string::npos) << r.output;
  // Not an image.
  const fs::path text = dir / "notes.txt";
  std::ofstream(text) << "not imagery\n";
  r = runTellus(fmt::format("render {} --algo rings --imagery {} -o {}", quoted(store), quoted(text), quoted(out)));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("notes.txt"), std::string::npos) << r.output;
  // A heights-only raster (one band).
  r = runTellus(fmt::format("render {} --algo rings --imagery {} -o {}", quoted(store),
                            quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(out)));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("N37E127.hgt"), std::string::npos) << r.output;
  // Stack terrain has no height field to drape over.
  const fs::path tif = dir / "small.tif", stacks = dir / "small.tstack";
  ASSERT_EQ(runTellus(fmt::format("generate -o {} --size 65 --seed 3", quoted(tif))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("stacks build {} -o {}", quoted(tif), quoted(stacks))).exitCode, 0);
  for (const std::string command : {"render {} --imagery {} -o {}", "bench {} --frames 2 --imagery {} --json {}"}) {
    r = runTellus(fmt::format(fmt::runtime(command), quoted(stacks),
                              quoted(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg"), quoted(out)));
    EXPECT_NE(r.exitCode, 0) << command;
    EXPECT_NE(r.output.find("--imagery drapes imagery over height fields"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(out));
}

// The globe: the same --imagery over RINGO and the spiral, placed by longitude and latitude;
// Landsat's Kanto scene over Tokyo Bay, Blue Marble round the globe (across the antimeridian).
TEST(ImageryCli, GlobeRenderersDrapeImageryByLatitudeAndLongitude) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "earth.tstore";
  const RunResult built = runTellus(fmt::format("build --global {} -o {}",
                                                quoted(data / "etopo5-global/etopo5_int16.tif"), quoted(store)));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  const fs::path blueMarble = data / "bluemarble8k-global/BlueMarbleAlbedo.jpg";
  const fs::path landsat = data / "landsat9-kanto/landsat9_kanto_z12_3857.tif";
  // Straight down on Tokyo Bay from 60 km: the tint paints the bay's ETOPO5 sea floor blue and
  // the land green; Landsat shows the bay dark and the city grey.
  const std::string tokyo = "--geo-camera 35.45,139.85,60000,0,-90,50 --size 160x90";
  for (const std::string algo : {"ringo", "spiral"}) {
    const RunResult draped = runTellus(fmt::format("render {} --algo {} {} --imagery {} {} -o {}", quoted(store),
                                                   algo, tokyo, quoted(blueMarble), quoted(landsat),
                                                   quoted(dir / (algo + "-tokyo.png"))));
    ASSERT_EQ(draped.exitCode, 0) << draped.output;
    const RunResult tint = runTellus(fmt::format("render {} --algo {} {} -o {}", quoted(store), algo, tokyo,
                                                 quoted(dir / (algo + "-tint.png"))));
    ASSERT_EQ(tint.exitCode, 0) << tint.output;
    Result<RgbImage> a = readPng(dir / (algo + "-tokyo.png"));
    Result<RgbImage> b = readPng(dir / (algo + "-tint.png"));
    ASSERT_TRUE(a && b);
    // Landsat is a photograph: its pixels differ from the tint's nearly everywhere, and it is
    // grey (the city) where the tint is saturated.
    double difference = 0.0, saturation = 0.0;
    for (std::size_t k = 0; k < a->pixels.size(); k += 3) {
      for (int c = 0; c < 3; ++c) difference += std::abs(int(a->pixels[k + c]) - int(b->pixels[k + c]));
      const auto [lo, hi] = std::minmax({a->pixels[k], a->pixels[k + 1], a->pixels[k + 2]});
      saturation += double(hi - lo);
    }
    const double pixels = double(a->pixels.size() / 3);
    EXPECT_GT(difference / (3.0 * pixels), 15.0) << algo;
    EXPECT_LT(saturation / pixels, 60.0) << algo;
  }
  // A descent onto Tokyo: the figures within their budgets, never a wait for the GPU, and at the
  // end the Landsat texels larger than a pixel.
  const fs::path report = dir / "descent.json";
  const RunResult bench = runTellus(fmt::format(
      "bench {} --algo ringo --path descent --target 35.68,139.77 --frames 12 --warmup 1 --size 192x108 "
      "--imagery {} {} --imagery-uploads 4 --json {}",
      quoted(store), quoted(blueMarble), quoted(landsat), quoted(report)));
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(report));
  const auto& s = json["algorithms"][0]["summary"];
  EXPECT_LE(s["imagery_uploads_max"].get<int>(), 4);
  EXPECT_LE(s["imagery_resident_bytes_max"].get<double>(), s["imagery_budget_bytes"].get<double>());
  for (const auto& frame : json["algorithms"][0]["frames"]) EXPECT_EQ(frame["gpu_waits"].get<int>(), 0);
  EXPECT_GT(json["algorithms"][0]["frames"].back()["imagery_texel_px_p50"].get<double>(), 1.0);
}

}  // namespace
}  // namespace tellus
