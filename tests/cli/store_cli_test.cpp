// End-to-end tests of the data pipeline commands: build, info, verify, export and render on
// stores built from the real DEMs; corrupted and interrupted stores; bad arguments.
#include <fstream>

#include <gtest/gtest.h>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

fs::path n37e127(const fs::path& data) {
  return data / "srtm3-hgt-east-asia/N37E127.hgt";
}

TEST(StoreCli, BuildInfoVerifyExportRender) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "n37e127.tstore";
  RunResult built = runTellus(fmt::format("build {} -o {} --codec bounded --max-error 2 --tile 128",
                                          quoted(n37e127(data)), quoted(store)));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  EXPECT_NE(built.output.find("5 levels"), std::string::npos) << built.output;

  const RunResult info = runTellus(fmt::format("info {}", quoted(store)));
  ASSERT_EQ(info.exitCode, 0) << info.output;
  for (const char* part : {"1201 x 1201 samples", "bounded (max error 2 m)", "WGS 84", "5 levels",
                           "bits/sample", "10x10"}) {
    EXPECT_NE(info.output.find(part), std::string::npos) << part << " missing from:\n"
                                                         << info.output;
  }
  const RunResult verified = runTellus(fmt::format("verify {}", quoted(store)));
  EXPECT_EQ(verified.exitCode, 0) << verified.output;
  EXPECT_NE(verified.output.find("all 139 tiles good"), std::string::npos) << verified.output;

  const fs::path tif = dir / "level1.tif";
  ASSERT_EQ(
      runTellus(fmt::format("export {} -o {} --level 1", quoted(store), quoted(tif))).exitCode, 0);
  Result<HeightGrid> exported = loadDem({tif});
  ASSERT_TRUE(exported) << exported.error().message;
  EXPECT_EQ(exported->width, 601);
  EXPECT_NEAR(exported->spacingXM, 2 * 73.69, 0.5);  // GDAL reads back the georeferencing

  const fs::path png = dir / "store.png";
  const RunResult rendered = runTellus(
      fmt::format("render {} -o {} --level 1 --size 320x200", quoted(store), quoted(png)));
  EXPECT_EQ(rendered.exitCode, 0) << rendered.output;
  EXPECT_TRUE(fs::exists(png));
}

void flipByte(const fs::path& path, std::uint64_t offset) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(std::streamoff(offset));
  char c = 0;
  file.get(c);
  file.seekp(std::streamoff(offset));
  file.put(char(c ^ 0x40));
}

TEST(StoreCli, VerifyNamesCorruptTilesAndRejectsTruncatedStores) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "s.tstore";
  ASSERT_EQ(
      runTellus(fmt::format("build {} -o {} --tile 128", quoted(n37e127(data)), quoted(store)))
          .exitCode,
      0);
  std::uint64_t offsetA = 0, offsetB = 0;
  {
    Result<std::shared_ptr<TileStore>> opened = TileStore::open(store);
    ASSERT_TRUE(opened);
    offsetA = opened.value()->find({0, 4, 7})->payloadOffset + 10;
    offsetB = opened.value()->find({2, 1, 0})->payloadOffset + 3;
  }
  fs::copy_file(store, dir / "corrupt.tstore");
  flipByte(dir / "corrupt.tstore", offsetA);
  flipByte(dir / "corrupt.tstore", offsetB);
  const RunResult verified = runTellus(fmt::format("verify {}", quoted(dir / "corrupt.tstore")));
  EXPECT_EQ(verified.exitCode, 1);
  EXPECT_NE(verified.output.find("tile 0/4/7"), std::string::npos) << verified.output;
  EXPECT_NE(verified.output.find("tile 2/1/0"), std::string::npos) << verified.output;
  EXPECT_NE(verified.output.find("2 of 139 tiles are bad"), std::string::npos) << verified.output;
  // Rendering the corrupt level fails with the tile's name instead of drawing garbage.
  const RunResult render = runTellus(fmt::format(
      "render {} -o {} --size 64x64", quoted(dir / "corrupt.tstore"), quoted(dir / "x.png")));
  EXPECT_NE(render.exitCode, 0);
  EXPECT_NE(render.output.find("tile 0/4/7"), std::string::npos) << render.output;
  EXPECT_FALSE(fs::exists(dir / "x.png"));

  fs::copy_file(store, dir / "short.tstore");
  fs::resize_file(dir / "short.tstore", fs::file_size(store) - 100);
  const RunResult truncated = runTellus(fmt::format("verify {}", quoted(dir / "short.tstore")));
  EXPECT_NE(truncated.exitCode, 0);
  EXPECT_NE(truncated.output.find("truncated"), std::string::npos) << truncated.output;
}

