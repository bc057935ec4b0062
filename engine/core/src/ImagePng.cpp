// PNG reading and writing through libpng's classic API. libpng reports errors by longjmp, so every C++ object
// with a destructor lives outside the frame that calls setjmp (see decode()/encode()).
#include <sylva/core/Image.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Limits.hpp>

#include <png.h>

#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

namespace sylva {

namespace {

struct PngIo {
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  std::size_t pos = 0;
  std::FILE* file = nullptr;
  char message[256] = {};
};

void onError(png_structp png, png_const_charp msg) {
  auto* io = static_cast<PngIo*>(png_get_error_ptr(png));
  std::snprintf(io->message, sizeof(io->message), "%s", msg);
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}

void readBytes(png_structp png, png_bytep out, png_size_t n) {
  auto* io = static_cast<PngIo*>(png_get_io_ptr(png));
  if (io->pos + n > io->size) {
    png_error(png, "truncated PNG data");
  }
  std::memcpy(out, io->data + io->pos, n);
  io->pos += n;
}

/** Receives the decoded size and returns storage for the rows (top row first). */
using Allocate = std::byte* (*)(void* context, int width, int height, int channels, int bitDepth);

bool decode(PngIo& io, Allocate allocate, void* context) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, onError, onWarning);
  if (png == nullptr) {
    std::snprintf(io.message, sizeof(io.message), "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  png_bytep* volatile rows = nullptr;
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    std::free(rows);
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  // Our own size message before libpng's generic "Invalid IHDR data": width and height are the big-endian
  // words at bytes 16..23 (signature, IHDR length and type come first).
  if (io.data != nullptr && io.size >= 24) {
    const auto word = [&](std::size_t at) {
      return std::uint32_t{static_cast<unsigned char>(io.data[at])} << 24 |
             std::uint32_t{static_cast<unsigned char>(io.data[at + 1])} << 16 |
             std::uint32_t{static_cast<unsigned char>(io.data[at + 2])} << 8 |
             std::uint32_t{static_cast<unsigned char>(io.data[at + 3])};
    };
    const std::uint32_t w = word(16);
    const std::uint32_t h = word(20);
    if (w > 65536 || h > 65536) {
      std::snprintf(io.message, sizeof(io.message), "absurd size %ux%u pixels (at most 65536 per side)", w,
                    h);
      png_destroy_read_struct(&png, &info, nullptr);
      return false;
    }
  }
  png_set_read_fn(png, &io, readBytes);
  png_set_user_limits(png, 65536, 65536);
  png_read_info(png, info);
  // A PNG's rows (plus one filter byte each) are zlib-deflated, which expands at most ~1032:1; a header that
  // claims more than the file can hold is corrupt, and is rejected before a byte of pixels is allocated.
  const std::uint64_t inflated =
      (std::uint64_t{png_get_rowbytes(png, info)} + 1) * std::uint64_t{png_get_image_height(png, info)};
  if (inflated > std::uint64_t{io.size} * kMaxDeflateRatio + 4096) {
    std::snprintf(
        io.message, sizeof(io.message),
        "truncated or corrupt PNG: a %ux%u image needs %llu bytes of pixel data, more than %zu bytes "
        "of file can hold",
        png_get_image_width(png, info), png_get_image_height(png, info),
        static_cast<unsigned long long>(inflated), io.size);
    png_longjmp(png, 1);
  }
  const int colorType = png_get_color_type(png, info);
  const int depth = png_get_bit_depth(png, info);
  if (colorType == PNG_COLOR_TYPE_PALETTE) {
    png_set_palette_to_rgb(png);
  }
  if (colorType == PNG_COLOR_TYPE_GRAY && depth < 8) {
    png_set_expand_gray_1_2_4_to_8(png);
  }
  if (png_get_valid(png, info, PNG_INFO_tRNS)) {
    png_set_tRNS_to_alpha(png);
  }
  if (depth == 16) {
    png_set_swap(png); // PNG stores big-endian samples; we keep native little-endian uint16_t.
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const int width = static_cast<int>(png_get_image_width(png, info));
  const int height = static_cast<int>(png_get_image_height(png, info));
  const int channels = png_get_channels(png, info);
  const int outDepth = png_get_bit_depth(png, info);
  std::byte* pixels = allocate(context, width, height, channels, outDepth);
  if (pixels == nullptr) {
    png_error(png, "unsupported image layout");
  }
  const std::size_t rowBytes = png_get_rowbytes(png, info);
  rows = static_cast<png_bytep*>(std::malloc(sizeof(png_bytep) * static_cast<std::size_t>(height)));
  for (int y = 0; y < height; ++y) {
    rows[y] = reinterpret_cast<png_bytep>(pixels + rowBytes * static_cast<std::size_t>(y));
  }
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  std::free(rows);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

struct Target {
  Image image;
  std::string error;
};

std::byte* allocateImage(void* context, int width, int height, int channels, int bitDepth) {
  auto* target = static_cast<Target*>(context);
  if (bitDepth != 8 && bitDepth != 16) {
    target->error = "unsupported bit depth " + std::to_string(bitDepth);
    return nullptr;
  }
  try {
    target->image = Image(width, height, channels, bitDepth == 16 ? PixelType::U16 : PixelType::U8);
  } catch (const Error& e) {
    target->error = e.what();
    return nullptr;
  }
  return target->image.data();
}

bool encode(PngIo& io, const Image& image) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, onError, onWarning);
  if (png == nullptr) {
    std::snprintf(io.message, sizeof(io.message), "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, io.file);
  static constexpr int kColorTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                        PNG_COLOR_TYPE_RGB_ALPHA};
  const int depth = image.type() == PixelType::U16 ? 16 : 8;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width()), static_cast<png_uint_32>(image.height()),
               depth, kColorTypes[image.channels() - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  // Fast compression: goldens and intermediate maps are rewritten often; size matters less than time.
  png_set_compression_level(png, 3);
  png_write_info(png, info);
  if (depth == 16) {
    png_set_swap(png);
  }
  for (int y = 0; y < image.height(); ++y) {
    png_write_row(png, reinterpret_cast<png_const_bytep>(image.data() +
                                                         image.rowBytes() * static_cast<std::size_t>(y)));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

} // namespace

Image loadPng(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("{}: cannot open file (missing or unreadable)", path.string());
  }
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0) {
    fail("{}: not a PNG file (bad signature)", path.string());
  }
  PngIo io;
  io.data = bytes.data();
  io.size = bytes.size();
  Target target;
  if (!decode(io, allocateImage, &target)) {
    fail("{}: {}", path.string(), target.error.empty() ? io.message : target.error);
  }
  return std::move(target.image);
}

void savePng(const std::filesystem::path& path, const Image& image) {
  if (image.empty()) {
    fail("{}: cannot save an empty image", path.string());
  }
  if (image.type() == PixelType::F32) {
    savePng(path, image.converted(PixelType::U16));
    return;
  }
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    PngIo io;
    io.file = std::fopen(tmp.c_str(), "wb");
    if (io.file == nullptr) {
      fail("{}: cannot open for writing", path.string());
    }
    const bool ok = encode(io, image);
    const bool closed = std::fclose(io.file) == 0;
    if (!ok || !closed) {
      fail("{}: write failed: {}", path.string(), ok ? "I/O error" : io.message);
    }
  });
}

} // namespace sylva
