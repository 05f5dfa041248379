// Tellus in its ecosystem, end to end: the installed package (cmake --install, pkg-config, the
// .deb) builds and runs the embedding example out of tree; `tellus export --gltf` and
// `--quantized-mesh` on the real Korea mosaic, the tile set loaded by CesiumJS in headless
// Chromium from a local lighttpd; stores read over http://; bad arguments refused.
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/http_server.hpp"
#include "support/test_support.hpp"
#include "tellus/export/quantized_mesh.hpp"

namespace tellus {
namespace {

namespace fs = std::filesystem;

// The Korea mosaic as a store, built once per run.
fs::path koreaStore() {
  static const fs::path store = [] {
    const fs::path dir = test::testOutputDir() / "ecosystem-korea";
    fs::create_directories(dir);
    const fs::path path = dir / "korea.tstore";
    if (!fs::exists(path)) {
      const RunResult built =
          runTellus(fmt::format("build {} -o {}", koreaArguments(*test::sharedDataDir()), quoted(path)));
      if (built.exitCode != 0) throw std::runtime_error(built.output);
    }
    return path;
  }();
  return store;
}

// A small generated store for the package tests (no real data needed).
fs::path smallStore(const fs::path& dir) {
  const RunResult generated = runTellus(fmt::format("generate --size 513 -o {}", quoted(dir / "small.tif")));
  EXPECT_EQ(generated.exitCode, 0) << generated.output;
  const RunResult built = runTellus(fmt::format("build {} -o {}", quoted(dir / "small.tif"), quoted(dir / "small.tstore")));
  EXPECT_EQ(built.exitCode, 0) << built.output;
  return dir / "small.tstore";
}

// Configures, builds and runs examples/embed against the package under `prefix`.
void buildAndRunEmbedExample(const fs::path& prefix, const fs::path& dir, const fs::path& store) {
  const RunResult configured = runShell(fmt::format(
      "cmake -S {} -B {} -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH={}",
      quoted(fs::path(TELLUS_SOURCE_DIR) / "examples/embed"), quoted(dir / "build"), quoted(prefix)));
  ASSERT_EQ(configured.exitCode, 0) << configured.output;
  const RunResult built = runShell(fmt::format("cmake --build {}", quoted(dir / "build")));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  const RunResult ran = runShell(fmt::format("{} {} {} 3", quoted(dir / "build/tellus_embed"),
                                             quoted(store), quoted(dir / "embed.png")));
  ASSERT_EQ(ran.exitCode, 0) << ran.output;
  EXPECT_NE(ran.output.find("frame 2:"), std::string::npos) << ran.output;
  EXPECT_NE(ran.output.find("patches:"), std::string::npos) << ran.output;  // rings' frame report
  Result<RgbImage> image = readPng(dir / "embed.png");
  ASSERT_TRUE(image);
  EXPECT_GT(test::luminanceStdDev(image.value()), 5.0);  // terrain, not a blank frame
}

TEST(Ecosystem, InstalledPackageBuildsTheEmbedExampleOutOfTree) {
  const fs::path dir = test::freshTestDir();
  const fs::path prefix = dir / "prefix";
  const RunResult installed = runShell(fmt::format("cmake --install {} --prefix {}",
                                                   quoted(TELLUS_BINARY_DIR), quoted(prefix)));
  ASSERT_EQ(installed.exitCode, 0) << installed.output;
  EXPECT_TRUE(fs::exists(prefix / "bin/tellus"));
  EXPECT_TRUE(fs::exists(prefix / "lib/cmake/tellus/tellusConfig.cmake"));
  // The declared public API, and none of the library's own headers.
  std::vector<std::string> headers;
  for (const auto& entry : fs::recursive_directory_iterator(prefix / "include"))
    headers.push_back(fs::relative(entry.path(), prefix / "include").string());
  std::ranges::sort(headers);
  EXPECT_EQ(headers, (std::vector<std::string>{"tellus", "tellus/result.hpp", "tellus/tellus.hpp",
                                               "tellus/terrain.hpp", "tellus/terrain_export.hpp",
                                               "tellus/terrain_view.hpp"}));
  EXPECT_TRUE(fs::exists(prefix / "share/tellus/shaders/rings/rings.vert"));
  const fs::path store = smallStore(dir);
  buildAndRunEmbedExample(prefix, dir, store);

  // pkg-config: the same program from the flags alone.
  const RunResult pc = runShell(fmt::format(
      "PKG_CONFIG_PATH={} g++ -O1 -o {} {} $(PKG_CONFIG_PATH={} pkg-config --cflags --libs tellus)",
      quoted(prefix / "lib/pkgconfig"), quoted(dir / "embed-pc"),
      quoted(fs::path(TELLUS_SOURCE_DIR) / "examples/embed/main.cpp"), quoted(prefix / "lib/pkgconfig")));
  ASSERT_EQ(pc.exitCode, 0) << pc.output;
  const RunResult ran = runShell(fmt::format("{} {} {} 1", quoted(dir / "embed-pc"), quoted(store), quoted(dir / "pc.png")));
  EXPECT_EQ(ran.exitCode, 0) << ran.output;
  // Another renderer by name, and a name that is none.
  const RunResult rag = runShell(fmt::format("{} {} {} 1 rag", quoted(dir / "embed-pc"), quoted(store), quoted(dir / "rag.png")));
  EXPECT_EQ(rag.exitCode, 0) << rag.output;
  EXPECT_NE(rag.output.find("pass 1:"), std::string::npos) << rag.output;
  const RunResult list = runShell(fmt::format("{} --list", quoted(dir / "embed-pc")));
  EXPECT_EQ(list.exitCode, 0) << list.output;
  EXPECT_NE(list.output.find("rings-gpu-slots"), std::string::npos) << list.output;
  const RunResult none = runShell(fmt::format("{} {} {} 1 no-such", quoted(dir / "embed-pc"), quoted(store), quoted(dir / "x.png")));
  EXPECT_NE(none.exitCode, 0);
  EXPECT_NE(none.output.find("unknown renderer 'no-such'"), std::string::npos) << none.output;
}

TEST(Ecosystem, DebianPackageHasItsDependenciesAndIsUsable) {
  const fs::path dir = test::freshTestDir();
  const RunResult packed = runShell(fmt::format("cd {} && cpack -G DEB --config {} -B {}", quoted(dir),
                                                quoted(fs::path(TELLUS_BINARY_DIR) / "CPackConfig.cmake"),
                                                quoted(dir / "deb")));
  ASSERT_EQ(packed.exitCode, 0) << packed.output;
  fs::path deb;
  for (const auto& entry : fs::directory_iterator(dir / "deb")) {
    if (entry.path().extension() == ".deb") deb = entry.path();
  }
  ASSERT_FALSE(deb.empty()) << packed.output;
  const RunResult depends = runShell(fmt::format("dpkg-deb -f {} Depends", quoted(deb)));
  ASSERT_EQ(depends.exitCode, 0) << depends.output;
  for (const char* package : {"libgdal", "libepoxy", "libtbb", "libgdal-dev", "libmeshoptimizer-dev"}) {
    EXPECT_NE(depends.output.find(package), std::string::npos) << package << " in " << depends.output;
  }
  // Unpacked (as dpkg would, without touching this system), it builds the example.
  const RunResult unpacked = runShell(fmt::format("dpkg-deb -x {} {}", quoted(deb), quoted(dir / "root")));
  ASSERT_EQ(unpacked.exitCode, 0) << unpacked.output;
  EXPECT_TRUE(fs::exists(dir / "root/usr/bin/tellus"));
  buildAndRunEmbedExample(dir / "root/usr", dir, smallStore(dir));
}

TEST(Ecosystem, GltfExportOfAKoreaRegionWithinItsError) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  const fs::path dir = test::freshTestDir();
  const RunResult exported = runTellus(fmt::format(
      "export {} --gltf {} --region 127.6,35.25,127.8,35.4 --max-error 5 --colours hypsometric",
      quoted(koreaStore()), quoted(dir / "jirisan.glb")));
  ASSERT_EQ(exported.exitCode, 0) << exported.output;
  EXPECT_NE(exported.output.find("max 3-D error"), std::string::npos) << exported.output;
  EXPECT_TRUE(fs::exists(dir / "jirisan.glb"));
  // Nonsense is refused with the reason, nothing written.
  for (const std::string& args :
       {fmt::format("export {} --gltf {} -o {}", quoted(koreaStore()), quoted(dir / "a.glb"), quoted(dir / "a.tif")),
        fmt::format("export {} --quantized-mesh {} --region 127,35,128,36", quoted(koreaStore()), quoted(dir / "q")),
        fmt::format("export {} --gltf {} --max-error -1", quoted(koreaStore()), quoted(dir / "b.glb")),
        fmt::format("export {} -o {}", quoted(koreaStore()), quoted(dir / "e.jpg")),
        fmt::format("export {} --gltf {}", quoted(koreaStore()), quoted(dir / "f.gltf")),
        fmt::format("export {} --gltf {} --region 10,10,11,11", quoted(koreaStore()), quoted(dir / "c.glb")),
        fmt::format("export {} --gltf {}", quoted(test::koreaMosaicTiles(*test::sharedDataDir())[0]), quoted(dir / "d.glb"))}) {
    const RunResult refused = runTellus(args);
    EXPECT_NE(refused.exitCode, 0) << args << "\n" << refused.output;
    EXPECT_FALSE(refused.output.empty()) << args;  // the reason
  }
  for (const char* name : {"a.glb", "a.tif", "b.glb", "c.glb", "d.glb", "e.jpg", "f.gltf"}) {
    EXPECT_FALSE(fs::exists(dir / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "q"));
}

// Every kind of glTF `export --gltf` writes, checked by the Khronos glTF validator
// (scripts/cesium-check/validate-gltf.sh, npm gltf-validator): 0 errors and 0 warnings. Among
// them the region and bound that gave the mesh of exactly 65,536 vertices written with
// 16-bit indices (index 65535 is the primitive-restart value: ACCESSOR_INDEX_PRIMITIVE_RESTART);
// with the 3-D error it now has 65,321 (GltfExport.SixtyFiveThousandFiveHundredAndThirtySix...
// keeps the exact count in the unit tests).
TEST(Ecosystem, GltfExportsPassTheKhronosValidator) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  const fs::path dir = test::freshTestDir();
  const std::vector<std::pair<std::string, std::string>> exports = {
      {"jirisan-colours.glb", "--region 127.6,35.25,127.8,35.4 --max-error 5 --colours hypsometric"},
      {"jirisan-exact.glb", "--region 127.65,35.3,127.7,35.35 --max-error 0"},
      {"jirisan-quantized.glb", "--region 127.6,35.25,127.8,35.4 --max-error 5 --quantize"},
      {"jirisan-bluemarble.glb", fmt::format("--region 127.4,35.1,128.0,35.55 --max-error 20 --texture {} --texture-size 512",
                                             quoted(*test::sharedDataDir() / "bluemarble8k-global/BlueMarbleAlbedo.jpg"))},
      {"issue-region.glb", "--region 128.5,36.5,128.89,37.0 --max-error 10.0927734375"},
      {"korea-coarse.glb", "--max-error 50 --max-samples 250000"}};
  std::string files;
  for (const auto& [name, options] : exports) {
    const RunResult exported = runTellus(fmt::format("export {} --gltf {} {}", quoted(koreaStore()), quoted(dir / name), options));
    ASSERT_EQ(exported.exitCode, 0) << name << "\n" << exported.output;
    files += ' ';
    files += quoted(dir / name);
  }
  const RunResult validated = runShell(fmt::format(
      "TELLUS_NPM_CACHE={} {}{} --report {}", quoted(fs::path(TELLUS_BINARY_DIR) / "cesium-check"),
      quoted(fs::path(TELLUS_SOURCE_DIR) / "scripts/cesium-check/validate-gltf.sh"), files, quoted(dir / "reports")));
  EXPECT_EQ(validated.exitCode, 0) << validated.output;
  for (const auto& [name, options] : exports) {
    std::ifstream reportFile(dir / "reports" / (name + ".json"));
    ASSERT_TRUE(reportFile) << name;
    const nlohmann::json report = nlohmann::json::parse(reportFile);
    EXPECT_EQ(report["issues"]["numErrors"].get<int>(), 0) << name;
    EXPECT_EQ(report["issues"]["numWarnings"].get<int>(), 0) << name;
  }
  std::cout << validated.output;
  // The textured mesh in CesiumJS, placed by its extras' frame (gltf-tileset.mjs wraps it in a
  // one-tile 3D Tiles set): Jirisan's summit where it is, as high as the store says.
  const fs::path scripts = fs::path(TELLUS_SOURCE_DIR) / "scripts/cesium-check";
  const RunResult wrapped = runShell(fmt::format("node {} {} {}", quoted(scripts / "gltf-tileset.mjs"),
                                                 quoted(dir / "jirisan-bluemarble.glb"), quoted(dir / "wrapped")));
  ASSERT_EQ(wrapped.exitCode, 0) << wrapped.output;
  const RunResult viewed = runShell(fmt::format(
      "TELLUS_NPM_CACHE={} {} {} {} 127.7 34.95 25000 0 -35 --sample 127.7306,35.3369",
      quoted(fs::path(TELLUS_BINARY_DIR) / "cesium-check"), quoted(scripts / "run.sh"), quoted(dir / "wrapped"),
      quoted(dir / "cesium")));
  ASSERT_EQ(viewed.exitCode, 0) << viewed.output;
  std::ifstream summaryFile(dir / "cesium/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summaryFile);
  EXPECT_NEAR(summary["sampledHeights"][0]["height"].get<double>(), 1880.0, 40.0) << summary.dump();
}

TEST(Ecosystem, QuantizedMeshOfKoreaRendersInCesium) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  const fs::path dir = test::freshTestDir();
  const fs::path tiles = dir / "tiles";
  const std::string geoid = (*test::sharedDataDir() / "egm96-geoid/egm96_15.gtx").string();
  // Levels 0..11 (the whole set goes to 12: 8464 more tiles, 40 s more, the same check).
  const RunResult exported = runTellus(fmt::format("export {} --quantized-mesh {} --max-level 11 --geoid {}",
                                                   quoted(koreaStore()), quoted(tiles), quoted(fs::path(geoid))));
  ASSERT_EQ(exported.exitCode, 0) << exported.output;
  EXPECT_TRUE(fs::exists(tiles / "layer.json"));
  EXPECT_TRUE(fs::exists(tiles / "0/0/0.terrain"));
  // CesiumJS in headless Chromium, served by lighttpd on 127.0.0.1 (scripts/cesium-check):
  // south of Jirisan looking north, the height sampled at its summit.
  const fs::path out = dir / "cesium";
  const RunResult viewed = runShell(fmt::format(
      "TELLUS_NPM_CACHE={} {} {} {} 127.73 35.05 25000 0 -35 --sample 127.7306,35.3369",
      quoted(fs::path(TELLUS_BINARY_DIR) / "cesium-check"),
      quoted(fs::path(TELLUS_SOURCE_DIR) / "scripts/cesium-check/run.sh"), quoted(tiles), quoted(out)));
  ASSERT_EQ(viewed.exitCode, 0) << viewed.output;
  std::ifstream summaryFile(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summaryFile);
  EXPECT_TRUE(summary["ok"].get<bool>());
  EXPECT_GT(summary["tilesRequested"].get<int>(), 10);
  EXPECT_EQ(summary["consoleErrors"].size(), 0u);
  // Jirisan's summit: SRTM's 1915 m peak at 3" (about 1880 m in the mosaic) plus EGM96's ~27 m,
  // as Cesium decodes it from the tiles.
  const double summit = summary["sampledHeights"][0]["height"].get<double>();
  EXPECT_NEAR(summit, 1900.0, 60.0) << summary.dump();
  EXPECT_TRUE(fs::exists(out / "screenshot.png"));
  fs::copy_file(out / "screenshot.png", test::testOutputDir() / "cesium-korea.png",
                fs::copy_options::overwrite_existing);
}

// The quantized-mesh set of N37E127 (every level, 0..12, heights made ellipsoidal with EGM96)
// checked by scripts/cesium-check/verify-tiles.mjs, a decoder written from the format's
// specification that shares no code with Tellus: at every level, the 3-D distance between the
// surface Cesium draws and each of the tile's 1.44 million SRTM samples is within Cesium's
// geometric error of that level (the Earth's curvature included), no sample falls in a hole,
// and neighbours share their edge vertices. The same set read as if it had no geoid misses
// by the geoid's 20-odd metres at the finest levels: the check can fail.
// N37E127's quantized-mesh set, every level (0..12), heights made ellipsoidal with EGM96, the
// metadata extension in the tiles of levels 0, 5 and 10;
// built once per test process in a folder of its own (ctest may run two of them at once).
struct N37TileSet {
  fs::path hgt, geoid, tiles;
};
const N37TileSet& n37TileSet() {
  static const N37TileSet set = [] {
    const fs::path data = *test::sharedDataDir();
    N37TileSet s{data / "srtm3-hgt-east-asia/N37E127.hgt", data / "egm96-geoid/egm96_15.gtx",
                 test::testOutputDir() / fmt::format("ecosystem-n37-{}", ::getpid()) / "tiles"};
    const fs::path dir = s.tiles.parent_path();
    fs::remove_all(dir);
    fs::create_directories(dir);
    const RunResult built = runTellus(fmt::format("build {} -o {}", quoted(s.hgt), quoted(dir / "n37.tstore")));
    if (built.exitCode != 0) throw std::runtime_error(built.output);
    // With the metadata extension every 5 levels: Cesium learns the tiles of levels 1..12
    // from the tiles of levels 0, 5 and 10.
    const RunResult exported = runTellus(fmt::format("export {} --quantized-mesh {} --geoid {} --metadata-levels 5",
                                                     quoted(dir / "n37.tstore"), quoted(s.tiles), quoted(s.geoid)));
    if (exported.exitCode != 0 || exported.output.find("max 3-D error m") == std::string::npos) {
      throw std::runtime_error(exported.output);
    }
    return s;
  }();
  return set;
}

TEST(Ecosystem, QuantizedMeshIsWithinItsErrorIn3DByAnIndependentDecoder) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  const fs::path dir = test::freshTestDir();
  const N37TileSet& set = n37TileSet();
  const fs::path& hgt = set.hgt;
  const fs::path& geoid = set.geoid;
  const fs::path checker = fs::path(TELLUS_SOURCE_DIR) / "scripts/cesium-check/verify-tiles.mjs";
  const RunResult verified = runShell(fmt::format("node {} {} --hgt {} --geoid {} --summary {}", quoted(checker),
                                                  quoted(set.tiles), quoted(hgt), quoted(geoid),
                                                  quoted(dir / "summary.json")));
  ASSERT_EQ(verified.exitCode, 0) << verified.output;
  std::cout << verified.output;  // the table, with the worst ratio
  std::ifstream summaryFile(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summaryFile);
  ASSERT_EQ(summary["levels"].size(), 13u);
  // Availability as Cesium reads it from the metadata (2,048 tiles of level 5, 2 of level 0,
  // 49 of level 10 carry it) names every file, and the same tiles as layer.json.
  EXPECT_EQ(summary["tilesWithMetadata"].get<int>(), 2 + 2048 + 49) << summary.dump();
  EXPECT_EQ(summary["availableTiles"], summary["filesOnDisk"]);
  for (const nlohmann::json& level : summary["levels"]) {
    EXPECT_EQ(level["samples"].get<std::int64_t>(), 1442396) << level.dump();  // 1201^2 less the edges
    EXPECT_LE(level["worstRatio"].get<double>(), 1.0) << level.dump();
    EXPECT_GT(level["worstRatio"].get<double>(), 0.1) << level.dump();  // measured, not zero
    EXPECT_EQ(level["holes"].get<int>(), 0) << level.dump();
  }
  const RunResult withoutGeoid = runShell(fmt::format("node {} {} --hgt {}", quoted(checker), quoted(set.tiles), quoted(hgt)));
  EXPECT_EQ(withoutGeoid.exitCode, 1) << withoutGeoid.output;
  EXPECT_NE(withoutGeoid.output.find("over the 18.82 m bound"), std::string::npos) << withoutGeoid.output;
}

