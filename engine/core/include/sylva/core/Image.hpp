#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace sylva {

/** Storage type of one image channel. */
enum class PixelType : std::uint8_t {
  U8,  ///< 8-bit unsigned normalised, [0, 255] ↔ [0, 1]
  U16, ///< 16-bit unsigned normalised, [0, 65535] ↔ [0, 1]
  F32, ///< 32-bit float, unbounded
};

/** Bytes per channel of a PixelType. */
constexpr std::size_t bytesPerChannel(PixelType type) {
  return type == PixelType::U8 ? 1 : type == PixelType::U16 ? 2 : 4;
}

/** Human-readable name ("8-bit", "16-bit", "float"). */
const char* pixelTypeName(PixelType type);

/**
 * A 2D image with 1..4 interleaved channels, stored row by row with row 0 at the top (file order). Pixel (x,
 * y) is at column x from the left and row y from the top. Value semantics; not thread-safe for concurrent
 * writes.
 */
class Image {
public:
  /** An empty 0×0 image. */
  Image() = default;
  /** A zero-filled image; throws sylva::Error for non-positive or absurd sizes (> 65536 per side). */
  Image(int width, int height, int channels, PixelType type);

  int width() const { return mWidth; }                       ///< pixels
  int height() const { return mHeight; }                     ///< pixels
  int channels() const { return mChannels; }                 ///< 1 (grey) … 4 (RGBA)
  PixelType type() const { return mType; }                   ///< type of each channel value
  bool empty() const { return mWidth == 0 || mHeight == 0; } ///< no pixels

  /** Bytes of one row (no padding between rows). */
  std::size_t rowBytes() const {
    return static_cast<std::size_t>(mWidth) * mChannels * bytesPerChannel(mType);
  }
  /** Bytes of all pixels: rowBytes() · height(). */
  std::size_t byteSize() const { return mData.size(); }
  /** The pixels, rows top to bottom, channels interleaved. */
  std::byte* data() { return mData.data(); }
  /** The pixels, rows top to bottom, channels interleaved. */
  const std::byte* data() const { return mData.data(); }

  /** Typed view of all channel values; T must match type() (uint8_t, uint16_t or float), else throws. */
  template <typename T> std::span<T> values();
  /** Typed read-only view of all channel values; T must match type(), else throws. */
  template <typename T> std::span<const T> values() const;

  /**
   * Channel c of pixel (x, y) as a float: normalised to [0, 1] for U8/U16, raw for F32. No bounds checks
   * beyond a debug assert; callers iterate within width()/height().
   */
  float get(int x, int y, int c) const;
  /** Sets channel c of pixel (x, y) from a float; U8/U16 values are clamped to [0, 1] and rounded. */
  void set(int x, int y, int c, float value);

  /** A copy with another channel type (values keep their normalised meaning). */
  Image converted(PixelType type) const;
  /** Mirrors rows in place (GL read-back is bottom-up; files are top-down). */
  void flipVertically();

  /** Same size, channels, type and bytes. */
  bool operator==(const Image& other) const = default;

private:
  int mWidth = 0;
  int mHeight = 0;
  int mChannels = 0;
  PixelType mType = PixelType::U8;
  std::vector<std::byte> mData;
};

/**
 * Loads a PNG (8- or 16-bit; grey, grey+alpha, RGB, RGBA; palette images expand to RGB(A)) or an OpenEXR
 * image (loaded as F32) by file extension. Throws sylva::Error naming the file and the reason (missing,
 * truncated, unsupported bit depth or format).
 */
Image loadImage(const std::filesystem::path& path);

/**
 * Saves by extension: `.png` writes 8- or 16-bit PNG (F32 images are converted to 16-bit, clamped to [0, 1]);
 * `.exr` writes 32-bit float channels. The file is written to a temporary name and renamed, so a failure
 * never leaves a partial file. Throws sylva::Error naming the file.
 */
void saveImage(const std::filesystem::path& path, const Image& image);

/** Reads a PNG (8 or 16 bit, grey to RGBA); throws sylva::Error naming the file. */
Image loadPng(const std::filesystem::path& path);
/** Writes a PNG (8 or 16 bit by the image's type; F32 as 16 bit), atomically. */
void savePng(const std::filesystem::path& path, const Image& image);
/** Reads an OpenEXR image as F32; throws sylva::Error naming the file. */
Image loadExr(const std::filesystem::path& path);
/** Writes an image as float OpenEXR, atomically. */
void saveExr(const std::filesystem::path& path, const Image& image);

} // namespace sylva
