// tellus view end to end under Xvfb on a real DEM: it replays a keyframe path, records the
// flight to a keyframe JSON that tellus bench replays, and its screenshot is exactly the frame
// tellus render draws from the path's last camera; with the panel shown, only the panel's
// corner differs. Bad arguments fail before a window opens, with a message.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "run_tellus.hpp"
#include "support/test_support.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/eval/camera_path.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

using test::meanDifference;

class ViewCli : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  }
};

TEST_F(ViewCli, ReplaysAPathRecordsItAndScreenshotsTheFrame) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path store = dir / "n37e127.tstore";
  ASSERT_EQ(
      runTellus(fmt::format("-q build {} -o {} --tile 64",
                            quoted(data / "srtm3-hgt-east-asia" / "N37E127.hgt"), quoted(store)))
          .exitCode,
      0);
  // A short flight north-east over the tile (88 x 111 km), descending.
  std::ofstream(dir / "flight.json") << R"({"keyframes": [
    {"time": 0, "position": [20000, 20000, 3000], "yaw": 45, "pitch": -20, "fov": 55},
    {"time": 4, "position": [45000, 50000, 2500], "yaw": 60, "pitch": -15, "fov": 55},
    {"time": 8, "position": [60000, 80000, 2200], "yaw": 30, "pitch": -12, "fov": 55}]})";

  const std::string common = fmt::format("{} --path {} --frames 8 --wait-tiles --size 480x270",
                                         quoted(store), quoted(dir / "flight.json"));
  const RunResult bare = runViewUnderXvfb(
      common + fmt::format(" --no-panel --record {} --screenshot {}", quoted(dir / "recorded.json"),
                           quoted(dir / "bare.png")));
  ASSERT_EQ(bare.exitCode, 0) << bare.output;

  // The screenshot is the frame tellus render draws from the path's last camera.
  ASSERT_EQ(runTellus(fmt::format("-q render {} --algo rings --size 480x270 --camera "
                                  "60000,80000,2200,30,-12,55 -o {}",
                                  quoted(store), quoted(dir / "render.png")))
                .exitCode,
            0);
  Result<RgbImage> shot = readPng(dir / "bare.png"), still = readPng(dir / "render.png");
  ASSERT_TRUE(shot && still);
  ASSERT_EQ(shot->width, 480);
  ASSERT_EQ(shot->height, 270);
  EXPECT_GT(test::luminanceStdDev(*shot), 8.0);
  EXPECT_EQ(shot->pixels, still->pixels);

  // The recording holds the 8 cameras of the replay, over the path's 8 seconds ...
  Result<CameraPath> recorded = loadCameraPath(dir / "recorded.json");
  ASSERT_TRUE(recorded) << recorded.error().message;
  ASSERT_EQ(recorded->keyframes().size(), 8u);
  EXPECT_DOUBLE_EQ(recorded->durationS(), 8.0);
  const Camera last = recorded->keyframes().back().camera;
  EXPECT_NEAR(last.position.x, 60000.0, 1e-6);
  EXPECT_NEAR(last.position.y, 80000.0, 1e-6);
  EXPECT_NEAR(last.yawDeg, 30.0, 1e-9);
  // ... and tellus bench replays it.
  const RunResult bench =
      runTellus(fmt::format("bench {} --algo rings --path {} --frames 4 "
                            "--size 160x90 --warmup 0",
                            quoted(store), quoted(dir / "recorded.json")));
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  EXPECT_NE(bench.output.find("rings"), std::string::npos) << bench.output;

  // With the panel: the panel covers the top-left, the rest of the frame is unchanged.
  const RunResult panel = runViewUnderXvfb(common + " --screenshot " + quoted(dir / "panel.png"));
  ASSERT_EQ(panel.exitCode, 0) << panel.output;
  Result<RgbImage> withPanel = readPng(dir / "panel.png");
  ASSERT_TRUE(withPanel);
  EXPECT_GT(meanDifference(*withPanel, *shot, 20, 300), 20.0);
  EXPECT_EQ(meanDifference(*withPanel, *shot, 400, 480), 0.0);
}

