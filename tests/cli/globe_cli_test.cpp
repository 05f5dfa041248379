// The globe reference end to end: N37E127 on the ellipsoid from the default camera (straight
// down on the tile's centre) and from an explicit geo camera, with the EGM96 geoid.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/dem/dem_loader.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

TEST(GlobeCli, RendersASrtmTileOnTheEllipsoid) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string input = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const std::string geoid = quoted(data / "egm96-geoid/egm96_15.gtx");
  for (const char* camera : {"", "--geo-camera 37.2,127.5,6000,30,-25,55"}) {
    SCOPED_TRACE(camera);
    const fs::path png = dir / "globe.png";
    const RunResult result =
        runTellus(fmt::format("render {} -o {} --algo globe-reference --geoid {} --size 320x180 {}",
                              input, quoted(png), geoid, camera));
    ASSERT_EQ(result.exitCode, 0) << result.output;
    EXPECT_NE(result.output.find("geo camera"), std::string::npos) << result.output;
    Result<RgbImage> image = readPng(png);
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(image->width, 320);
    EXPECT_GT(test::luminanceStdDev(*image), 5.0) << "a blank image";
  }
}

// ETOPO5, one SRTM tile and one BIL tile into a global store (a few seconds).
std::string globalSources(const fs::path& data) {
  return fmt::format("{} {} {}", quoted(data / "etopo5-global/etopo5_int16.tif"),
                     quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"),
                     quoted(data / "srtm3-bil-guadeloupe/n16_w062_3arc_v2.bil"));
}

