#include "internal/VideoFile.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>

namespace sylva::folding::internal {

namespace {

/** The number an enum field holds, read as an integer: a decoder may store values the enum does not name. */
template <typename Enum> int enumValue(const Enum& field) {
  static_assert(sizeof(Enum) == sizeof(int));
  int value = 0;
  std::memcpy(&value, &field, sizeof value);
  return value;
}

/**
 * FFmpeg's own messages ("moov atom not found", "corrupt decoded frame") go to the debug log instead of
 * stderr, so the CLI's errors stay one line and `--log-level debug` still shows why a file did not decode.
 * The callback may run on the decoder's threads; spdlog is thread-safe.
 */
void logThroughSpdlog(void* avcl, int level, const char* format, va_list args) {
  if (level > AV_LOG_WARNING || !spdlog::should_log(spdlog::level::debug)) {
    return;
  }
  std::array<char, 1024> line{};
  int prefix = 1;
  av_log_format_line2(avcl, level, format, args, line.data(), static_cast<int>(line.size()), &prefix);
  std::string_view text(line.data());
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) {
    text.remove_suffix(1);
  }
  if (!text.empty()) {
    log::debug("ffmpeg: {}", text);
  }
}

/** Set at every open (an atomic pointer store), so a library that installed its own callback since loses it.
 */
void routeFfmpegLog() {
  av_log_set_callback(logThroughSpdlog);
}

std::string averror(int code) {
  std::array<char, AV_ERROR_MAX_STRING_SIZE> text{};
  av_strerror(code, text.data(), text.size());
  return text.data();
}

} // namespace

struct VideoFile::State {
  std::string name;
  int maxSide = 0;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = nullptr;
  AVFrame* frame = nullptr;
  AVFrame* rgba = nullptr; ///< libswscale's output, padded and aligned as FFmpeg allocates frames
  SwsContext* sws = nullptr;
  int stream = -1;
  bool draining = false; ///< the demuxer is at its end and the decoder has been told so
  int decoded = 0;       ///< frames returned so far

  ~State() {
    sws_freeContext(sws);
    av_frame_free(&rgba);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }

  /** Hands the decoder the next packet of our stream, or tells it the stream has ended. */
  void feed() {
    for (;;) {
      if (av_read_frame(format, packet) < 0) {
        // The end of the file, or a read error a player would treat as one: decode what is buffered.
        avcodec_send_packet(codec, nullptr);
        draining = true;
        return;
      }
      if (packet->stream_index != stream) {
        av_packet_unref(packet);
        continue;
      }
      // A packet the decoder rejects (AVERROR_INVALIDDATA on corrupt data) is dropped; the next one may
      // decode.
      const int sent = avcodec_send_packet(codec, packet);
      av_packet_unref(packet);
      if (sent < 0) {
        log::debug("{}: packet skipped: {}", name, averror(sent));
      }
      return;
    }
  }

  /** The decoded frame as RGBA8 at the size and format the decoder reports for this very frame. */
  void convert(Image& out) {
    const int width = frame->width;
    const int height = frame->height;
    if (width < 1 || height < 1 || width > maxSide || height > maxSide) {
      fail("{}: frame {} is {}×{} pixels; frames must be 1..{} per side", name, decoded, width, height,
           maxSide);
    }
    const auto pixels = static_cast<AVPixelFormat>(frame->format);
    sws = sws_getCachedContext(sws, width, height, pixels, width, height, AV_PIX_FMT_RGBA, SWS_BICUBIC,
                               nullptr, nullptr, nullptr);
    if (sws == nullptr) {
      const char* pixelName = av_get_pix_fmt_name(pixels);
      fail("{}: frame {} is in pixel format '{}', which cannot be converted to RGBA", name, decoded,
           pixelName != nullptr ? pixelName : "unknown");
    }
    // The frame's own colour matrix and range (BT.709 for HD video, full range for Motion-JPEG) rather than
    // libswscale's BT.601 default. Only YUV sources have one; for RGB sources the call fails and changes
    // nothing.
    int* inverse = nullptr;
    int* table = nullptr;
    int srcRange = 0;
    int dstRange = 0;
    int brightness = 0;
    int contrast = 0;
    int saturation = 0;
    if (sws_getColorspaceDetails(sws, &inverse, &srcRange, &table, &dstRange, &brightness, &contrast,
                                 &saturation) >= 0) {
      // A file may carry any number in these fields, and FFmpeg stores it in the enums as it is: read them as
      // integers (loading an enum outside its values is undefined) and keep only the known ones.
      const int spaceRaw = enumValue(frame->colorspace);
      const int rangeRaw = enumValue(frame->color_range);
      const bool known = spaceRaw >= 0 && spaceRaw < AVCOL_SPC_NB && spaceRaw != AVCOL_SPC_UNSPECIFIED;
      const int space = known ? spaceRaw : SWS_CS_DEFAULT;
      srcRange = srcRange != 0 || rangeRaw == AVCOL_RANGE_JPEG ? 1 : 0;
      sws_setColorspaceDetails(sws, sws_getCoefficients(space), srcRange, table, 1, brightness, contrast,
                               saturation);
    }
    if (rgba->width != width || rgba->height != height) {
      av_frame_unref(rgba);
      rgba->format = AV_PIX_FMT_RGBA;
      rgba->width = width;
      rgba->height = height;
      if (av_frame_get_buffer(rgba, 0) < 0) {
        fail("{}: out of memory for a frame of {}×{} pixels", name, width, height);
      }
    }
    sws_scale(sws, frame->data, frame->linesize, 0, height, rgba->data, rgba->linesize);
    out = Image(width, height, 4, PixelType::U8);
    for (int y = 0; y < height; ++y) {
      std::copy_n(reinterpret_cast<const std::byte*>(rgba->data[0] +
                                                     static_cast<std::ptrdiff_t>(y) * rgba->linesize[0]),
                  out.rowBytes(), out.data() + static_cast<std::size_t>(y) * out.rowBytes());
    }
  }
};

