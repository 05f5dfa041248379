#include "tellus/video/video_encoder.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <system_error>

#include <fmt/format.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "tellus/core/atomic_output.hpp"

namespace tellus {
namespace {

std::string avMessage(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof(text));
  return text;
}

// The libavformat muxer for the destination's extension, and whether it holds the codec.
Result<const char*> muxerFor(const std::filesystem::path& path, VideoCodec codec) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".mp4") return "mp4";
  if (ext == ".mov") return "mov";
  if (ext == ".mkv") return "matroska";
  if (ext == ".webm") {
    if (codec != VideoCodec::VP9) return makeError("{}: a WebM file holds VP9, not H.264 (use --video-codec vp9 or .mp4)", path.string());
    return "webm";
  }
  return makeError("{}: unknown video container '{}' (use .mp4, .mkv, .webm or .mov)", path.string(), ext);
}

}  // namespace

struct VideoEncoder::State {
  std::filesystem::path path, temporary;
  int width = 0, height = 0;  // the frames given
  int encodedWidth = 0, encodedHeight = 0;  // even
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* scaler = nullptr;
  bool headerWritten = false, finished = false;
  int frames = 0;
  std::int64_t lastPts = -1;

  Error fail(const std::string& what, int code) const {
    return makeError("{}: {}: {}", path.string(), what, avMessage(code));
  }

  // Sends `input` (null: flush) and writes every packet the encoder has ready.
  Status encode(AVFrame* input) {
    if (int e = avcodec_send_frame(codec, input); e < 0) return fail("encoding a frame", e);
    while (true) {
      const int e = avcodec_receive_packet(codec, packet);
      if (e == AVERROR(EAGAIN) || e == AVERROR_EOF) return {};
      if (e < 0) return fail("encoding a frame", e);
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      const int w = av_interleaved_write_frame(format, packet);  // takes the packet's reference
      if (w < 0) return fail("writing a packet", w);
    }
  }

  ~State() {
    sws_freeContext(scaler);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
    if (!finished && !temporary.empty()) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
    }
  }
};

Result<VideoCodec> parseVideoCodec(const std::string& name) {
  if (name == "h264") return VideoCodec::H264;
  if (name == "vp9") return VideoCodec::VP9;
  return makeError("unknown video codec '{}' (h264 or vp9)", name);
}

std::string videoCodecName(VideoCodec codec) { return codec == VideoCodec::H264 ? "h264" : "vp9"; }

VideoEncoder::VideoEncoder(std::unique_ptr<State> state) : state_(std::move(state)) {}
VideoEncoder::~VideoEncoder() = default;