// The same set drawn by CesiumJS (unlit, so that no globe pixel is black) and compared with the
// WGS84 ellipsoid as Cesium's camera sees it (check.mjs --globe-disc): from orbit over Korea,
// 2,000 km up looking at the limb, over the Atlantic (no data: the geoid's tiles of levels
// 0..5), at the antimeridian, and 3 km over the data looking at the horizon. The globe's
// limb within 1 % (area-equivalent radius), no background pixel inside its outline, no globe
// outside it. Before the tiles were bounded in 3-D the globe from orbit was a blob of 0.84
// its radius with 41,796 background pixels inside.
TEST(Ecosystem, QuantizedMeshGlobeIsRoundAndWholeInCesium) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  const fs::path dir = test::freshTestDir();
  const N37TileSet& set = n37TileSet();
  struct View {
    const char* name;
    const char* camera;  // lon lat height heading pitch [--sample lon,lat]
  };
  for (const View& view : {View{"orbit", "127.5 37.5 20000000 0 -90"}, View{"2000km", "127.5 25 2000000 0 -35"},
                           View{"atlantic", "-30 20 2000000 0 -30"},
                           View{"antimeridian", "180 0 20000000 0 -90 --sample 179.5,0.5"},
                           View{"ground", "127.2 37.2 3000 45 -10"}}) {
    const fs::path out = dir / view.name;
    const RunResult viewed = runShell(fmt::format(
        "TELLUS_NPM_CACHE={} {} {} {} {} --globe-disc --param lighting=0",
        quoted(fs::path(TELLUS_BINARY_DIR) / "cesium-check"),
        quoted(fs::path(TELLUS_SOURCE_DIR) / "scripts/cesium-check/run.sh"), quoted(set.tiles), quoted(out),
        view.camera));
    EXPECT_EQ(viewed.exitCode, 0) << view.name << "\n" << viewed.output;
    std::ifstream summaryFile(out / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(summaryFile);
    const nlohmann::json& disc = summary["globeDisc"];
    ASSERT_TRUE(disc.is_object()) << view.name << summary.dump();
    EXPECT_EQ(disc["backgroundInside"].get<int>(), 0) << view.name << disc.dump();
    if (!disc["fillsView"].get<bool>()) {
      EXPECT_NEAR(disc["radiusRatio"].get<double>(), 1.0, 0.01) << view.name << disc.dump();
    }
    std::cout << view.name << ": " << disc.dump() << "\n";
    if (std::string(view.name) == "ground") {
      // Levels 11 and 12 are known to Cesium only from the metadata of level 10's tiles.
      EXPECT_EQ(summary["levelsRequested"].back().get<int>(), 12) << summary["levelsRequested"].dump();
    }
  }
}