// SIGKILL a build once it has started writing: the destination keeps the previous valid store
// (or does not exist), and the next build removes the dead build's temporary file.
TEST(StoreCli, AKilledBuildLeavesNoCorruptStore) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "korea.tstore";
  const std::string slowBuild = fmt::format("'{}' build {} -o {} --codec bounded --tile 128",
                                            TELLUS_EXECUTABLE, koreaArguments(data), quoted(store));
  // Start, wait until the temporary store exists and has tiles, kill -9.
  const std::string killMidway = fmt::format(
      "cd {} && ({} >/dev/null 2>&1 & pid=$!; "
      "for i in $(seq 200); do f=$(ls -A | grep '^.korea.tstore.tellus-partial-' | head -1); "
      "[ -n \"$f\" ] && [ $(stat -c %s \"$f\") -gt 200000 ] && echo writing && break; "
      "sleep 0.02; done; kill -9 $pid && echo killed; wait $pid)",
      quoted(dir), slowBuild);
  RunResult killed = runShell(killMidway);
  ASSERT_NE(killed.output.find("writing\nkilled"), std::string::npos)
      << "the build was not killed while writing:\n"
      << killed.output;
  EXPECT_FALSE(fs::exists(store)) << "a killed first build must leave no store";

  // A complete build; then kill a rebuild of the same store: the first one stays valid.
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --tile 256", koreaArguments(data), quoted(store)))
                .exitCode,
            0);
  const auto before = fs::file_size(store);
  killed = runShell(killMidway);
  ASSERT_NE(killed.output.find("writing\nkilled"), std::string::npos) << killed.output;
  EXPECT_EQ(fs::file_size(store), before);
  EXPECT_EQ(runTellus(fmt::format("verify {}", quoted(store))).exitCode, 0);

  // The dead builds' temporaries are removed by the next build.
  ASSERT_EQ(
      runTellus(fmt::format("build {} -o {} --tile 128", quoted(n37e127(data)), quoted(store)))
          .exitCode,
      0);
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir))
    left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"korea.tstore"});
}

TEST(StoreCli, BadArgumentsFailCleanly) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string input = quoted(n37e127(data));
  const fs::path store = dir / "ok.tstore";
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --tile 256", input, quoted(store))).exitCode, 0);
  const fs::path out = dir / "out.tstore";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("build {} -o {} --codec gzip", input, quoted(out)), "unknown codec 'gzip'"},
      {fmt::format("build {} -o {} --max-error 1", input, quoted(out)), "lossy codecs"},
      {fmt::format("build {} -o {} --tile 100", input, quoted(out)), "power of two"},
      {fmt::format("build {} -o {} --tile 16", koreaArguments(data), quoted(out)),
       "use --tile 128 or larger"},
      {fmt::format("build {} -o {}", quoted(store), quoted(out)), "already a tile store"},
      {fmt::format("build {} -o {}/nowhere/x.tstore", input, dir.string()), "does not exist"},
      {fmt::format("verify {}", input), "not a tile store"},
      {fmt::format("export {} -o {} --level 9", quoted(store), quoted(dir / "x.tif")),
       "level 9 does not exist"},
      {fmt::format("render {} -o {} --level 7", quoted(store), quoted(dir / "x.png")),
       "level 7 does not exist"},
  };
  for (const auto& [arguments, message] : cases) {
    const RunResult result = runTellus(arguments);
    EXPECT_NE(result.exitCode, 0) << arguments;
    EXPECT_NE(result.output.find(message), std::string::npos) << arguments << ":\n"
                                                              << result.output;
  }
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir))
    left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"ok.tstore"});
}

TEST(StoreCli, BenchCodecsWritesTheJsonTable) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const RunResult result = runTellus(fmt::format("bench codecs {} --json {} --repeat 1",
                                                 quoted(n37e127(data)), quoted(dir / "c.json")));
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::ifstream in(dir / "c.json");
  const std::string json{std::istreambuf_iterator<char>(in), {}};
  for (const char* part :
       {"\"bits_per_sample\"", "\"decode_msamples_per_s\"", "\"gdal-zstd-pred2\"",
        "\"bounded (1 m)\"", "\"rmse_m\"", "\"machine\""}) {
    EXPECT_NE(json.find(part), std::string::npos) << part;
  }
  EXPECT_NE(result.output.find("gdal-deflate-pred2"), std::string::npos);
}

}  // namespace
}  // namespace tellus
