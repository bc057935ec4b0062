// Exports of rendered frames: animated GIF (giflib), sprite sheet (PNG + JSON) and video through the `ffmpeg`
// program. Every output is written to a temporary file and renamed, so a failure leaves nothing behind.
#include <sylva/media/Export.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include <gif_lib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace sylva::media {

namespace {

/** Checks that `frames` is non-empty and every frame is RGBA8 of the first frame's size. */
void checkFrames(const std::filesystem::path& path, std::span<const Image> frames) {
  if (frames.empty()) {
    fail("{}: no frames to write", path.string());
  }
  const Image& first = frames.front();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Image& f = frames[i];
    if (f.channels() != 4 || f.type() != PixelType::U8) {
      fail("{}: frame {} is not RGBA8", path.string(), i);
    }
    if (f.width() != first.width() || f.height() != first.height()) {
      fail("{}: frame {} is {}x{}, frame 0 is {}x{}", path.string(), i, f.width(), f.height(), first.width(),
           first.height());
    }
  }
}

/** Closes a giflib encoder (it frees the handle whatever happens). */
struct GifCloser {
  void operator()(GifFileType* gif) const {
    int error = 0;
    EGifCloseFile(gif, &error);
  }
};

/** Nearest palette entry per 24-bit colour, computed on first use (squared RGB distance, lowest index wins).
 */
class NearestColour {
public:
  NearestColour() : mCache(std::size_t{1} << 24, -1) {}

  /** Maps onto `palette` from now on (not owned; must outlive the calls); forgets the cached answers. */
  void use(std::span<const GifColorType> palette) {
    for (const std::uint32_t key : mTouched) {
      mCache[key] = -1;
    }
    mTouched.clear();
    mPalette = palette;
  }

  GifPixelType operator()(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    const std::size_t key = (std::size_t{r} << 16) | (std::size_t{g} << 8) | b;
    std::int16_t& cached = mCache[key];
    if (cached < 0) {
      mTouched.push_back(static_cast<std::uint32_t>(key));
      int best = 0;
      int bestDistance = 1 << 30;
      for (std::size_t i = 0; i < mPalette.size(); ++i) {
        const int dr = int{mPalette[i].Red} - r;
        const int dg = int{mPalette[i].Green} - g;
        const int db = int{mPalette[i].Blue} - b;
        const int d = dr * dr + dg * dg + db * db;
        if (d < bestDistance) {
          bestDistance = d;
          best = static_cast<int>(i);
        }
      }
      cached = static_cast<std::int16_t>(best);
    }
    return static_cast<GifPixelType>(cached);
  }

private:
  std::span<const GifColorType> mPalette;
  std::vector<std::int16_t> mCache;
  std::vector<std::uint32_t> mTouched;
};

/** A pixel rectangle [x0, x1) × [y0, y1); empty when x1 <= x0. */
struct Rect {
  int x0 = 0;
  int y0 = 0;
  int x1 = 0;
  int y1 = 0;
};

/**
 * The palette of the pixels of `rect` in one RGBA8 frame of `width` pixels a row: every k-th pixel so that at
 * most ~1 M pixels are read; when they hold 256 colours or fewer (flat art, a small change) those colours are
 * the palette, exactly. Otherwise a variance-based median cut (Heckbert's median cut choosing, as Wu's
 * quantiser does, the box with the largest squared error and cutting it across its widest-spread channel at
 * the pixel-weighted median) gives 256 boxes whose pixel means are the entries. giflib's GifQuantizeBuffer
 * was used before; it splits the box widest in colour whatever its pixels, and on a cat's portrait gave the
 * whole pupil (26, 19, 11) one entry of (68, 42, 22), 58 levels off. Deterministic: of boxes with equal
 * error the first is cut, and colours equal along the cut channel are ordered by their whole RGB value.
 */