// The 3D Tiles set of N37E127 (export --3d-tiles, EGM96), checked as a user of another tool
// would: tileset.json and every subtree against the 3D Tiles 1.1 JSON schemas (ajv), every
// subtree's availability decoded and every content present (validate-3dtiles.mjs), every glTF
// content through the Khronos validator (0 errors, 0 warnings); every content against each of
// the 1.44 million SRTM samples in 3-D, within the geometric error the tile set gives its
// level (verify-tiles.mjs, which shares no code with Tellus), vertices inside their bounding
// regions; and CesiumJS drawing it as a Cesium3DTileset (the globe hidden, unlit, terrain's
// maximumScreenSpaceError of 2) from the five views of the quantized-mesh test: no background
// pixel inside the ellipsoid's outline, the limb within 1 %.
TEST(Ecosystem, Tiles3dSetIsValidWithinItsErrorsAndWholeInCesium) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  const fs::path dir = test::freshTestDir();
  const N37TileSet& set = n37TileSet();  // its store
  const fs::path tiles = dir / "tiles3d";
  const RunResult exported = runTellus(fmt::format("export {} --3d-tiles {} --geoid {}",
                                                   quoted(set.tiles.parent_path() / "n37.tstore"), quoted(tiles),
                                                   quoted(set.geoid)));
  ASSERT_EQ(exported.exitCode, 0) << exported.output;
  std::cout << exported.output;
  const fs::path npmCache = fs::path(TELLUS_BINARY_DIR) / "cesium-check";
  const fs::path scripts = fs::path(TELLUS_SOURCE_DIR) / "scripts/cesium-check";
  const RunResult validated = runShell(fmt::format("TELLUS_NPM_CACHE={} {} {} --gltf --summary {}", quoted(npmCache),
                                                   quoted(scripts / "validate-3dtiles.sh"), quoted(tiles),
                                                   quoted(dir / "validation.json")));
  ASSERT_EQ(validated.exitCode, 0) << validated.output;
  std::ifstream validationFile(dir / "validation.json");
  const nlohmann::json validation = nlohmann::json::parse(validationFile);
  EXPECT_TRUE(validation["ok"].get<bool>()) << validation.dump();
  EXPECT_EQ(validation["contents"].get<int>(), 3554) << validation.dump();
  EXPECT_NE(validated.output.find("glTF validator: 3554 files, 0 errors, 0 warnings"), std::string::npos)
      << validated.output;

  const RunResult verified = runShell(fmt::format("node {} {} --hgt {} --geoid {} --summary {}",
                                                  quoted(scripts / "verify-tiles.mjs"), quoted(tiles), quoted(set.hgt),
                                                  quoted(set.geoid), quoted(dir / "verified.json")));
  ASSERT_EQ(verified.exitCode, 0) << verified.output;
  std::cout << verified.output;
  std::ifstream verifiedFile(dir / "verified.json");
  const nlohmann::json summary = nlohmann::json::parse(verifiedFile);
  ASSERT_EQ(summary["levels"].size(), 13u);
  for (const nlohmann::json& level : summary["levels"]) {
    EXPECT_EQ(level["samples"].get<std::int64_t>(), 1442396) << level.dump();
    EXPECT_LE(level["worstRatio"].get<double>(), 1.0) << level.dump();
    EXPECT_GT(level["worstRatio"].get<double>(), 0.1) << level.dump();
    EXPECT_EQ(level["holes"].get<int>(), 0) << level.dump();
    EXPECT_EQ(level["outsideVolume"].get<int>(), 0) << level.dump();
  }
  // Read as if the set had no geoid, its finest tiles miss by the geoid's 20-odd metres.
  const RunResult withoutGeoid =
      runShell(fmt::format("node {} {} --hgt {}", quoted(scripts / "verify-tiles.mjs"), quoted(tiles), quoted(set.hgt)));
  EXPECT_EQ(withoutGeoid.exitCode, 1) << withoutGeoid.output;
  // With KHR_mesh_quantization: valid, smaller, and still within every level's error.
  const fs::path quantized = dir / "tiles3d-quantized";
  const RunResult packed = runTellus(fmt::format("export {} --3d-tiles {} --geoid {} --quantize",
                                                 quoted(set.tiles.parent_path() / "n37.tstore"), quoted(quantized),
                                                 quoted(set.geoid)));
  ASSERT_EQ(packed.exitCode, 0) << packed.output;
  const RunResult packedValid = runShell(fmt::format("TELLUS_NPM_CACHE={} {} {} --gltf", quoted(npmCache),
                                                     quoted(scripts / "validate-3dtiles.sh"), quoted(quantized)));
  EXPECT_EQ(packedValid.exitCode, 0) << packedValid.output;
  const RunResult packedVerified = runShell(fmt::format("node {} {} --hgt {} --geoid {}", quoted(scripts / "verify-tiles.mjs"),
                                                        quoted(quantized), quoted(set.hgt), quoted(set.geoid)));
  EXPECT_EQ(packedVerified.exitCode, 0) << packedVerified.output;
  const auto bytesOf = [](const fs::path& folder) {
    std::uintmax_t bytes = 0;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder)) {
      if (e.is_regular_file()) bytes += e.file_size();
    }
    return bytes;
  };
  EXPECT_LT(double(bytesOf(quantized)), 0.9 * double(bytesOf(tiles)));

  struct View {
    const char* name;
    const char* camera;
  };
  for (const View& view : {View{"orbit", "127.5 37.5 20000000 0 -90"}, View{"2000km", "127.5 25 2000000 0 -35"},
                           View{"atlantic", "-30 20 2000000 0 -30"},
                           View{"antimeridian", "180 0 20000000 0 -90 --sample 179.5,0.5"},
                           View{"ground", "127.2 37.2 3000 45 -10"}}) {
    const fs::path out = dir / view.name;
    const RunResult viewed = runShell(fmt::format(
        "TELLUS_NPM_CACHE={} {} {} {} {} --globe-disc --param lighting=0 --param sse=2", quoted(npmCache),
        quoted(scripts / "run.sh"), quoted(tiles), quoted(out), view.camera));
    EXPECT_EQ(viewed.exitCode, 0) << view.name << "\n" << viewed.output;
    std::ifstream viewFile(out / "summary.json");
    const nlohmann::json drawn = nlohmann::json::parse(viewFile);
    EXPECT_GT(drawn["tilesRequested"].get<int>(), 0) << view.name;
    EXPECT_EQ(drawn["consoleErrors"].size(), 0u) << view.name << drawn["consoleErrors"].dump();
    const nlohmann::json& disc = drawn["globeDisc"];
    ASSERT_TRUE(disc.is_object()) << view.name << drawn.dump();
    EXPECT_EQ(disc["backgroundInside"].get<int>(), 0) << view.name << disc.dump();
    if (!disc["fillsView"].get<bool>()) {
      EXPECT_NEAR(disc["radiusRatio"].get<double>(), 1.0, 0.01) << view.name << disc.dump();
    }
    std::cout << view.name << ": " << drawn["tilesRequested"] << " glTF tiles, " << disc.dump() << "\n";
  }
}

