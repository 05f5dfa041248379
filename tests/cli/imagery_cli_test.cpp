// Imagery draped on the flat renderers (issue 46, item 1): `--imagery` in render and bench over
// a store built from a real SRTM tile, with Blue Marble (a JPEG with a world file, no CRS) and a
// pattern in Web Mercator warped onto the store's latitude/longitude grid; the pyramids cached
// beside the store; the bench's imagery figures within their budgets; bad requests refused with
// the file named and nothing written; stack terrain draped by the georeference of its DEM.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/imagery_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_file.hpp"

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
  // A stack terrain without a georeference (written before Tellus kept one, or generated).
  const fs::path stacks = dir / "plain.tstack";
  Result<StackTerrain> flat = StackTerrain::fromColumns(8, 8, 30.0, std::vector<std::vector<StackLayer>>(
                                                                     64, std::vector<StackLayer>{{0.0f, 50.0f, 1}}));
  ASSERT_TRUE(flat);
  ASSERT_TRUE(writeStackFile(stacks, buildStackPyramid(std::move(flat.value()))));
  for (const std::string command : {"render {} --imagery {} -o {}", "bench {} --frames 2 --imagery {} --json {}"}) {
    r = runTellus(fmt::format(fmt::runtime(command), quoted(stacks),
                              quoted(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg"), quoted(out)));
    EXPECT_NE(r.exitCode, 0) << command;
    EXPECT_NE(r.output.find("plain.tstack' has no georeference"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(out));
}

// Stack terrain keeps the georeference of the DEM it was built from (`tellus info` shows it), and
// both stack renderers drape imagery by it, in render and in bench (the budgets hold there too).
TEST(ImageryCli, StackTerrainBuiltFromAGeoreferencedDemTakesImagery) {
  const fs::path dir = test::freshTestDir();
  const fs::path tif = dir / "hills.tif", stacks = dir / "hills.tstack";
  // generate: UTM 33N, the north-west sample at 400,000 E, 5,200,000 N, 30 m apart (1,920 m).
  ASSERT_EQ(runTellus(fmt::format("generate -o {} --size 65 --seed 3 --relief 300", quoted(tif))).exitCode, 0);
  const RunResult built = runTellus(fmt::format("stacks build {} -o {}", quoted(tif), quoted(stacks)));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  const RunResult info = runTellus(fmt::format("info {}", quoted(stacks)));
  EXPECT_NE(info.output.find("georeferenced: WGS 84 / UTM zone 33N"), std::string::npos) << info.output;
  // Magenta west of 400,960 E (the terrain's middle), cyan east of it, 10 m texels.
  test::TestImage image{.width = 240, .height = 240, .west = 399800.0, .north = 5200200.0, .texelSize = 10.0,
                        .epsg = 32633, .texel = [](int x, int) {
                          return x < 116 ? std::array<std::uint8_t, 4>{255, 0, 255, 255}
                                         : std::array<std::uint8_t, 4>{0, 255, 255, 255};
                        }};
  test::writeTestImage(image, dir / "ortho.tif");
  // Straight down on the middle, north up: the west half magenta, the east half cyan.
  for (const std::string algo : {"stacks-full", "stacks"}) {
    const fs::path png = dir / (algo + ".png");
    const RunResult r = runTellus(fmt::format("render {} --algo {} --imagery {} --camera 960,960,4200,0,-89.9,20 "
                                              "--size 200x200 -o {}",
                                              quoted(stacks), algo, quoted(dir / "ortho.tif"), quoted(png)));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Result<RgbImage> drawn = readPng(png);
    ASSERT_TRUE(drawn) << drawn.error().message;
    int west = 0, east = 0, pixels = 0;
    for (int y = 20; y < 180; ++y) {
      for (int x = 20; x < 180; ++x) {
        if (x >= 90 && x < 110) continue;
        const std::uint8_t* p = drawn->at(x, y);
        ++pixels;
        if (x < 90 && 2 * p[1] < p[0] && 2 * p[1] < p[2]) ++west;
        if (x >= 110 && 2 * p[0] < p[1] && 2 * p[0] < p[2]) ++east;
      }
    }
    EXPECT_GT(west + east, pixels * 9 / 10) << algo << ": " << west << " magenta west, " << east << " cyan east of "
                                            << pixels;
  }
  const fs::path json = dir / "bench.json";
  const RunResult bench = runTellus(fmt::format("bench {} --algo stacks --frames 4 --warmup 0 --size 160x90 "
                                                "--imagery {} --imagery-uploads 2 --json {}",
                                                quoted(stacks), quoted(dir / "ortho.tif"), quoted(json)));
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  std::ifstream in(json);
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& s = report["algorithms"][0]["summary"];
  EXPECT_LE(s["imagery_uploads_max"].get<int>(), 2);
  EXPECT_GT(s["imagery_resident_bytes_max"].get<double>(), 0.0);
  EXPECT_LE(s["imagery_resident_bytes_max"].get<double>(), s["imagery_budget_bytes"].get<double>());
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