std::vector<GifColorType> quantiseRect(std::span<const std::uint8_t> values, int width, Rect rect) {
  const std::size_t w = static_cast<std::size_t>(rect.x1 - rect.x0);
  const std::size_t pixels = w * static_cast<std::size_t>(rect.y1 - rect.y0);
  const std::size_t budget = 1 << 20;
  const std::size_t step = std::max<std::size_t>(1, (pixels + budget - 1) / budget);
  std::vector<std::uint32_t> keys;
  keys.reserve(pixels / step + 1);
  for (std::size_t p = 0; p < pixels; p += step) {
    const std::size_t i = 4 * ((static_cast<std::size_t>(rect.y0) + p / w) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(rect.x0) + p % w);
    keys.push_back((std::uint32_t{values[i]} << 16) | (std::uint32_t{values[i + 1]} << 8) | values[i + 2]);
  }
  std::sort(keys.begin(), keys.end());
  struct Colour {
    std::array<int, 3> c;
    double n;
  };
  std::vector<Colour> colours;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) {
      ++j;
    }
    colours.push_back({{static_cast<int>(keys[i] >> 16), static_cast<int>((keys[i] >> 8) & 255u),
                        static_cast<int>(keys[i] & 255u)},
                       static_cast<double>(j - i)});
    i = j;
  }
  const auto entry = [](double r, double g, double b) {
    return GifColorType{static_cast<GifByteType>(std::lround(r)), static_cast<GifByteType>(std::lround(g)),
                        static_cast<GifByteType>(std::lround(b))};
  };
  if (colours.size() <= 256) {
    std::vector<GifColorType> exact;
    for (const Colour& c : colours) {
      exact.push_back(entry(c.c[0], c.c[1], c.c[2]));
    }
    return exact;
  }
  struct Box {
    std::size_t begin = 0;
    std::size_t end = 0;
    double error = 0.0; // Σ n·|c − mean|² over the box
    int axis = 0;       // the channel of the largest spread
    std::array<double, 3> mean{};
  };
  const auto describe = [&](std::size_t begin, std::size_t end) {
    Box box{begin, end};
    std::array<double, 3> sum{};
    std::array<double, 3> squares{};
    double n = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      for (std::size_t ch = 0; ch < 3; ++ch) {
        sum[ch] += colours[i].n * colours[i].c[ch];
        squares[ch] += colours[i].n * colours[i].c[ch] * colours[i].c[ch];
      }
      n += colours[i].n;
    }
    double widest = -1.0;
    for (std::size_t ch = 0; ch < 3; ++ch) {
      box.mean[ch] = sum[ch] / n;
      const double spread = std::max(squares[ch] - sum[ch] * sum[ch] / n, 0.0);
      box.error += spread;
      if (spread > widest) {
        widest = spread;
        box.axis = static_cast<int>(ch);
      }
    }
    return box;
  };
  std::vector<Box> boxes{describe(0, colours.size())};
  while (boxes.size() < 256) {
    std::size_t worst = boxes.size();
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      if (boxes[b].end - boxes[b].begin >= 2 && boxes[b].error > 0.0 &&
          (worst == boxes.size() || boxes[b].error > boxes[worst].error)) {
        worst = b;
      }
    }
    if (worst == boxes.size()) {
      break;
    }
    const Box box = boxes[worst];
    const auto axis = static_cast<std::size_t>(box.axis);
    const auto first = colours.begin() + static_cast<std::ptrdiff_t>(box.begin);
    const auto last = colours.begin() + static_cast<std::ptrdiff_t>(box.end);
    std::sort(first, last, [axis](const Colour& a, const Colour& b) {
      return a.c[axis] != b.c[axis] ? a.c[axis] < b.c[axis] : a.c < b.c;
    });
    double total = 0.0;
    for (auto it = first; it != last; ++it) {
      total += it->n;
    }
    // The weighted median, kept off both ends so each half holds a colour.
    std::size_t cut = box.begin + 1;
    double below = colours[box.begin].n;
    while (cut < box.end - 1 && below + colours[cut].n <= 0.5 * total) {
      below += colours[cut].n;
      ++cut;
    }
    boxes[worst] = describe(box.begin, cut);
    boxes.push_back(describe(cut, box.end));
  }
  std::vector<GifColorType> palette;
  palette.reserve(boxes.size());
  for (const Box& box : boxes) {
    palette.push_back(entry(box.mean[0], box.mean[1], box.mean[2]));
  }
  return palette;
}

/** The bounding rectangle of the pixels whose RGB differs between two RGBA8 frames (empty: none). */
Rect changedRect(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b, int width, int height) {
  Rect r{width, height, 0, 0};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * width + x);
      if (a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2]) {
        r = {std::min(r.x0, x), std::min(r.y0, y), std::max(r.x1, x + 1), std::max(r.y1, y + 1)};
      }
    }
  }
  return r;
}

