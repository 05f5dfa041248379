#pragma once
// Helpers shared by the test suites: where the real DEMs and golden images are, temporary
// folders, image statistics.
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "tellus/core/rgb_image.hpp"

namespace tellus::test {

// ../shared/data (or $TELLUS_DATA_DIR), or nullopt when it is absent.
std::optional<std::filesystem::path> sharedDataDir();

// Skips the current test with a message when ../shared/data is absent.
#define TELLUS_REQUIRE_SHARED_DATA(var)                                                    \
  const std::optional<std::filesystem::path> var##Opt = ::tellus::test::sharedDataDir();   \
  if (!var##Opt) GTEST_SKIP() << "../shared/data is absent: skipping a test on real DEMs"; \
  const std::filesystem::path& var = *var##Opt

// The 16 SRTM tiles of the Korea 4x4 mosaic (N34..N37, E126..E129).
std::vector<std::filesystem::path> koreaMosaicTiles(const std::filesystem::path& dataDir);

// A fresh empty folder under the build tree, named after the running test.
std::filesystem::path freshTestDir();

// A fresh empty folder of this test process's own, `name` plus the process id, under the build
// tree: for fixtures a suite or file builds once and its tests share. ctest runs every test as a
// process of its own and `make test` runs several at once, so a fixture folder shared by name
// alone would be rebuilt under another test's feet. The folder is removed when the process exits.
std::filesystem::path processFixtureDir(const std::string& name);

// FFmpeg's own prober on a video file: its first video stream's codec_name, width, height,
// pix_fmt and nb_read_frames (every frame decoded and counted), the container's duration and
// format_name, as key -> value; anything else ffprobe said, or its failure, under "error".
std::map<std::string, std::string> probeVideo(const std::filesystem::path& file);

// A file's whole contents (empty when it cannot be read).
std::string readFileBytes(const std::filesystem::path& file);

// Where test images are written for inspection (build tree).
std::filesystem::path testOutputDir();

// Pixels that differ from `background` by more than `tolerance` in some channel.
struct ForegroundStats {
  double fraction = 0.0;   // of all pixels
  double centroidX = 0.0;  // pixels, over foreground pixels
  double centroidY = 0.0;
  int minX = 0, maxX = 0, minY = 0, maxY = 0;  // bounding box
};
ForegroundStats foregroundStats(const RgbImage& image, const unsigned char background[3],
                                int tolerance = 6);

// Standard deviation of the luminance over the image, 0..255.
double luminanceStdDev(const RgbImage& image);

// Mean absolute difference of two images of one size over columns [x0, x1) (x1 < 0: to the
// right edge), per channel, 0..255.
double meanDifference(const RgbImage& a, const RgbImage& b, int x0 = 0, int x1 = -1);

}  // namespace tellus::test
