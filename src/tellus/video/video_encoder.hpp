#pragma once
// Frames to a video file (FFmpeg's libavcodec / libavformat / libswscale): H.264 (libx264) or
// VP9 (libvpx), YUV 4:2:0, in the container the file name says (.mp4, .mkv, .webm, .mov).
//
// Contract:
// - The file appears complete or not at all: frames go to a temporary beside it
//   (atomic_output.hpp) that finish() renames over the destination; an encoder destroyed
//   without finish(), or any error, removes the temporary and leaves the destination as it was.
// - Each frame has a presentation time in seconds (a path's own timing); times must increase.
//   The stream's time base is a millisecond.
// - YUV 4:2:0 needs even sizes: an odd width or height loses its last column or row.
// - Every error names the file and what failed (the library's own message included).
#include <filesystem>
#include <memory>
#include <string>

#include "tellus/core/result.hpp"
#include "tellus/core/rgb_image.hpp"

namespace tellus {

enum class VideoCodec { H264, VP9 };

struct VideoSettings {
  VideoCodec codec = VideoCodec::H264;
  // Constant quality: lower is better and larger. -1 picks the codec's default here (H.264:
  // 20 of 0-51; VP9: 32 of 0-63).
  int quality = -1;
  // The nominal frame rate written into the stream (players show it; the frames' own times
  // decide when each is shown).
  double framesPerSecond = 30.0;
};

// "h264" or "vp9" (what --video-codec takes).
Result<VideoCodec> parseVideoCodec(const std::string& name);
std::string videoCodecName(VideoCodec codec);

class VideoEncoder {
 public:
  // Opens `path` for frames of width x height (the frame size of every addFrame). Checks the
  // container against the codec (WebM holds VP9 only) and that `path` may be written.
  static Result<std::unique_ptr<VideoEncoder>> create(const std::filesystem::path& path, int width, int height,
                                                      const VideoSettings& settings);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // Encodes one frame shown from `timeS` seconds (greater than the last frame's time).
  Status addFrame(const RgbImage& image, double timeS);
  // Flushes the encoder, writes the container's index and renames the temporary over the
  // destination. The encoder takes no frames after.
  Status finish();

  int framesWritten() const;
  const std::filesystem::path& path() const;

 private:
  struct State;
  explicit VideoEncoder(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace tellus
