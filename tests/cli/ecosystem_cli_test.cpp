// Tellus in its ecosystem, end to end: the installed package (cmake --install, pkg-config, the
// .deb) builds and runs the embedding example out of tree; `tellus export --gltf` and
// `--quantized-mesh` on the real Korea mosaic, the tile set loaded by CesiumJS in headless
// Chromium from a local lighttpd; stores read over http://; bad arguments refused.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_tellus.hpp"
#include "support/http_server.hpp"
#include "support/test_support.hpp"

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
  EXPECT_TRUE(fs::exists(prefix / "include/tellus/render/rings/rings_renderer.hpp"));
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
  EXPECT_NE(exported.output.find("max vertical error"), std::string::npos) << exported.output;
  EXPECT_TRUE(fs::exists(dir / "jirisan.glb"));
  // Nonsense is refused with the reason, nothing written.
  for (const std::string& args :
       {fmt::format("export {} --gltf {} -o {}", quoted(koreaStore()), quoted(dir / "a.glb"), quoted(dir / "a.tif")),
        fmt::format("export {} --quantized-mesh {} --region 127,35,128,36", quoted(koreaStore()), quoted(dir / "q")),
        fmt::format("export {} --gltf {} --max-error -1", quoted(koreaStore()), quoted(dir / "b.glb")),
        fmt::format("export {} --gltf {} --region 10,10,11,11", quoted(koreaStore()), quoted(dir / "c.glb")),
        fmt::format("export {} --gltf {}", quoted(test::koreaMosaicTiles(*test::sharedDataDir())[0]), quoted(dir / "d.glb"))}) {
    const RunResult refused = runTellus(args);
    EXPECT_NE(refused.exitCode, 0) << args << "\n" << refused.output;
    EXPECT_FALSE(refused.output.empty()) << args;  // the reason
  }
  for (const char* name : {"a.glb", "a.tif", "b.glb", "c.glb", "d.glb"}) EXPECT_FALSE(fs::exists(dir / name)) << name;
  EXPECT_FALSE(fs::exists(dir / "q"));
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
