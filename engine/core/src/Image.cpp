#include <sylva/core/Image.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

namespace sylva {

namespace {
constexpr int kMaxSide = 65536;
} // namespace

const char* pixelTypeName(PixelType type) {
  switch (type) {
  case PixelType::U8:
    return "8-bit";
  case PixelType::U16:
    return "16-bit";
  case PixelType::F32:
    return "float";
  }
  return "?";
}

Image::Image(int width, int height, int channels, PixelType type)
    : mWidth(width), mHeight(height), mChannels(channels), mType(type) {
  if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide) {
    fail("image size {}x{} is out of range (1..{} per side)", width, height, kMaxSide);
  }
  if (channels < 1 || channels > 4) {
    fail("image channel count {} is out of range (1..4)", channels);
  }
  mData.resize(static_cast<std::size_t>(height) * rowBytes());
}

template <typename T> static bool matches(PixelType type) {
  if constexpr (std::is_same_v<std::remove_const_t<T>, std::uint8_t>) {
    return type == PixelType::U8;
  } else if constexpr (std::is_same_v<std::remove_const_t<T>, std::uint16_t>) {
    return type == PixelType::U16;
  } else {
    static_assert(std::is_same_v<std::remove_const_t<T>, float>,
                  "Image values are uint8_t, uint16_t or float");
    return type == PixelType::F32;
  }
}

template <typename T> std::span<T> Image::values() {
  if (!matches<T>(mType)) {
    fail("image holds {} values; requested another type", pixelTypeName(mType));
  }
  return {reinterpret_cast<T*>(mData.data()), mData.size() / sizeof(T)};
}

template <typename T> std::span<const T> Image::values() const {
  if (!matches<T>(mType)) {
    fail("image holds {} values; requested another type", pixelTypeName(mType));
  }
  return {reinterpret_cast<const T*>(mData.data()), mData.size() / sizeof(T)};
}

template std::span<std::uint8_t> Image::values<std::uint8_t>();
template std::span<std::uint16_t> Image::values<std::uint16_t>();
template std::span<float> Image::values<float>();
template std::span<const std::uint8_t> Image::values<std::uint8_t>() const;
template std::span<const std::uint16_t> Image::values<std::uint16_t>() const;
template std::span<const float> Image::values<float>() const;

float Image::get(int x, int y, int c) const {
  assert(x >= 0 && x < mWidth && y >= 0 && y < mHeight && c >= 0 && c < mChannels);
  const std::size_t i = (static_cast<std::size_t>(y) * mWidth + x) * mChannels + c;
  switch (mType) {
  case PixelType::U8:
    return static_cast<float>(reinterpret_cast<const std::uint8_t*>(mData.data())[i]) / 255.0f;
  case PixelType::U16:
    return static_cast<float>(reinterpret_cast<const std::uint16_t*>(mData.data())[i]) / 65535.0f;
  case PixelType::F32:
    return reinterpret_cast<const float*>(mData.data())[i];
  }
  return 0.0f;
}

void Image::set(int x, int y, int c, float value) {
  assert(x >= 0 && x < mWidth && y >= 0 && y < mHeight && c >= 0 && c < mChannels);
  const std::size_t i = (static_cast<std::size_t>(y) * mWidth + x) * mChannels + c;
  const float clamped = std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f);
  switch (mType) {
  case PixelType::U8:
    reinterpret_cast<std::uint8_t*>(mData.data())[i] =
        static_cast<std::uint8_t>(std::lround(clamped * 255.0f));
    break;
  case PixelType::U16:
    reinterpret_cast<std::uint16_t*>(mData.data())[i] =
        static_cast<std::uint16_t>(std::lround(clamped * 65535.0f));
    break;
  case PixelType::F32:
    reinterpret_cast<float*>(mData.data())[i] = value;
    break;
  }
}

Image Image::converted(PixelType type) const {
  if (type == mType) {
    return *this;
  }
  Image out(mWidth, mHeight, mChannels, type);
  for (int y = 0; y < mHeight; ++y) {
    for (int x = 0; x < mWidth; ++x) {
      for (int c = 0; c < mChannels; ++c) {
        out.set(x, y, c, get(x, y, c));
      }
    }
  }
  return out;
}

void Image::flipVertically() {
  const std::size_t row = rowBytes();
  std::vector<std::byte> tmp(row);
  for (int y = 0; y < mHeight / 2; ++y) {
    std::byte* a = mData.data() + static_cast<std::size_t>(y) * row;
    std::byte* b = mData.data() + static_cast<std::size_t>(mHeight - 1 - y) * row;
    std::memcpy(tmp.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, tmp.data(), row);
  }
}

Image loadImage(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") {
    return loadPng(path);
  }
  if (ext == ".exr") {
    return loadExr(path);
  }
  fail("{}: unsupported image format '{}' (expected .png or .exr)", path.string(), ext);
}

void saveImage(const std::filesystem::path& path, const Image& image) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    fail("{}: cannot write: it is a directory (give a file name, e.g. {})", path.string(),
         (path / "image.png").string());
  }
  const std::string ext = lowerExtension(path);
  if (ext == ".png") {
    savePng(path, image);
  } else if (ext == ".exr") {
    saveExr(path, image);
  } else {
    fail("{}: unsupported image format '{}' (expected .png or .exr)", path.string(), ext);
  }
}

} // namespace sylva