Result<std::unique_ptr<VideoEncoder>> VideoEncoder::create(const std::filesystem::path& path, int width, int height,
                                                           const VideoSettings& settings) {
  av_log_set_level(AV_LOG_ERROR);  // the libraries report through our errors, not on stderr
  if (width < 2 || height < 2) return makeError("{}: a video frame needs at least 2 x 2 pixels, not {} x {}", path.string(), width, height);
  if (!(settings.framesPerSecond > 0.0) || settings.framesPerSecond > 1000.0) {
    return makeError("{}: frame rate {} outside (0, 1000]", path.string(), settings.framesPerSecond);
  }
  const int maxQuality = settings.codec == VideoCodec::H264 ? 51 : 63;
  const int quality = settings.quality >= 0 ? settings.quality : (settings.codec == VideoCodec::H264 ? 20 : 32);
  if (quality > maxQuality) return makeError("{}: quality {} outside 0-{} for {}", path.string(), quality, maxQuality, videoCodecName(settings.codec));
  Result<const char*> muxer = muxerFor(path, settings.codec);
  if (!muxer) return muxer.error();
  if (Status writable = checkOutputWritable(path); !writable) return writable.error();
  removeStaleTemporariesFor(path);

  auto s = std::make_unique<State>();
  s->path = path;
  s->temporary = temporaryPathFor(path);
  s->width = width;
  s->height = height;
  s->encodedWidth = width & ~1;
  s->encodedHeight = height & ~1;
  const std::string temporary = s->temporary.string();
  if (int e = avformat_alloc_output_context2(&s->format, nullptr, *muxer, temporary.c_str()); e < 0 || !s->format) {
    return s->fail("opening the container", e);
  }
  const char* encoderName = settings.codec == VideoCodec::H264 ? "libx264" : "libvpx-vp9";
  const AVCodec* encoder = avcodec_find_encoder_by_name(encoderName);
  if (!encoder) return makeError("{}: this FFmpeg has no {} encoder", path.string(), encoderName);
  s->stream = avformat_new_stream(s->format, nullptr);
  s->codec = avcodec_alloc_context3(encoder);
  s->frame = av_frame_alloc();
  s->packet = av_packet_alloc();
  if (!s->stream || !s->codec || !s->frame || !s->packet) return makeError("{}: out of memory opening the encoder", path.string());
  AVCodecContext* c = s->codec;
  c->width = s->encodedWidth;
  c->height = s->encodedHeight;
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->time_base = AVRational{1, 1000};  // milliseconds: the frames' own times
  c->framerate = av_d2q(settings.framesPerSecond, 100000);
  c->gop_size = std::max(1, int(std::lround(settings.framesPerSecond * 2.0)));  // a key frame every 2 s
  c->thread_count = 0;  // the library's choice: one per core
  if (s->format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (settings.codec == VideoCodec::H264) {
    av_opt_set(c->priv_data, "preset", "medium", 0);
    av_opt_set_int(c->priv_data, "crf", quality, 0);
  } else {
    c->bit_rate = 0;  // constant quality
    av_opt_set_int(c->priv_data, "crf", quality, 0);
    av_opt_set(c->priv_data, "deadline", "good", 0);
    av_opt_set_int(c->priv_data, "cpu-used", 4, 0);
    av_opt_set_int(c->priv_data, "row-mt", 1, 0);
  }
  if (int e = avcodec_open2(c, encoder, nullptr); e < 0) return s->fail(fmt::format("opening the {} encoder", encoderName), e);
  if (int e = avcodec_parameters_from_context(s->stream->codecpar, c); e < 0) return s->fail("describing the stream", e);
  s->stream->time_base = c->time_base;
  s->stream->avg_frame_rate = c->framerate;
  s->frame->format = c->pix_fmt;
  s->frame->width = c->width;
  s->frame->height = c->height;
  if (int e = av_frame_get_buffer(s->frame, 0); e < 0) return s->fail("allocating a frame", e);
  s->scaler = sws_getContext(s->encodedWidth, s->encodedHeight, AV_PIX_FMT_RGB24, s->encodedWidth, s->encodedHeight,
                             AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (!s->scaler) return makeError("{}: cannot convert RGB to YUV 4:2:0 at {} x {}", path.string(), width, height);
  if (int e = avio_open(&s->format->pb, temporary.c_str(), AVIO_FLAG_WRITE); e < 0) return s->fail("creating the file", e);
  AVDictionary* options = nullptr;
  // MP4 and MOV: the index first, so a browser plays the file while it loads.
  if (std::string(*muxer) == "mp4" || std::string(*muxer) == "mov") av_dict_set(&options, "movflags", "+faststart", 0);
  const int header = avformat_write_header(s->format, &options);
  av_dict_free(&options);
  if (header < 0) return s->fail("writing the header", header);
  s->headerWritten = true;
  return std::unique_ptr<VideoEncoder>(new VideoEncoder(std::move(s)));
}

Status VideoEncoder::addFrame(const RgbImage& image, double timeS) {
  State& s = *state_;
  if (s.finished) return makeError("{}: a frame after the video was finished", s.path.string());
  if (image.width != s.width || image.height != s.height) {
    return makeError("{}: a frame of {} x {} in a video of {} x {}", s.path.string(), image.width, image.height, s.width, s.height);
  }
  const std::int64_t pts = std::llround(timeS * 1000.0);
  if (!std::isfinite(timeS) || pts <= s.lastPts) {
    return makeError("{}: frame {} at {} s is not after the previous frame", s.path.string(), s.frames, timeS);
  }
  if (int e = av_frame_make_writable(s.frame); e < 0) return s.fail("preparing a frame", e);
  const std::uint8_t* source[1] = {image.pixels.data()};
  const int stride[1] = {image.width * 3};
  sws_scale(s.scaler, source, stride, 0, s.encodedHeight, s.frame->data, s.frame->linesize);
  s.frame->pts = pts;
  if (Status encoded = s.encode(s.frame); !encoded) return encoded;
  s.lastPts = pts;
  ++s.frames;
  return {};
}

Status VideoEncoder::finish() {
  State& s = *state_;
  if (s.finished) return makeError("{}: finished twice", s.path.string());
  if (s.frames == 0) return makeError("{}: no frames to write", s.path.string());
  if (Status flushed = s.encode(nullptr); !flushed) return flushed;
  if (int e = av_write_trailer(s.format); e < 0) return s.fail("writing the index", e);
  if (int e = avio_closep(&s.format->pb); e < 0) return s.fail("closing the file", e);
  std::error_code error;
  std::filesystem::rename(s.temporary, s.path, error);
  if (error) return makeError("{}: renaming the finished video into place: {}", s.path.string(), error.message());
  s.finished = true;
  return {};
}

int VideoEncoder::framesWritten() const { return state_->frames; }
const std::filesystem::path& VideoEncoder::path() const { return state_->path; }

}  // namespace tellus