/**
 * Floyd–Steinberg error diffusion of the RGBA8 `values` inside `rect` onto `palette`, serpentine (rows
 * alternate direction so the error does not drift one way), errors in 1/16 levels and clamped to the 0..255
 * range of the colour they are added to. Writes the indices of `rect` into `indices` (width × height).
 */
void diffuse(std::span<const std::uint8_t> values, int width, Rect rect,
             std::span<const GifColorType> palette, NearestColour& nearest,
             std::vector<GifPixelType>& indices) {
  if (rect.x1 <= rect.x0) {
    return;
  }
  const int w = rect.x1 - rect.x0;
  // Two rows of accumulated error (sixteenths), with a pixel of margin on each side.
  std::vector<std::array<int, 3>> here(static_cast<std::size_t>(w) + 2, {0, 0, 0});
  std::vector<std::array<int, 3>> below(here.size(), {0, 0, 0});
  const auto divide16 = [](int e) { return e >= 0 ? (e + 8) / 16 : -((8 - e) / 16); };
  for (int y = rect.y0; y < rect.y1; ++y) {
    const bool forward = (y - rect.y0) % 2 == 0;
    const int step = forward ? 1 : -1;
    for (int k = 0; k < w; ++k) {
      const int cx = forward ? k : w - 1 - k; // column in the rectangle
      const int x = rect.x0 + cx;
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      std::array<int, 3> c{};
      for (int ch = 0; ch < 3; ++ch) {
        c[static_cast<std::size_t>(ch)] =
            std::clamp(int{values[4 * i + static_cast<std::size_t>(ch)]} +
                           divide16(here[static_cast<std::size_t>(cx + 1)][static_cast<std::size_t>(ch)]),
                       0, 255);
      }
      const GifPixelType index = nearest(static_cast<std::uint8_t>(c[0]), static_cast<std::uint8_t>(c[1]),
                                         static_cast<std::uint8_t>(c[2]));
      indices[i] = index;
      const GifColorType& p = palette[index];
      const std::array<int, 3> e{c[0] - p.Red, c[1] - p.Green, c[2] - p.Blue};
      const auto add = [&](std::vector<std::array<int, 3>>& row, int column, int weight) {
        for (int ch = 0; ch < 3; ++ch) {
          row[static_cast<std::size_t>(column + 1)][static_cast<std::size_t>(ch)] +=
              weight * e[static_cast<std::size_t>(ch)];
        }
      };
      add(here, cx + step, 7);
      add(below, cx - step, 3);
      add(below, cx, 5);
      add(below, cx + step, 1);
    }
    std::swap(here, below);
    std::fill(below.begin(), below.end(), std::array<int, 3>{0, 0, 0});
  }
}

/** The last non-empty line of a text file, trimmed ("" when there is none). */
std::string lastLine(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos) {
      last = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
    }
  }
  return last;
}

/** Writes all of `size` bytes; false when the reader has gone (EPIPE) or another error occurs. */
bool writeAll(int fd, const std::byte* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) {
        continue;
      }
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

/** Ignores SIGPIPE while it lives (a dead ffmpeg must give EPIPE, not end Sylva), then restores it. */
class IgnoreSigpipe {
public:
  IgnoreSigpipe() {
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGPIPE, &ignore, &mPrevious);
  }
  ~IgnoreSigpipe() { ::sigaction(SIGPIPE, &mPrevious, nullptr); }
  IgnoreSigpipe(const IgnoreSigpipe&) = delete;
  IgnoreSigpipe& operator=(const IgnoreSigpipe&) = delete;

private:
  struct sigaction mPrevious {};
};

/** A file descriptor closed on destruction. */
struct Fd {
  int fd = -1;
  ~Fd() { reset(); }
  void reset() {
    if (fd >= 0) {
      ::close(fd);
    }
    fd = -1;
  }
};

} // namespace