TEST(GlobeCli, GlobalStoreBuildInfoVerifyExportRender) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "earth.tstore";
  const RunResult built =
      runTellus(fmt::format("build --global {} -o {} --blend-edges 3000", globalSources(data),
                            quoted(store)));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  EXPECT_NE(built.output.find("global store, depths 0..10"), std::string::npos) << built.output;
  EXPECT_NE(built.output.find("taken as WGS 84"), std::string::npos)
      << "the BIL tile has no .prj: " << built.output;

  const RunResult info = runTellus(fmt::format("info {}", quoted(store)));
  ASSERT_EQ(info.exitCode, 0) << info.output;
  EXPECT_NE(info.output.find("N37E127.hgt: 127.0000..128.0000 E, 37.0000..38.0000 N"),
            std::string::npos)
      << info.output;
  EXPECT_NE(info.output.find("feeds depths 0..3"), std::string::npos) << "ETOPO5: " << info.output;
  EXPECT_NE(info.output.find("fades into the coarser ones over 3000 m"), std::string::npos)
      << info.output;

  const RunResult verify = runTellus(fmt::format("verify {}", quoted(store)));
  ASSERT_EQ(verify.exitCode, 0) << verify.output;
  EXPECT_NE(verify.output.find("shared edges, nesting, poles"), std::string::npos);

  const fs::path tif = dir / "region.tif";
  const RunResult exported = runTellus(fmt::format(
      "export {} -o {} --depth 10 --region 127.2,37.2,127.4,37.4", quoted(store), quoted(tif)));
  ASSERT_EQ(exported.exitCode, 0) << exported.output;
  Result<HeightGrid> region = loadDem({tif});
  ASSERT_TRUE(region) << region.error().message;
  EXPECT_TRUE(region->georef.isGeographic);
  EXPECT_GT(region->heightRange().maxM - region->heightRange().minM, 300.0f) << "Korean hills";

  // The Earth from orbit: a disc of land and sea colours in the middle, sky in the corners.
  const fs::path orbit = dir / "orbit.png";
  const RunResult drawn = runTellus(fmt::format(
      "render {} -o {} --algo globe-reference --size 320x180 --geo-camera 30,120,15000000,0,-90,45",
      quoted(store), quoted(orbit)));
  ASSERT_EQ(drawn.exitCode, 0) << drawn.output;
  // From orbit the store's cut stays shallow: ETOPO5's depths, whose error is sub-pixel there.
  EXPECT_NE(drawn.output.find("store cut:"), std::string::npos) << drawn.output;
  EXPECT_EQ(drawn.output.find("..10 within"), std::string::npos) << drawn.output;
  Result<RgbImage> image = readPng(orbit);
  ASSERT_TRUE(image);
  const auto pixel = [&](int x, int y) {
    const std::size_t i = 3 * (std::size_t(y) * std::size_t(image->width) + std::size_t(x));
    return std::array<int, 3>{image->pixels[i], image->pixels[i + 1], image->pixels[i + 2]};
  };
  EXPECT_EQ(pixel(2, 2), pixel(317, 177)) << "sky in both corners";
  EXPECT_NE(pixel(160, 90), pixel(2, 2)) << "the globe in the middle";
  EXPECT_LT(pixel(2, 2)[0] + pixel(2, 2)[1] + pixel(2, 2)[2], 60) << "space behind the globe";

  // Draped with the Blue Marble (the GPU test checks the colours land where they belong).
  const fs::path draped = dir / "draped.png";
  const RunResult drapedRun = runTellus(fmt::format(
      "render {} -o {} --algo globe-reference --size 320x180 --geo-camera 30,120,15000000,0,-90,45 "
      "--drape {}",
      quoted(store), quoted(draped), quoted(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg")));
  ASSERT_EQ(drapedRun.exitCode, 0) << drapedRun.output;
  image = readPng(draped);
  ASSERT_TRUE(image);
  EXPECT_NE(pixel(160, 90), pixel(2, 2));

  // 2 km over the SRTM tile: its full depth, hills in view.
  const fs::path low = dir / "low.png";
  const RunResult near = runTellus(fmt::format(
      "render {} -o {} --algo globe-reference --size 320x180 --geo-camera 37.49,127.53,2000,0,-45,60",
      quoted(store), quoted(low)));
  ASSERT_EQ(near.exitCode, 0) << near.output;
  EXPECT_NE(near.output.find("..10 within 1 px"), std::string::npos)
      << "the SRTM's depth under the camera: " << near.output;
  Result<RgbImage> hills = readPng(low);
  ASSERT_TRUE(hills);
  EXPECT_GT(test::luminanceStdDev(*hills), 5.0);

  // RINGO (seed 002) streams the same store: the same view nearly the same, with far fewer
  // triangles (its outer rings are coarser).
  const fs::path ringoLow = dir / "ringo-low.png";
  const RunResult ringo = runTellus(fmt::format(
      "render {} -o {} --algo ringo --size 320x180 --geo-camera 37.49,127.53,2000,0,-45,60",
      quoted(store), quoted(ringoLow)));
  ASSERT_EQ(ringo.exitCode, 0) << ringo.output;
  Result<RgbImage> ringoHills = readPng(ringoLow);
  ASSERT_TRUE(ringoHills);
  EXPECT_GT(test::luminanceStdDev(*ringoHills), 5.0);
  EXPECT_LT(test::meanDifference(*ringoHills, *hills), 12.0);

  // The spiral globe (seed 001) from the same store: the same hills, from one static spiral.
  const fs::path spiralLow = dir / "spiral-low.png";
  const RunResult spiral = runTellus(fmt::format(
      "render {} -o {} --algo spiral --spiral-textures none --size 320x180 "
      "--geo-camera 37.49,127.53,2000,0,-45,60",
      quoted(store), quoted(spiralLow)));
  ASSERT_EQ(spiral.exitCode, 0) << spiral.output;
  Result<RgbImage> spiralHills = readPng(spiralLow);
  ASSERT_TRUE(spiralHills);
  EXPECT_GT(test::luminanceStdDev(*spiralHills), 5.0);
  EXPECT_LT(test::meanDifference(*spiralHills, *hills), 15.0);
  // From orbit with the Blue Marble set: converted once into cube maps beside the store (small
  // faces here), read from there the second time; the night side is dark, the day side bright.
  for (int run = 0; run < 2; ++run) {
    const fs::path orbitPng = dir / "spiral-orbit.png";
    const RunResult r = runTellus(fmt::format(
        "render {} -o {} --algo spiral --spiral-textures {} --spiral-cube-size 128 --size 200x200 "
        "--geo-camera 20,150,15000000,0,-90,40",
        quoted(store), quoted(orbitPng), quoted(data / "bluemarble8k-global")));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("converting the Blue Marble set") != std::string::npos, run == 0)
        << r.output;
    EXPECT_TRUE(fs::exists(fs::path(store.string() + ".spiral-textures") / "surface-128.cube"));
    Result<RgbImage> earth = readPng(orbitPng);
    ASSERT_TRUE(earth);
    EXPECT_GT(test::luminanceStdDev(*earth), 20.0);
  }

  // The Landsat 9 scene over Tokyo (seed 001's texture quadtree) from 5 km: preprocessed once
  // into a pyramid beside the store, refined where the camera looks to the scene's own texels
  // (38.2 m Web Mercator pixels: 31 m on the ground at 35.6 N).
  const fs::path tokyo = dir / "spiral-tokyo.png";
  const RunResult landsat = runTellus(fmt::format(
      "render {} -o {} --algo spiral --spiral-textures none --spiral-imagery {} --size 320x180 "
      "--geo-camera 35.62,139.77,5000,0,-45,50",
      quoted(store), quoted(tokyo), quoted(data / "landsat9-kanto/landsat9_kanto_z12_3857.tif")));
  ASSERT_EQ(landsat.exitCode, 0) << landsat.output;
  EXPECT_NE(landsat.output.find("building the imagery pyramid"), std::string::npos);
  const std::size_t texelAt = landsat.output.find("finest texel ");
  ASSERT_NE(texelAt, std::string::npos) << landsat.output;
  const double finestM = std::stod(landsat.output.substr(texelAt + 13));
  EXPECT_GT(finestM, 28.0);
  EXPECT_LT(finestM, 34.0);
  Result<RgbImage> city = readPng(tokyo);
  ASSERT_TRUE(city);
  EXPECT_GT(test::luminanceStdDev(*city), 10.0);

  // Wrong uses say what is wrong.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("render {} -o {} --algo spiral --spiral-imagery {} --geo-camera 37,127,1000,0,0,60",
                   quoted(store), quoted(dir / "x.png"), quoted(data / "terrain-rgb-fuji/fuji.png")),
       "has no georeferencing"},
      {fmt::format("render {} -o {} --algo reference", quoted(store), quoted(dir / "x.png")),
       "is a global store"},
      {fmt::format("render {} -o {} --algo ringo --geo-camera 37,127,1000,0,0,60",
                   quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(dir / "x.png")),
       "streams from a global store"},
      {fmt::format("render {} -o {} --algo ringo", quoted(store), quoted(dir / "x.png")),
       "needs a camera"},
      {fmt::format("render {} -o {} --algo spiral --spiral-spin-step 7 --geo-camera 37,127,1000,0,0,60",
                   quoted(store), quoted(dir / "x.png")),
       "does not divide 360"},
      {fmt::format("render {} -o {} --algo spiral --spiral-textures {} --geo-camera 37,127,1000,0,0,60",
                   quoted(store), quoted(dir / "x.png"), quoted(dir)),
       "BlueMarbleAlbedo.jpg"},
      {fmt::format("render {} -o {} --algo spiral --spiral-projection mercator --geo-camera 37,127,1000,0,0,60",
                   quoted(store), quoted(dir / "x.png")),
       "mercator"},
      {fmt::format("render {} -o {} --algo ringo --store-depth 3 --geo-camera 37,127,1000,0,0,60",
                   quoted(store), quoted(dir / "x.png")),
       "chooses its blocks"},
      {fmt::format("render {} -o {} --algo globe-reference --store-depth 11", quoted(store),
                   quoted(dir / "x.png")),
       "depths 0..10, not 11"},
      {fmt::format("render {} -o {} --algo globe-reference --region 10,20,5,30", quoted(store),
                   quoted(dir / "x.png")),
       "west < east"},
      {fmt::format("export {} -o {} --depth 2", quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"),
                   quoted(dir / "x.tif")),
       "apply to --gltf and to -o of a global store"},
      {fmt::format("build --global {} -o {} --encoding terrarium",
                   quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(dir / "y.tstore")),
       "none of the sources is an 8-bit RGB image"},
      {fmt::format("build {} -o {} --blend-edges 5000",
                   quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(dir / "y.tstore")),
       "--blend-edges applies to --global builds"},
      {fmt::format("build --global {} -o {} --blend-edges -5",
                   quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(dir / "y.tstore")),
       "--blend-edges"},
      {fmt::format("build --global {} -o {} --spacing 30",
                   quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(dir / "y.tstore")),
       "--spacing does not apply to --global"},
      {fmt::format("build --global {} -o {} --encoding terrain-rgb",
                   quoted(data / "terrain-rgb-fuji/fuji.png"), quoted(dir / "y.tstore")),
       "has no georeferencing"},
      {fmt::format("render {} -o {} --algo globe-reference --drape {}", quoted(store),
                   quoted(dir / "x.png"),
                   quoted(data / "bluemarble8k-global/BlueMarbleAltitude.jpg")),
       "red, green and blue"},
      {fmt::format("render {} -o {} --drape {}",
                   quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(dir / "x.png"),
                   quoted(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg")),
       "are for globe renderers"},
      {fmt::format("build --global {} -o {}", quoted(data / "terrain-rgb-fuji/fuji.png"),
                   quoted(dir / "y.tstore")),
       "fuji.png"},
  };
  for (const auto& [arguments, expected] : cases) {
    const RunResult r = runTellus(arguments);
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "x.png"));
  EXPECT_FALSE(fs::exists(dir / "y.tstore"));
}

