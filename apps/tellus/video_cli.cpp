#include "video_cli.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_numbers.hpp"
#include "tellus/core/atomic_output.hpp"

namespace tellus::cli {
namespace fs = std::filesystem;

void addVideoOptions(CLI::App* command, VideoCliOptions& o) {
  command->add_option("--video", o.file,
                      "Encode the frames into a video (.mp4, .mkv, .mov; .webm with vp9), shown at the "
                      "path's own timing; with several renderers one file each, named FILE-ALGO.ext");
  command->add_option("--video-codec", o.codec, "Video codec: h264 (default) or vp9")
      ->check(CLI::IsMember({"h264", "vp9"}));
  command->add_option("--video-quality", o.quality,
                      "Constant video quality, lower is better and larger: h264 0-51 (default 20), "
                      "vp9 0-63 (default 32)")
      ->check(integerIn(0, 63));
  command->add_option("--video-speed", o.speed,
                      "Play the path this many times faster than its own timing (a time-lapse; default 1)")
      ->check(numberIn(0.01, 1000.0));
}

Result<std::shared_ptr<PathVideoRecorder>> PathVideoRecorder::create(const VideoCliOptions& options,
                                                                     const std::vector<std::string>& algos,
                                                                     int width, int height) {
  auto recorder = std::make_shared<PathVideoRecorder>();
  recorder->options_ = options;
  recorder->algos_ = algos;
  recorder->width_ = width;
  recorder->height_ = height;
  Result<VideoCodec> codec = parseVideoCodec(options.codec);
  if (!codec) return codec.error();
  recorder->settings_.codec = codec.value();
  recorder->settings_.quality = options.quality;
  // Open and drop an encoder for each output: the container, codec, quality and the file's
  // folder are checked now, not after minutes of drawing (nothing is written: an unfinished
  // encoder removes its temporary).
  for (const std::string& algo : algos) {
    Result<std::unique_ptr<VideoEncoder>> probe =
        VideoEncoder::create(recorder->fileFor(algo), width, height, recorder->settings_);
    if (!probe) return probe.error();
  }
  return recorder;
}

fs::path PathVideoRecorder::fileFor(const std::string& algo) const {
  const fs::path file(options_.file);
  if (algos_.size() <= 1) return file;
  return file.parent_path() / fmt::format("{}-{}{}", file.stem().string(), algo, file.extension().string());
}

Status PathVideoRecorder::closeOpen() {
  if (!open_) return {};
  std::unique_ptr<VideoEncoder> encoder = std::move(open_);
  if (Status finished = encoder->finish(); !finished) return finished;
  spdlog::info("video: {} ({} frames)", encoder->path().string(), encoder->framesWritten());
  written_.push_back(encoder->path());
  return {};
}

std::function<Status(const FrameImage&)> PathVideoRecorder::sink() {
  return [this](const FrameImage& frame) -> Status {
    if (frame.index == 0) {
      if (Status closed = closeOpen(); !closed) return closed;
      VideoSettings settings = settings_;
      settings.framesPerSecond =
          std::clamp(frame.intervalS > 0.0 ? options_.speed / frame.intervalS : 30.0, 0.01, 1000.0);
      Result<std::unique_ptr<VideoEncoder>> encoder =
          VideoEncoder::create(fileFor(std::string(frame.algo)), width_, height_, settings);
      if (!encoder) return encoder.error();
      open_ = std::move(encoder.value());
    }
    if (!open_) return makeError("video: frame {} of {} came before its run's first frame", frame.index, frame.algo);
    return open_->addFrame(frame.image, frame.timeS / options_.speed);
  };
}

Result<std::vector<fs::path>> PathVideoRecorder::finish() {
  if (Status closed = closeOpen(); !closed) return closed.error();
  return written_;
}

}  // namespace tellus::cli