VideoFile::VideoFile(const std::string& path, int maxSide) : mState(std::make_unique<State>()) {
  routeFfmpegLog();
  State& s = *mState;
  s.name = path;
  s.maxSide = maxSide;
  if (const int opened = avformat_open_input(&s.format, path.c_str(), nullptr, nullptr); opened < 0) {
    s.format = nullptr;
    fail("{}: cannot decode: not a video FFmpeg can read ({})", path, averror(opened));
  }
  if (const int found = avformat_find_stream_info(s.format, nullptr); found < 0) {
    fail("{}: cannot decode: not a video FFmpeg can read ({})", path, averror(found));
  }
  const AVCodec* decoder = nullptr;
  s.stream = av_find_best_stream(s.format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (s.stream == AVERROR_DECODER_NOT_FOUND) {
    fail("{}: cannot decode: this FFmpeg has no decoder for its video codec", path);
  }
  if (s.stream < 0 || decoder == nullptr) {
    fail("{}: cannot decode: not a video FFmpeg can read (no video stream)", path);
  }
  for (unsigned i = 0; i < s.format->nb_streams; ++i) {
    s.format->streams[i]->discard = static_cast<int>(i) == s.stream ? AVDISCARD_DEFAULT : AVDISCARD_ALL;
  }
  const AVCodecParameters* parameters = s.format->streams[s.stream]->codecpar;
  if (parameters->width > maxSide || parameters->height > maxSide) {
    fail("{}: frames of {}×{} pixels exceed the {} per side this loader accepts", path, parameters->width,
         parameters->height, maxSide);
  }
  s.codec = avcodec_alloc_context3(decoder);
  s.packet = av_packet_alloc();
  s.frame = av_frame_alloc();
  s.rgba = av_frame_alloc();
  if (s.codec == nullptr || s.packet == nullptr || s.frame == nullptr || s.rgba == nullptr) {
    fail("{}: out of memory opening the decoder", path);
  }
  if (const int copied = avcodec_parameters_to_context(s.codec, parameters); copied < 0) {
    fail("{}: cannot decode: {}", path, averror(copied));
  }
  // The decoder refuses (AVERROR_INVALIDDATA) a frame over this many pixels before allocating it, whatever
  // the header said.
  s.codec->max_pixels = static_cast<std::int64_t>(maxSide) * maxSide;
  s.codec->thread_count = 0; // as many as FFmpeg finds useful
  if (const int ready = avcodec_open2(s.codec, decoder, nullptr); ready < 0) {
    fail("{}: cannot decode: {} ({})", path, decoder->name, averror(ready));
  }
}

VideoFile::~VideoFile() = default;

double VideoFile::fps() const {
  const State& s = *mState;
  const AVRational rate = av_guess_frame_rate(s.format, s.format->streams[s.stream], nullptr);
  const double fps = rate.den != 0 ? av_q2d(rate) : 0.0;
  return std::isfinite(fps) && fps > 0.0 && fps < 1e4 ? fps : 0.0;
}

bool VideoFile::read(Image& rgba, double& timeS) {
  State& s = *mState;
  // A decoder that keeps failing while draining (it has nothing more to take) ends the stream.
  int drainFailures = 0;
  for (;;) {
    const int got = avcodec_receive_frame(s.codec, s.frame);
    if (got == 0) {
      s.convert(rgba);
      const AVStream* stream = s.format->streams[s.stream];
      const std::int64_t pts = s.frame->best_effort_timestamp;
      const std::int64_t start = stream->start_time != AV_NOPTS_VALUE ? stream->start_time : 0;
      // In double: a corrupt stream's timestamps may be far apart enough to overflow a difference in int64.
      timeS = pts != AV_NOPTS_VALUE
                  ? (static_cast<double>(pts) - static_cast<double>(start)) * av_q2d(stream->time_base)
                  : std::numeric_limits<double>::quiet_NaN();
      av_frame_unref(s.frame);
      ++s.decoded;
      return true;
    }
    if (got == AVERROR_EOF) {
      return false;
    }
    if (s.draining) {
      if (got == AVERROR(EAGAIN) || ++drainFailures > 64) {
        return false;
      }
      continue;
    }
    // AVERROR(EAGAIN): the decoder wants input; another error: this frame was corrupt, go on with the next.
    s.feed();
  }
}

} // namespace sylva::folding::internal
