// `tellus generate --srtm-tiles` (issue 47's planet-scale input data): the planet's land in a box
// as SRTM3 tiles that Tellus (and GDAL) read as SRTM, the work announced before it starts, the
// same bytes for the same seed, and a folder that is not empty refused (it never replaces files).
#include <fstream>

#include <gtest/gtest.h>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

std::vector<std::string> hgtFilesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(PlanetTilesCli, GeneratesSrtmTilesOfTheLandInABox) {
  const fs::path dir = test::freshTestDir();
  // A box on the coast of a continent of the planet of seed 3: land and open sea tiles.
  const std::string box = "--srtm-tiles 0,31,3,33 --seed 3 --relief 9000 --srtm-detail 1";
  const RunResult first = runTellus(fmt::format("generate {} -o {}", box, quoted(dir / "a")));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  EXPECT_NE(first.output.find("4 tiles with land of 6 in 0..3 E, 31..33 N"), std::string::npos) << first.output;
  const std::vector<std::string> tiles = hgtFilesIn(dir / "a");
  ASSERT_FALSE(tiles.empty());
  ASSERT_EQ(tiles.size(), 4u) << "open sea tiles are left out";
  for (const std::string& name : tiles) {
    EXPECT_TRUE(name.size() == 11 && name.ends_with(".hgt") && name[0] == 'N') << name;
    EXPECT_EQ(fs::file_size(dir / "a" / name), 1201u * 1201u * 2u) << name;
  }
  // Tellus reads them as SRTM (their georeferencing from the names) and builds a store of them.
  std::string inputs;
  for (const std::string& name : tiles) inputs += fmt::format(" {}", quoted(dir / "a" / name));
  const RunResult info = runTellus(fmt::format("info{}", inputs));
  ASSERT_EQ(info.exitCode, 0) << info.output;
  // (One tile: the open sea missing from the mosaic would be filled as voids, a minute's work.)
  const RunResult built =
      runTellus(fmt::format("build {} -o {}", quoted(dir / "a" / tiles.front()), quoted(dir / "tile.tstore")));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  // The same seed, the same bytes.
  const RunResult second = runTellus(fmt::format("generate {} -o {}", box, quoted(dir / "b")));
  ASSERT_EQ(second.exitCode, 0) << second.output;
  ASSERT_EQ(hgtFilesIn(dir / "b"), tiles);
  for (const std::string& name : tiles) {
    std::ifstream a(dir / "a" / name, std::ios::binary), b(dir / "b" / name, std::ios::binary);
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), {}, std::istreambuf_iterator<char>(b), {})) << name;
  }
  // A folder that is not empty, and boxes that mean nothing, are refused before any work.
  const RunResult again = runTellus(fmt::format("generate {} -o {}", box, quoted(dir / "a")));
  EXPECT_NE(again.exitCode, 0);
  EXPECT_NE(again.output.find("is not empty"), std::string::npos) << again.output;
  for (const char* bad : {"12,33,15,31", "12.5,31,15,33", "170,31,190,33", "1,2,3"}) {
    const RunResult r = runTellus(fmt::format("generate --srtm-tiles {} -o {}", bad, quoted(dir / "c")));
    EXPECT_NE(r.exitCode, 0) << bad;
    EXPECT_NE(r.output.find("--srtm-tiles"), std::string::npos) << bad << ": " << r.output;
    EXPECT_FALSE(fs::exists(dir / "c")) << bad;
  }
}

}  // namespace
}  // namespace tellus
