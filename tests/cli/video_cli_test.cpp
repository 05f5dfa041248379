// Flights as video (issue 46): `tellus render --path P --video F` and `tellus bench ... --video
// F`, each file read back by FFmpeg's own prober (ffprobe: codec, size, frame count, duration);
// bad requests refused before anything is drawn, with nothing left behind.
#include <fstream>

#include <gtest/gtest.h>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

// A generated mountain range (no shared data needed).
fs::path generatedTerrain(const fs::path& dir) {
  const fs::path tif = dir / "range.tif";
  const RunResult made = runTellus(fmt::format("generate -o {} --size 257 --relief 1500 --seed 3", quoted(tif)));
  EXPECT_EQ(made.exitCode, 0) << made.output;
  return tif;
}

TEST(VideoCli, RenderFliesAPathIntoAnMp4AtThePathsTiming) {
  const fs::path dir = test::freshTestDir();
  const fs::path tif = generatedTerrain(dir);
  // A keyframe path of 2 seconds: 12 frames are 11 intervals of 2/11 s.
  const fs::path path = dir / "path.json";
  std::ofstream(path) << R"({"keyframes": [
    {"time": 0, "position": [2000, 2000, 3000], "yaw": 45, "pitch": -20, "fov": 60},
    {"time": 2, "position": [5000, 5000, 2500], "yaw": 60, "pitch": -15, "fov": 60}]})";
  const fs::path video = dir / "flight.mp4";
  const RunResult r = runTellus(fmt::format("render {} --path {} --frames 12 --size 160x90 --video {}",
                                            quoted(tif), quoted(path), quoted(video)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto info = test::probeVideo(video);
  ASSERT_EQ(info.count("error"), 0u) << info.at("error");
  EXPECT_EQ(info.at("codec_name"), "h264");
  EXPECT_EQ(info.at("width"), "160");
  EXPECT_EQ(info.at("height"), "90");
  EXPECT_EQ(info.at("nb_read_frames"), "12");
  // 12 frames 2/11 s apart, the last shown for one interval.
  EXPECT_NEAR(std::stod(info.at("duration")), 12.0 * 2.0 / 11.0, 0.05);

  // Without --frames: 30 frames a second of the path's time (2 s: 61 frames), VP9 in WebM.
  const fs::path webm = dir / "flight.webm";
  const RunResult vp9 = runTellus(fmt::format("render {} --path {} --size 96x54 --video {} --video-codec vp9",
                                              quoted(tif), quoted(path), quoted(webm)));
  ASSERT_EQ(vp9.exitCode, 0) << vp9.output;
  const auto webmInfo = test::probeVideo(webm);
  ASSERT_EQ(webmInfo.count("error"), 0u) << webmInfo.at("error");
  EXPECT_EQ(webmInfo.at("codec_name"), "vp9");
  EXPECT_EQ(webmInfo.at("nb_read_frames"), "61");
}

TEST(VideoCli, BenchWritesOneVideoPerRenderer) {
  const fs::path dir = test::freshTestDir();
  const fs::path tif = generatedTerrain(dir);
  const RunResult r = runTellus(fmt::format(
      "bench {} --algo reference,rag --path orbit --frames 6 --warmup 0 --size 128x72 --quality --video {}",
      quoted(tif), quoted(dir / "orbit.mp4")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "orbit.mp4"));
  for (const char* algo : {"reference", "rag"}) {
    const auto info = test::probeVideo(dir / fmt::format("orbit-{}.mp4", algo));
    ASSERT_EQ(info.count("error"), 0u) << algo << ": " << info.at("error");
    EXPECT_EQ(info.at("nb_read_frames"), "6") << algo;
    EXPECT_EQ(info.at("width"), "128") << algo;
  }
}

TEST(VideoCli, BadRequestsAreRefusedBeforeDrawingAndLeaveNothing) {
  const fs::path dir = test::freshTestDir();
  const fs::path tif = generatedTerrain(dir);
  const fs::path kept = dir / "kept.mp4";
  std::ofstream(kept) << "an earlier file";
  const std::string input = quoted(tif);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("render {} --path orbit --video {}", input, quoted(dir / "a.avi")), "unknown video container"},
      {fmt::format("render {} --path orbit --video {}", input, quoted(dir / "a.webm")), "WebM"},
      {fmt::format("render {} --path orbit --video {}", input, quoted(dir / "missing" / "a.mp4")), "missing"},
      {fmt::format("render {} --path orbit -o {}", input, quoted(dir / "a.png")), "--video"},
      {fmt::format("render {} --path nowhere --video {}", input, quoted(kept)), "nowhere"},
      {fmt::format("render {} -o {} --video {}", input, quoted(dir / "a.png"), quoted(dir / "a.mp4")), "--path"},
      {fmt::format("bench {} --path orbit --frames 3 --video {} --video-quality 99", input, quoted(dir / "b.mp4")), "video-quality"},
  };
  for (const auto& [arguments, expected] : cases) {
    const RunResult r = runTellus(arguments);
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
  }
  std::ifstream in(kept);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "an earlier file");
  // Only the terrain, its sidecars if any, and the kept file: no video and no temporary.
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name.starts_with("range.tif") || name == "kept.mp4") << name;
  }
}

}  // namespace
}  // namespace tellus