// --background: beyond N37E127 the ground is ETOPO5's (5', heights above the geoid), so the
// data's edge meets it instead of falling to the geoid. CesiumJS samples the ground 0.02 degrees
// east of the tile (the Taebaek range, about 500 m): with the background it is there; the set
// without one (n37TileSet) has the geoid's 25 m, a cliff of hundreds of metres at the edge.
TEST(Ecosystem, QuantizedMeshMeetsTheBackgroundReliefAtTheDataEdge) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  const fs::path dir = test::freshTestDir();
  const N37TileSet& set = n37TileSet();
  const fs::path etopo = *test::sharedDataDir() / "etopo5-global/etopo5_int16.tif";
  const RunResult exported = runTellus(fmt::format("export {} --quantized-mesh {} --max-level 9 --geoid {} --background {}",
                                                   quoted(set.tiles.parent_path() / "n37.tstore"), quoted(dir / "tiles"),
                                                   quoted(set.geoid), quoted(etopo)));
  ASSERT_EQ(exported.exitCode, 0) << exported.output;
  const auto heightEastOfTheData = [&](const fs::path& tiles, const std::string& name) {
    const RunResult viewed = runShell(fmt::format(
        "TELLUS_NPM_CACHE={} {} {} {} 128.5 36.7 30000 300 -15 --sample 128.02,37.5",
        quoted(fs::path(TELLUS_BINARY_DIR) / "cesium-check"),
        quoted(fs::path(TELLUS_SOURCE_DIR) / "scripts/cesium-check/run.sh"), quoted(tiles), quoted(dir / name)));
    EXPECT_EQ(viewed.exitCode, 0) << viewed.output;
    std::ifstream summaryFile(dir / name / "summary.json");
    return nlohmann::json::parse(summaryFile)["sampledHeights"][0]["height"].get<double>();
  };
  const double withBackground = heightEastOfTheData(dir / "tiles", "with");
  const double withoutBackground = heightEastOfTheData(set.tiles, "without");
  std::cout << "128.02 E, 37.5 N: " << withBackground << " m with ETOPO5 beyond the data, " << withoutBackground
            << " m without\n";
  EXPECT_GT(withBackground, 300.0);
  EXPECT_LT(withoutBackground, 60.0);
  // Refused without a tile set to make.
  const RunResult misplaced = runTellus(fmt::format("export {} -o {} --background {}",
                                                    quoted(set.tiles.parent_path() / "n37.tstore"),
                                                    quoted(dir / "x.tif"), quoted(etopo)));
  EXPECT_NE(misplaced.exitCode, 0);
  EXPECT_NE(misplaced.output.find("--background apply to --quantized-mesh and --3d-tiles"), std::string::npos)
      << misplaced.output;
}

