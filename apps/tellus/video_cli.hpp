#pragma once
// --video FILE for commands that fly a camera path (bench, render --path): every recorded frame
// of each renderer's run encoded into a video (tellus/video/video_encoder.hpp), shown at the
// path's own timing.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "tellus/core/result.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/video/video_encoder.hpp"

namespace tellus::cli {

struct VideoCliOptions {
  std::string file;  // empty: no video
  std::string codec = "h264";
  int quality = -1;  // -1: the codec's default
  double speed = 1.0;  // the video plays the path this many times faster than its own timing
};

// --video, --video-codec, --video-quality, --video-speed.
void addVideoOptions(CLI::App* command, VideoCliOptions& options);

// The videos of one command: FILE when one renderer runs, else FILE with "-ALGO" before its
// extension for each (flight.mp4: flight-rings.mp4, flight-rag.mp4).
class PathVideoRecorder {
 public:
  // Checks the codec, the container and every output before anything is drawn.
  static Result<std::shared_ptr<PathVideoRecorder>> create(const VideoCliOptions& options,
                                                           const std::vector<std::string>& algos,
                                                           int width, int height);
  // The file the run of `algo` goes to.
  std::filesystem::path fileFor(const std::string& algo) const;
  // Encodes each frame into its renderer's video: a run's frame 0 opens the video (finishing
  // the previous renderer's), each shown at its path time over the speed (speed / intervalS
  // frames a second).
  std::function<Status(const FrameImage&)> sink();
  // Finishes the video still open; returns the files written, in run order.
  Result<std::vector<std::filesystem::path>> finish();

 private:
  VideoCliOptions options_;
  VideoSettings settings_;
  std::vector<std::string> algos_;
  int width_ = 0, height_ = 0;
  std::unique_ptr<VideoEncoder> open_;
  std::vector<std::filesystem::path> written_;
  Status closeOpen();
};

}  // namespace tellus::cli