void writeGif(const std::filesystem::path& path, std::span<const Image> frames, int delayCs, bool loop,
              bool dither) {
  checkFrames(path, frames);
  if (delayCs < 1 || delayCs > 65535) {
    fail("{}: frame delay {} cs is outside 1..65535", path.string(), delayCs);
  }
  const int width = frames[0].width();
  const int height = frames[0].height();
  if (width > 65535 || height > 65535) {
    fail("{}: {}x{} is larger than a GIF can hold (65535)", path.string(), width, height);
  }
  // A colour map of a power-of-two size (GIF's), the palette padded with black.
  const auto colourMap = [&](const std::vector<GifColorType>& palette) {
    const int bits = std::max(1, GifBitSize(static_cast<int>(palette.size())));
    std::vector<GifColorType> padded(std::size_t{1} << bits, GifColorType{0, 0, 0});
    std::copy(palette.begin(), palette.end(), padded.begin());
    std::unique_ptr<ColorMapObject, void (*)(ColorMapObject*)> map(
        GifMakeMapObject(static_cast<int>(padded.size()), padded.data()), GifFreeMapObject);
    if (!map) {
      fail("{}: writing GIF failed: out of memory", path.string());
    }
    return map;
  };
  NearestColour nearest;
  const std::vector<GifColorType> firstPalette =
      quantiseRect(frames[0].values<std::uint8_t>(), width, Rect{0, 0, width, height});

  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    const auto gifError = [&](int code) {
      fail("{}: writing GIF failed: {}", path.string(), GifErrorString(code) ? GifErrorString(code) : "?");
    };
    int error = 0;
    // Opened here rather than by EGifOpenFileName, which creates files readable by their owner only.
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) {
      fail("{}: cannot write: {}", path.string(), std::strerror(errno));
    }
    std::unique_ptr<GifFileType, GifCloser> gif(EGifOpenFileHandle(fd, &error));
    if (!gif) {
      ::close(fd);
      gifError(error);
    }
    EGifSetGifVersion(gif.get(), true);
    // The first frame's palette is the global colour map; every later frame brings its own (a local colour
    // map) for the rectangle it changes.
    const auto global = colourMap(firstPalette);
    if (EGifPutScreenDesc(gif.get(), width, height, global->BitsPerPixel, 0, global.get()) != GIF_OK) {
      gifError(gif->Error);
    }
    if (loop) {
      // NETSCAPE2.0 application block: sub-block 1, loop count 0 = forever.
      static const char kApp[] = "NETSCAPE2.0";
      const std::array<GifByteType, 3> loopBlock{1, 0, 0};
      if (EGifPutExtensionLeader(gif.get(), APPLICATION_EXT_FUNC_CODE) != GIF_OK ||
          EGifPutExtensionBlock(gif.get(), 11, kApp) != GIF_OK ||
          EGifPutExtensionBlock(gif.get(), 3, loopBlock.data()) != GIF_OK ||
          EGifPutExtensionTrailer(gif.get()) != GIF_OK) {
        gifError(gif->Error);
      }
    }
    // Frames after the first store only the rectangle of pixels that changed since the previous one (drawn
    // over it: disposal "do not dispose"), so a cinemagraph whose motion covers a small part of the picture
    // costs little more than its moving part, and still parts keep their pixels (they do not shimmer). The
    // rectangle is quantised on its own: its palette holds the colours it shows.
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    std::vector<GifPixelType> current(pixels);
    for (std::size_t f = 0; f < frames.size(); ++f) {
      const auto values = frames[f].values<std::uint8_t>();
      Rect rect{0, 0, width, height};
      if (f > 0) {
        rect = changedRect(frames[f - 1].values<std::uint8_t>(), values, width, height);
        if (rect.x1 <= rect.x0) {
          rect = Rect{0, 0, 1, 1}; // nothing changed: one unchanged pixel keeps the frame and its delay
        }
      }
      const std::vector<GifColorType> palette = f == 0 ? firstPalette : quantiseRect(values, width, rect);
      const auto local =
          f == 0 ? decltype(colourMap(palette))(nullptr, GifFreeMapObject) : colourMap(palette);
      nearest.use(palette);
      if (dither) {
        diffuse(values, width, rect, palette, nearest, current);
      } else {
        for (int y = rect.y0; y < rect.y1; ++y) {
          for (int x = rect.x0; x < rect.x1; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            current[i] = nearest(values[4 * i], values[4 * i + 1], values[4 * i + 2]);
          }
        }
      }
      const int x0 = rect.x0;
      const int y0 = rect.y0;
      const int x1 = rect.x1;
      const int y1 = rect.y1;
      GraphicsControlBlock gcb{};
      gcb.DisposalMode = DISPOSE_DO_NOT;
      gcb.UserInputFlag = false;
      gcb.DelayTime = delayCs;
      gcb.TransparentColor = NO_TRANSPARENT_COLOR;
      std::array<GifByteType, 4> ext{};
      const std::size_t extSize = EGifGCBToExtension(&gcb, ext.data());
      if (EGifPutExtension(gif.get(), GRAPHICS_EXT_FUNC_CODE, static_cast<int>(extSize), ext.data()) !=
              GIF_OK ||
          EGifPutImageDesc(gif.get(), x0, y0, x1 - x0, y1 - y0, false, local.get()) != GIF_OK) {
        gifError(gif->Error);
      }
      for (int y = y0; y < y1; ++y) {
        if (EGifPutLine(gif.get(), current.data() + static_cast<std::size_t>(y) * width + x0, x1 - x0) !=
            GIF_OK) {
          gifError(gif->Error);
        }
      }
    }
    GifFileType* raw = gif.release();
    if (EGifCloseFile(raw, &error) != GIF_OK) {
      gifError(error);
    }
  });
}

