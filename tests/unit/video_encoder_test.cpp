// The video encoder (video_encoder.hpp), judged by FFmpeg's own prober (ffprobe, a separate
// program reading the file from its container's spec): codec, size, frame count and duration;
// and the file hygiene every Tellus output keeps (complete or absent, nothing replaced on error).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <fmt/format.h>

#include "support/test_support.hpp"
#include "tellus/core/scratch_folder.hpp"
#include "tellus/video/video_encoder.hpp"

namespace tellus {
namespace {

namespace fs = std::filesystem;

// A frame that changes with i: a moving gradient and a bar, so the encoder has motion to code.
RgbImage testFrame(int width, int height, int i) {
  RgbImage image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = std::uint8_t((x * 4 + i * 8) & 255);
      p[1] = std::uint8_t((y * 4) & 255);
      p[2] = (x / 8 == i % (width / 8)) ? 255 : 40;
    }
  }
  return image;
}

class VideoEncoderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<ScratchFolder> scratch = ScratchFolder::create(fs::temp_directory_path());
    ASSERT_TRUE(scratch) << scratch.error().message;
    scratch_ = std::make_unique<ScratchFolder>(std::move(scratch.value()));
  }
  fs::path dir() const { return scratch_->path(); }
  std::unique_ptr<ScratchFolder> scratch_;
};

TEST_F(VideoEncoderTest, H264InMp4HasItsFramesSizeAndDuration) {
  const fs::path file = dir() / "flight.mp4";
  Result<std::unique_ptr<VideoEncoder>> encoder = VideoEncoder::create(file, 96, 64, {VideoCodec::H264, -1, 24.0});
  ASSERT_TRUE(encoder) << encoder.error().message;
  for (int i = 0; i < 48; ++i) ASSERT_TRUE((*encoder)->addFrame(testFrame(96, 64, i), i / 24.0));
  EXPECT_FALSE(fs::exists(file)) << "the destination appears only when finished";
  ASSERT_TRUE((*encoder)->finish());
  EXPECT_EQ((*encoder)->framesWritten(), 48);
  const auto info = test::probeVideo(file);
  ASSERT_EQ(info.count("error"), 0u) << info.at("error");
  EXPECT_EQ(info.at("codec_name"), "h264");
  EXPECT_EQ(info.at("pix_fmt"), "yuv420p");
  EXPECT_EQ(info.at("width"), "96");
  EXPECT_EQ(info.at("height"), "64");
  EXPECT_EQ(info.at("nb_read_frames"), "48");
  EXPECT_NEAR(std::stod(info.at("duration")), 2.0, 0.05);  // 48 frames at 24 a second
  // Nothing but the video is left in the folder (no temporary).
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir())) ++files;
  EXPECT_EQ(files, 1);
}

TEST_F(VideoEncoderTest, Vp9InWebmAndOddSizesLoseTheirLastColumnAndRow) {
  const fs::path file = dir() / "flight.webm";
  Result<std::unique_ptr<VideoEncoder>> encoder = VideoEncoder::create(file, 65, 49, {VideoCodec::VP9, 40, 10.0});
  ASSERT_TRUE(encoder) << encoder.error().message;
  // The path's own timing: frames 0.25 s apart.
  for (int i = 0; i < 12; ++i) ASSERT_TRUE((*encoder)->addFrame(testFrame(65, 49, i), 0.25 * i));
  ASSERT_TRUE((*encoder)->finish());
  const auto info = test::probeVideo(file);
  ASSERT_EQ(info.count("error"), 0u) << info.at("error");
  EXPECT_EQ(info.at("codec_name"), "vp9");
  EXPECT_EQ(info.at("width"), "64");
  EXPECT_EQ(info.at("height"), "48");
  EXPECT_EQ(info.at("nb_read_frames"), "12");
  EXPECT_NE(info.at("format_name").find("webm"), std::string::npos);
  EXPECT_NEAR(std::stod(info.at("duration")), 3.0, 0.3);
}

TEST_F(VideoEncoderTest, AnUnfinishedVideoLeavesTheDestinationAsItWas) {
  const fs::path file = dir() / "kept.mp4";
  { std::ofstream(file) << "an earlier file"; }
  {
    Result<std::unique_ptr<VideoEncoder>> encoder = VideoEncoder::create(file, 32, 32, {});
    ASSERT_TRUE(encoder) << encoder.error().message;
    ASSERT_TRUE((*encoder)->addFrame(testFrame(32, 32, 0), 0.0));
    // Times must increase; a frame of another size is refused.
    Status late = (*encoder)->addFrame(testFrame(32, 32, 1), 0.0);
    ASSERT_FALSE(late);
    EXPECT_NE(late.error().message.find("kept.mp4"), std::string::npos) << late.error().message;
    EXPECT_FALSE((*encoder)->addFrame(testFrame(32, 30, 1), 1.0));
  }  // destroyed without finish()
  std::ifstream in(file);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "an earlier file");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir())) ++files;
  EXPECT_EQ(files, 1) << "the temporary is removed";
}

TEST_F(VideoEncoderTest, RefusesWhatItCannotWrite) {
  // H.264 in WebM, an unknown container, a quality out of range, a folder, a missing folder.
  for (const auto& [name, settings, expected] :
       {std::tuple{"a.webm", VideoSettings{VideoCodec::H264}, "WebM"},
        std::tuple{"a.avi", VideoSettings{}, "unknown video container"},
        std::tuple{"a.mp4", VideoSettings{VideoCodec::H264, 52}, "quality"},
        std::tuple{"missing/a.mp4", VideoSettings{}, "missing"}}) {
    Result<std::unique_ptr<VideoEncoder>> encoder = VideoEncoder::create(dir() / name, 32, 32, settings);
    ASSERT_FALSE(encoder) << name;
    EXPECT_NE(encoder.error().message.find(expected), std::string::npos) << encoder.error().message;
  }
  EXPECT_FALSE(VideoEncoder::create(dir(), 32, 32, {}));
  EXPECT_FALSE(parseVideoCodec("av1"));
  EXPECT_EQ(parseVideoCodec("vp9").value(), VideoCodec::VP9);
}

}  // namespace
}  // namespace tellus