// bench on the globe: the reference judged against the store's finest surface along a descent
// from 20,000 km to 2 m onto the SRTM tile (0 cracks, error and popping well under a pixel: it
// draws the store's deepest tiles wherever a shallower one would show), the other paths running,
// and wrong combinations refused.
TEST(GlobeCli, BenchesTheGlobeReferenceAlongGlobePaths) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "earth.tstore";
  ASSERT_EQ(runTellus(fmt::format("build --global {} {} -o {}",
                                  quoted(data / "etopo5-global/etopo5_int16.tif"),
                                  quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"), quoted(store)))
                .exitCode,
            0);
  const fs::path json = dir / "descent.json";
  const RunResult descent = runTellus(fmt::format(
      "bench {} --algo globe-reference,ringo,spiral --path descent --target 37.49,127.53 --frames 8 "
      "--warmup 0 --quality --settle --size 160x90 --spiral-radii analytic --spiral-textures none "
      "--geoid {} --json {}",
      quoted(store), quoted(data / "egm96-geoid/egm96_15.gtx"), quoted(json)));
  ASSERT_EQ(descent.exitCode, 0) << descent.output;
  std::ifstream in(json);
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& run = report.at("algorithms").at(0);
  EXPECT_EQ(run.at("algo"), "globe-reference");
  EXPECT_EQ(run.at("summary").at("crack_pixels_total"), 0);
  EXPECT_LT(run.at("summary").at("sse_px_p99").get<double>(), 0.5);
  EXPECT_LT(run.at("summary").at("pop_px_p99").get<double>(), 0.5);
  int referencePopMeasured = 0;  // its previous frame's cut redrawn: popping is measured
  for (const nlohmann::json& frame : run.at("frames")) {
    referencePopMeasured += frame.at("pop_pixels").get<int>() > 0 ? 1 : 0;
  }
  EXPECT_GE(referencePopMeasured, 6);
  EXPECT_EQ(run.at("frames").size(), 8u);
  EXPECT_EQ(run.at("frames").at(0).at("geo_camera").get<std::string>().substr(0, 19),
            "37.490000,127.53000");
  // RINGO draws the same descent from the store (settled: 8 frames from orbit to 2 m are a
  // time-lapse no streaming keeps up with), judged against the store's finest surface; its
  // popping is measured (the previous frame's blocks redrawn) and its background threads' CPU
  // reported.
  const nlohmann::json& ringo = report.at("algorithms").at(1);
  EXPECT_EQ(ringo.at("algo"), "ringo");
  EXPECT_EQ(ringo.at("summary").at("crack_pixels_total"), 0);
  EXPECT_LT(ringo.at("summary").at("sse_px_p99").get<double>(), 2.0);
  int popMeasured = 0;
  double backgroundMs = 0.0;
  for (const nlohmann::json& frame : ringo.at("frames")) {
    popMeasured += frame.at("pop_pixels").get<int>() > 0 ? 1 : 0;
    backgroundMs += frame.at("background_cpu_ms").get<double>();
  }
  EXPECT_GE(popMeasured, 6);
  EXPECT_GT(backgroundMs, 0.0);
  // The spiral, its radii chosen analytically (the occlusion feedback trails a descent of 8
  // frames by several: docs/spiral.md): no cracks, close to the store's surface, about the same
  // triangles in every frame.
  const nlohmann::json& spiral = report.at("algorithms").at(2);
  EXPECT_EQ(spiral.at("algo"), "spiral");
  EXPECT_EQ(spiral.at("summary").at("crack_pixels_total"), 0);
  EXPECT_LT(spiral.at("summary").at("sse_px_p99").get<double>(), 5.0);
  std::uint64_t fewest = ~std::uint64_t(0), most = 0;
  for (const nlohmann::json& frame : spiral.at("frames")) {
    fewest = std::min(fewest, frame.at("triangles").get<std::uint64_t>());
    most = std::max(most, frame.at("triangles").get<std::uint64_t>());
  }
  // Within a factor of 8 from orbit to the ground (the range is cut at the horizon from high
  // up, at the fan near the ground): RINGO's and the reference's vary far more.
  EXPECT_LT(double(most), 8.0 * double(fewest)) << "the spiral's about constant density";
  for (const char* path : {"walk"}) {  // orbit and lowflight: unit-tested paths, slower here
    const RunResult r = runTellus(fmt::format(
        "bench {} --algo globe-reference --path {} --target 37.49,127.53 --frames 3 --warmup 0 "
        "--size 160x90",
        quoted(store), path));
    EXPECT_EQ(r.exitCode, 0) << path << "\n" << r.output;
  }
  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("bench {} --algo reference,globe-reference", quoted(store)),
       "draw different worlds"},
      {fmt::format("bench {} --algo reference --target 1,2",
                   quoted(data / "srtm3-hgt-east-asia/N37E127.hgt")),
       "are for globe renderers"},
      {fmt::format("bench {} --algo globe-reference --path spiral", quoted(store)),
       "unknown globe camera path"},
      {fmt::format("bench {} --algo globe-reference --path descent --target 0,-30", quoted(store)),
       ""},
  };
  for (const auto& [arguments, expected] : cases) {
    const RunResult r = runTellus(arguments + " --frames 2 --size 64x36 --warmup 0");
    if (expected.empty()) {
      EXPECT_EQ(r.exitCode, 0) << arguments << "\n" << r.output << " (ETOPO5 covers the ocean)";
      continue;
    }
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
  }
}