void writeSpriteSheet(const std::filesystem::path& imagePath, const std::filesystem::path& jsonPath,
                      std::span<const Image> frames, int columns, double fps) {
  checkFrames(imagePath, frames);
  if (columns < 1) {
    fail("{}: sprite sheet columns must be at least 1 (got {})", imagePath.string(), columns);
  }
  if (!(fps > 0.0) || !std::isfinite(fps)) {
    fail("{}: frames per second must be positive (got {})", imagePath.string(), fps);
  }
  const int count = static_cast<int>(frames.size());
  const int cols = std::min(columns, count);
  const int rows = (count + cols - 1) / cols;
  const int w = frames[0].width();
  const int h = frames[0].height();
  if (static_cast<long long>(cols) * w > 65536 || static_cast<long long>(rows) * h > 65536) {
    fail("{}: a {}x{} sheet of {}x{} frames is larger than 65536 pixels; use fewer frames or more/fewer "
         "columns",
         imagePath.string(), cols, rows, w, h);
  }
  Image sheet(cols * w, rows * h, 4, PixelType::U8);
  nlohmann::json rects = nlohmann::json::array();
  for (int i = 0; i < count; ++i) {
    const int x0 = (i % cols) * w;
    const int y0 = (i / cols) * h;
    const Image& frame = frames[static_cast<std::size_t>(i)];
    for (int y = 0; y < h; ++y) {
      std::memcpy(sheet.data() + static_cast<std::size_t>(y0 + y) * sheet.rowBytes() +
                      static_cast<std::size_t>(x0) * 4,
                  frame.data() + static_cast<std::size_t>(y) * frame.rowBytes(), frame.rowBytes());
    }
    rects.push_back({{"index", i}, {"x", x0}, {"y", y0}, {"w", w}, {"h", h}, {"t", i / fps}});
  }
  const std::filesystem::path relative =
      std::filesystem::absolute(imagePath).lexically_normal().lexically_relative(
          std::filesystem::absolute(jsonPath).lexically_normal().parent_path());
  const nlohmann::json json = {{"format", "sylva-fold-sprites"},
                               {"version", 1},
                               {"image", relative.empty() ? imagePath.string() : relative.generic_string()},
                               {"size", {sheet.width(), sheet.height()}},
                               {"columns", cols},
                               {"rows", rows},
                               {"fps", fps},
                               {"frames", rects}};
  saveImage(imagePath, sheet);
  saveJsonFile(jsonPath, json);
}

bool ffmpegAvailable() {
  return !findOnPath("ffmpeg").empty();
}