// On the globe: the viewer replays a globe path (a walk on the SRTM tile) and its last frame is
// the frame tellus render draws from that camera (as tellus bench reports it); what it records
// is a lat/lon keyframe file that tellus bench replays.
TEST_F(ViewCli, ReplaysAGlobePathAsRenderDrawsIt) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string hgt = quoted(data / "srtm3-hgt-east-asia" / "N37E127.hgt");
  const std::string path = "--algo globe-reference --path walk --target 37.49,127.53 --frames 3";
  const RunResult bench = runTellus(fmt::format("bench {} {} --warmup 0 --size 64x36 --json {}",
                                                hgt, path, quoted(dir / "walk.json")));
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  std::ifstream in(dir / "walk.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const std::string last =
      report.at("algorithms").at(0).at("frames").at(2).at("geo_camera").get<std::string>();

  const RunResult view = runViewUnderXvfb(
      fmt::format("{} {} --no-panel --size 320x180 --screenshot {} --record {}", hgt, path,
                  quoted(dir / "view.png"), quoted(dir / "recorded.json")));
  ASSERT_EQ(view.exitCode, 0) << view.output;
  // The recording is a lat/lon keyframe file ending on the last camera of the replay ...
  std::ifstream recordedFile(dir / "recorded.json");
  const nlohmann::json recorded = nlohmann::json::parse(recordedFile);
  const nlohmann::json& keyframes = recorded.at("keyframes");
  ASSERT_GE(keyframes.size(), 2u);
  const nlohmann::json& end = keyframes.back();
  EXPECT_EQ(fmt::format("{:.6f},{:.6f}", end.at("lat").get<double>(), end.at("lon").get<double>()),
            last.substr(0, last.find(',', last.find(',') + 1)));
  // ... that tellus bench replays.
  const RunResult replay = runTellus(
      fmt::format("bench {} --algo globe-reference --path {} --frames 3 --warmup 0 --size 64x36",
                  hgt, quoted(dir / "recorded.json")));
  EXPECT_EQ(replay.exitCode, 0) << replay.output;
  ASSERT_EQ(runTellus(fmt::format("-q render {} --algo globe-reference --size 320x180 "
                                  "--geo-camera {} -o {}",
                                  hgt, last, quoted(dir / "render.png")))
                .exitCode,
            0);
  Result<RgbImage> shot = readPng(dir / "view.png"), still = readPng(dir / "render.png");
  ASSERT_TRUE(shot && still);
  EXPECT_GT(test::luminanceStdDev(*shot), 3.0) << "sky and hills";
  // The camera string rounds to 0.1 m and the clip planes differ (render takes its near plane
  // from the highest terrain): nearly, not exactly, the same pixels.
  EXPECT_LT(meanDifference(*shot, *still, 0, 320), 2.0);
}

TEST(ViewCliArguments, BadArgumentsFailWithAMessageBeforeAWindowOpens) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const std::string hgt = quoted(data / "srtm3-hgt-east-asia" / "N37E127.hgt");
  const struct {
    std::string arguments, expected;
  } cases[] = {
      {"view " + hgt + " --screenshot out.png", "--frames"},
      {"view " + hgt + " --algo rings --frames 1", "streams from a tile store"},
      {"view " + hgt + " --geo-camera 37,127,1000,0,0,60 --frames 1", "are for globe renderers"},
      {"view " + hgt + " --algo globe-reference --camera 1,2,3 --frames 1",
       "give --geo-camera"},
      {"view " + hgt + " --path " + quoted(dir / "missing.json") + " --frames 1", "missing.json"},
      {"view " + hgt + " --camera 1,2,3 --frames 1", "camera"},
      {"view " + hgt + " --shading glossy", "glossy"},
  };
  for (const auto& c : cases) {
    const RunResult result = runTellus(c.arguments);
    EXPECT_NE(result.exitCode, 0) << c.arguments;
    EXPECT_NE(result.output.find(c.expected), std::string::npos) << c.arguments << "\n"
                                                                 << result.output;
  }
  // No display at all: a clear error, not a crash.
  const RunResult noDisplay = runShell(fmt::format(
      "env -u DISPLAY -u WAYLAND_DISPLAY '{}' view {} --frames 1", TELLUS_EXECUTABLE, hgt));
  EXPECT_EQ(noDisplay.exitCode, 1) << noDisplay.output;
  EXPECT_NE(noDisplay.output.find("window"), std::string::npos) << noDisplay.output;
}