// The watermask extension from NASA's BlueMarbleWater.jpg: layer.json names it, a tile of the
// open Pacific is one byte of water, a tile over Korea's west coast a 256 x 256 mask with both
// land and (coastal, grey) water, and CesiumJS asking for it (requestWaterMask) loads the set without an
// error. A colour image is refused as a mask, and --water without --quantized-mesh.
TEST(Ecosystem, QuantizedMeshCarriesTheWaterMask) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  const fs::path dir = test::freshTestDir();
  const fs::path data = *test::sharedDataDir();
  const fs::path water = data / "bluemarble8k-global/BlueMarbleWater.jpg";
  ASSERT_EQ(runTellus(fmt::format("build {} -o {}", quoted(data / "srtm3-hgt-east-asia/N37E127.hgt"),
                                  quoted(dir / "n37.tstore")))
                .exitCode,
            0);
  const RunResult exported = runTellus(fmt::format("export {} --quantized-mesh {} --max-level 8 --water {}",
                                                   quoted(dir / "n37.tstore"), quoted(dir / "tiles"), quoted(water)));
  ASSERT_EQ(exported.exitCode, 0) << exported.output;
  std::ifstream layerFile(dir / "tiles/layer.json");
  const nlohmann::json layer = nlohmann::json::parse(layerFile);
  EXPECT_EQ(layer["extensions"], nlohmann::json({"octvertexnormals", "watermask"}));
  auto maskOf = [&](const char* tile) {
    const std::string bytes = test::readFileBytes(dir / "tiles" / tile);
    Result<QuantizedMeshTile> decoded = decodeQuantizedMesh(std::as_bytes(std::span(bytes)), tile);
    EXPECT_TRUE(decoded) << tile;
    return decoded ? decoded->waterMask : std::vector<std::uint8_t>{};
  };
  // Level 5, x 5, y 16: 151.875..146.25 W, 0..5.625 N, open ocean.
  EXPECT_EQ(maskOf("5/5/16.terrain"), std::vector<std::uint8_t>{255});
  // Level 8, x 436, y 180: 126.56..127.27 E, 36.56..37.27 N, Asan Bay on the Yellow Sea.
  const std::vector<std::uint8_t> coast = maskOf("8/436/180.terrain");
  ASSERT_EQ(coast.size(), 65536u);
  EXPECT_NE(std::find(coast.begin(), coast.end(), 0), coast.end());
  EXPECT_GT(*std::max_element(coast.begin(), coast.end()), 128);  // coastal water is grey in it
  // CesiumJS asking for the extension.
  const RunResult viewed = runShell(fmt::format(
      "TELLUS_NPM_CACHE={} {} {} {} 126.8 36.4 200000 0 -60 --param water=1",
      quoted(fs::path(TELLUS_BINARY_DIR) / "cesium-check"),
      quoted(fs::path(TELLUS_SOURCE_DIR) / "scripts/cesium-check/run.sh"), quoted(dir / "tiles"), quoted(dir / "cesium")));
  EXPECT_EQ(viewed.exitCode, 0) << viewed.output;
  // Refusals.
  const RunResult colour = runTellus(fmt::format("export {} --quantized-mesh {} --water {}", quoted(dir / "n37.tstore"),
                                                 quoted(dir / "t2"), quoted(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg")));
  EXPECT_NE(colour.exitCode, 0);
  EXPECT_NE(colour.output.find("a water mask is one band"), std::string::npos) << colour.output;
  const RunResult misplaced = runTellus(fmt::format("export {} -o {} --water {}", quoted(dir / "n37.tstore"),
                                                    quoted(dir / "x.tif"), quoted(water)));
  EXPECT_NE(misplaced.exitCode, 0);
  EXPECT_NE(misplaced.output.find("apply to --quantized-mesh"), std::string::npos) << misplaced.output;
  const RunResult misplacedMetadata = runTellus(fmt::format("export {} -o {} --metadata-levels 5",
                                                            quoted(dir / "n37.tstore"), quoted(dir / "x.tif")));
  EXPECT_NE(misplacedMetadata.exitCode, 0);
  EXPECT_NE(misplacedMetadata.output.find("apply to --quantized-mesh"), std::string::npos) << misplacedMetadata.output;
  EXPECT_FALSE(fs::exists(dir / "t2"));
  EXPECT_FALSE(fs::exists(dir / "x.tif"));
}

TEST(Ecosystem, CommandsReadAStoreOverHttp) {
  if (!test::sharedDataDir()) GTEST_SKIP() << "no ../shared/data";
  std::string why;
  std::optional<test::LocalHttpServer> server = test::LocalHttpServer::start(koreaStore().parent_path(), why);
  ASSERT_TRUE(server) << why;
  const RunResult info = runTellus("info " + server->url("korea.tstore"));
  ASSERT_EQ(info.exitCode, 0) << info.output;
  EXPECT_NE(info.output.find("4801 x 4801"), std::string::npos) << info.output;
  const fs::path dir = test::freshTestDir();
  const RunResult remote = runTellus(fmt::format("render {} --algo rings --size 320x180 -o {}",
                                                 server->url("korea.tstore"), quoted(dir / "remote.png")));
  ASSERT_EQ(remote.exitCode, 0) << remote.output;
  const RunResult local = runTellus(fmt::format("render {} --algo rings --size 320x180 -o {}",
                                                quoted(koreaStore()), quoted(dir / "local.png")));
  ASSERT_EQ(local.exitCode, 0) << local.output;
  EXPECT_EQ(test::readFileBytes(dir / "remote.png"), test::readFileBytes(dir / "local.png"));
  const RunResult missing = runTellus("info " + server->url("missing.tstore"));
  EXPECT_NE(missing.exitCode, 0);
  EXPECT_NE(missing.output.find("HTTP 404"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace tellus