void writeVideo(const std::filesystem::path& path, std::span<const Image> frames, double fps) {
  const std::string ext = lowerExtension(path);
  if (ext != ".mp4" && ext != ".webm") {
    fail("{}: unsupported video extension '{}' (use .mp4 or .webm)", path.string(), ext);
  }
  checkFrames(path, frames);
  if (!(fps > 0.0) || !std::isfinite(fps)) {
    fail("{}: frames per second must be positive (got {})", path.string(), fps);
  }
  const std::filesystem::path ffmpeg = findOnPath("ffmpeg");
  if (ffmpeg.empty()) {
    fail("ffmpeg not found on PATH: install it (apt install ffmpeg) or write --gif/--sprites/--frames "
         "instead");
  }
  const int width = frames[0].width();
  const int height = frames[0].height();

  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    std::vector<std::string> args = {ffmpeg.string(),
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-f",
                                     "rawvideo",
                                     "-pix_fmt",
                                     "rgba",
                                     "-s",
                                     fmt::format("{}x{}", width, height),
                                     "-r",
                                     fmt::format("{}", fps),
                                     "-i",
                                     "pipe:0",
                                     "-an",
                                     "-vf",
                                     "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                     "-pix_fmt",
                                     "yuv420p",
                                     "-fflags",
                                     "+bitexact"};
    if (ext == ".mp4") {
      args.insert(args.end(), {"-c:v", "libx264", "-crf", "18", "-movflags", "+faststart", "-f", "mp4"});
    } else {
      args.insert(args.end(), {"-c:v", "libvpx-vp9", "-crf", "30", "-b:v", "0", "-f", "webm"});
    }
    args.push_back(tmp.string());
    std::vector<char*> argv;
    for (std::string& a : args) {
      argv.push_back(a.data());
    }
    argv.push_back(nullptr);

    // ffmpeg's messages go to a temporary file: read after it ends, so a chatty ffmpeg can never block on a
    // full stderr pipe while Sylva blocks writing frames to it.
    std::string errTemplate = (std::filesystem::temp_directory_path() / "sylva-ffmpeg-XXXXXX").string();
    Fd err{::mkstemp(errTemplate.data())};
    if (err.fd < 0) {
      fail("{}: cannot create a temporary file for ffmpeg's messages: {}", path.string(),
           std::strerror(errno));
    }
    const std::filesystem::path errPath = errTemplate;
    struct RemoveFile {
      std::filesystem::path p;
      ~RemoveFile() {
        std::error_code ignored;
        std::filesystem::remove(p, ignored);
      }
    } removeErr{errPath};
    ::fcntl(err.fd, F_SETFD, FD_CLOEXEC);
    int fds[2] = {-1, -1};
    if (::pipe2(fds, O_CLOEXEC) != 0) {
      fail("{}: cannot create a pipe to ffmpeg: {}", path.string(), std::strerror(errno));
    }
    Fd readEnd{fds[0]};
    Fd writeEnd{fds[1]};

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, readEnd.fd, STDIN_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, err.fd, STDERR_FILENO);
    pid_t pid = -1;
    const int spawned = ::posix_spawn(&pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
      fail("{}: cannot start {}: {}", path.string(), ffmpeg.string(), std::strerror(spawned));
    }
    readEnd.reset();
    bool fed = true;
    {
      const IgnoreSigpipe ignore;
      for (const Image& frame : frames) {
        if (!writeAll(writeEnd.fd, frame.data(), frame.byteSize())) {
          fed = false; // ffmpeg stopped reading: its exit status and message say why
          break;
        }
      }
      writeEnd.reset();
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
      if (errno != EINTR) {
        fail("{}: waiting for ffmpeg failed: {}", path.string(), std::strerror(errno));
      }
    }
    const std::string message = lastLine(errPath);
    if (WIFSIGNALED(status)) {
      fail("{}: ffmpeg was killed by signal {}{}{}", path.string(), WTERMSIG(status),
           message.empty() ? "" : ": ", message);
    }
    if (WEXITSTATUS(status) != 0) {
      fail("{}: ffmpeg failed (exit {}): {}", path.string(), WEXITSTATUS(status),
           message.empty() ? "no message" : message);
    }
    if (!fed) {
      fail("{}: ffmpeg stopped reading frames{}{}", path.string(), message.empty() ? "" : ": ", message);
    }
    std::error_code ec;
    if (!std::filesystem::exists(tmp, ec) || std::filesystem::file_size(tmp, ec) == 0) {
      fail("{}: ffmpeg exited without writing the video", path.string());
    }
  });
}

} // namespace sylva::media