// A .tstack opens with stacks-full (its default) and the panel shows the pipeline's parameters;
// the screenshot is the still tellus render draws from the same camera.
TEST_F(ViewCli, DrawsAStackTerrain) {
  const fs::path dir = test::freshTestDir();
  const fs::path dem = dir / "steep.tif", stacks = dir / "steep.tstack";
  ASSERT_EQ(runTellus(fmt::format("-q generate --size 97 --spacing 2 --relief 3000 --seed 5 -o {}", quoted(dem))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("-q stacks build {} -o {}", quoted(dem), quoted(stacks))).exitCode, 0);
  const std::string camera = "--camera 96,-80,140,0,-20,55";
  const RunResult viewed = runViewUnderXvfb(fmt::format("{} {} --algo stacks-full --frames 2 --size 320x200 --no-panel --screenshot {}",
                                                        quoted(stacks), camera, quoted(dir / "view.png")));
  ASSERT_EQ(viewed.exitCode, 0) << viewed.output;
  ASSERT_EQ(runTellus(fmt::format("-q render {} {} --size 320x200 -o {}", quoted(stacks), camera,
                                  quoted(dir / "render.png"))).exitCode, 0);
  Result<RgbImage> shot = readPng(dir / "view.png"), still = readPng(dir / "render.png");
  ASSERT_TRUE(shot && still);
  EXPECT_GT(test::luminanceStdDev(*shot), 5.0);
  EXPECT_LT(meanDifference(*shot, *still), 1.0);
  // With the panel: it opens, and a heightfield renderer is refused for the stacks.
  const RunResult panel = runViewUnderXvfb(fmt::format("{} --frames 1 --size 640x400", quoted(stacks)));
  EXPECT_EQ(panel.exitCode, 0) << panel.output;
  const RunResult refused = runTellus(fmt::format("view {} --algo rag --frames 1", quoted(stacks)));
  EXPECT_NE(refused.exitCode, 0);
  EXPECT_NE(refused.output.find("holds material stacks"), std::string::npos) << refused.output;
}

TEST_F(ViewCli, BrushStrokesEditTheStacksAndSaveThemAsTheEditCommandDoes) {
  const fs::path dir = test::freshTestDir();
  const fs::path dem = dir / "steep.tif", viewed = dir / "viewed.tstack", edited = dir / "edited.tstack";
  ASSERT_EQ(runTellus(fmt::format("-q generate --size 97 --spacing 2 --relief 3000 --seed 5 -o {}", quoted(dem))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("-q stacks build {} -o {}", quoted(dem), quoted(viewed))).exitCode, 0);
  fs::copy_file(viewed, edited);
  // Two strokes through the octree renderer, saved at exit...
  const std::string camera = "--camera 96,-80,140,0,-20,55";
  const RunResult view = runViewUnderXvfb(fmt::format(
      "{} {} --frames 3 --size 320x200 --no-panel --stack-edit 1:90,90,40,12:remove "
      "--stack-edit 2:60,120,45,8:soil --save-stack-edits --screenshot {}",
      quoted(viewed), camera, quoted(dir / "edited.png")));
  ASSERT_EQ(view.exitCode, 0) << view.output;
  // ... write the file tellus stacks edit writes for the same strokes.
  ASSERT_EQ(runTellus(fmt::format("-q stacks edit {} --sphere 90,90,40,12 --remove", quoted(edited))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("-q stacks edit {} --sphere 60,120,45,8 --add soil", quoted(edited))).exitCode, 0);
  EXPECT_EQ(test::readFileBytes(viewed), test::readFileBytes(edited));
  // The stroke shows: the edited frame is not the unedited one, and matches the ground truth
  // of the edited stacks.
  ASSERT_EQ(runTellus(fmt::format("-q render {} {} --size 320x200 -o {}", quoted(edited), camera,
                                  quoted(dir / "truth.png"))).exitCode, 0);
  Result<RgbImage> shot = readPng(dir / "edited.png"), truth = readPng(dir / "truth.png");
  ASSERT_TRUE(shot && truth);
  EXPECT_LT(meanDifference(*shot, *truth), 6.0);
  // Bad strokes are refused before the window opens.
  for (const char* bad : {"1:90,90,40:remove", "x:90,90,40,5:rock", "1:90,90,40,5:lava", "1:90,90,40,5"}) {
    const RunResult refused = runTellus(fmt::format("view {} --frames 1 --stack-edit {}", quoted(viewed), bad));
    EXPECT_NE(refused.exitCode, 0) << bad;
    EXPECT_NE(refused.output.find("--stack-edit"), std::string::npos) << refused.output;
  }
}

}  // namespace
}  // namespace tellus