// SIGKILL a global build while it writes: no store appears, and the next build sweeps the
// temporary file away.
TEST(GlobeCli, AKilledGlobalBuildLeavesNoStore) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string build = fmt::format("'{}' build --global {} -o earth.tstore",
                                        TELLUS_EXECUTABLE, globalSources(data));
  const RunResult killed = runShell(fmt::format(
      "cd {} && ({} >/dev/null 2>&1 & pid=$!; "
      "for i in $(seq 500); do f=$(ls -A | grep '^.earth.tstore.tellus-partial-' | head -1); "
      "[ -n \"$f\" ] && [ $(stat -c %s \"$f\") -gt 100000 ] && echo writing && break; "
      "sleep 0.02; done; kill -9 $pid && echo killed; wait $pid)",
      quoted(dir), build));
  ASSERT_NE(killed.output.find("writing\nkilled"), std::string::npos) << killed.output;
  EXPECT_FALSE(fs::exists(dir / "earth.tstore"));
  ASSERT_EQ(runTellus(fmt::format("build --global {} -o {}",
                                  quoted(data / "etopo5-global/etopo5_int16.tif"),
                                  quoted(dir / "earth.tstore")))
                .exitCode,
            0);
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"earth.tstore"});
}

}  // namespace
}  // namespace tellus
