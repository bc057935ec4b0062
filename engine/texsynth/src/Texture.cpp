#include <sylva/texsynth/Texture.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/ImageHeader.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <system_error>

namespace sylva::texsynth {

namespace fs = std::filesystem;

Texture Texture::blank(int width, int height, int channels, std::string name) {
  if (width < 1 || height < 1 || width > kMaxTextureSide || height > kMaxTextureSide) {
    fail("{}: texture size {}x{} is out of range (1..{} per side)", name, width, height, kMaxTextureSide);
  }
  if (channels != 3 && channels != 6) {
    fail("{}: a texture has 3 or 6 channels, not {}", name, channels);
  }
  Texture texture;
  texture.width = width;
  texture.height = height;
  texture.channels = channels;
  texture.name = std::move(name);
  texture.texels.assign(static_cast<std::size_t>(width) * height * channels, 0.0f);
  return texture;
}

namespace {

void checkPicture(const Image& image, const std::string& name) {
  if (image.empty()) {
    fail("{}: the image is empty", name);
  }
  if (image.width() > kMaxTextureSide || image.height() > kMaxTextureSide) {
    fail("{}: image size {}x{} is out of range (1..{} per side)", name, image.width(), image.height(),
         kMaxTextureSide);
  }
}

} // namespace

Texture textureFromImages(const Image& colour, const std::string& colourName, const Image* normalMap,
                          const std::string& normalName, NormalGreen green) {
  checkPicture(colour, colourName);
  if (normalMap != nullptr) {
    checkPicture(*normalMap, normalName);
    if (normalMap->width() != colour.width() || normalMap->height() != colour.height()) {
      fail("{}: normal map is {}x{} but the colour photo {} is {}x{}", normalName, normalMap->width(),
           normalMap->height(), colourName, colour.width(), colour.height());
    }
    if (normalMap->channels() < 3) {
      fail("{}: a normal map needs 3 channels, it has {}", normalName, normalMap->channels());
    }
  }
  Texture texture = Texture::blank(colour.width(), colour.height(), normalMap != nullptr ? 6 : 3, colourName);
  const bool grey = colour.channels() < 3;
  for (int y = 0; y < colour.height(); ++y) {
    for (int x = 0; x < colour.width(); ++x) {
      float* texel = texture.at(x, y);
      for (int c = 0; c < 3; ++c) {
        texel[c] = std::clamp(colour.get(x, y, grey ? 0 : c), 0.0f, 1.0f);
      }
      if (normalMap != nullptr) {
        for (int c = 0; c < 3; ++c) {
          texel[3 + c] = std::clamp(2.0f * normalMap->get(x, y, c) - 1.0f, -1.0f, 1.0f);
        }
        if (green == NormalGreen::Up) {
          texel[4] = -texel[4];
        }
      }
    }
  }
  return texture;
}

Image colourImage(const Texture& texture) {
  Image image(texture.width, texture.height, 3, PixelType::U8);
  for (int y = 0; y < texture.height; ++y) {
    for (int x = 0; x < texture.width; ++x) {
      const float* texel = texture.at(x, y);
      for (int c = 0; c < 3; ++c) {
        image.set(x, y, c, texel[c]);
      }
    }
  }
  return image;
}

Image normalImage(const Texture& texture, NormalGreen green) {
  if (!texture.hasNormals()) {
    fail("{}: the texture has no normal channels", texture.name);
  }
  Image image(texture.width, texture.height, 3, PixelType::U8);
  for (int y = 0; y < texture.height; ++y) {
    for (int x = 0; x < texture.width; ++x) {
      const float* texel = texture.at(x, y);
      const float n[3] = {texel[3], green == NormalGreen::Up ? -texel[4] : texel[4], texel[5]};
      for (int c = 0; c < 3; ++c) {
        image.set(x, y, c, 0.5f * (n[c] + 1.0f));
      }
    }
  }
  return image;
}

Image loadPhoto(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    fail("{}: no such file", name);
  }
  const std::string ext = lowerExtension(path);
  // The size the header states is checked before anything decodes: libjpeg allocates (and for progressive
  // files zeroes) the whole image's coefficients up front, whatever the file's length, and a PNG or an EXR
  // of 20000² takes gigabytes before the size could be checked on the decoded image.
  const std::optional<ImageHeader> header = readImageHeader(path);
  if (header && (header->width > kMaxTextureSide || header->height > kMaxTextureSide)) {
    fail("{}: image size {}x{} is out of range (1..{} per side)", name, header->width, header->height,
         kMaxTextureSide);
  }
  if (ext == ".png" || ext == ".exr") {
    Image image = loadImage(path);
    checkPicture(image, name);
    return image;
  }
  if (ext != ".jpg" && ext != ".jpeg") {
    fail("{}: unsupported photo format '{}' (expected .jpg, .jpeg, .png or .exr)", name, ext);
  }
  // OpenCV decodes by content, whatever the name: a .jpg must hold a JPEG, whose size was checked above.
  if (!header || header->format != "JPEG") {
    fail("{}: not a JPEG file (its content is {})", name,
         header ? header->format : "unrecognised or cut short");
  }
  cv::Mat bgr;
  try {
    bgr = cv::imread(name, cv::IMREAD_COLOR);
  } catch (const cv::Exception&) {
    bgr.release();
  }
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    fail("{}: cannot read the JPEG image (corrupt or truncated)", name);
  }
  if (bgr.cols > kMaxTextureSide || bgr.rows > kMaxTextureSide) {
    fail("{}: image size {}x{} is out of range (1..{} per side)", name, bgr.cols, bgr.rows, kMaxTextureSide);
  }
  Image image(bgr.cols, bgr.rows, 3, PixelType::U8);
  const auto values = image.values<std::uint8_t>();
  for (int y = 0; y < bgr.rows; ++y) {
    const auto* row = bgr.ptr<std::uint8_t>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * bgr.cols + x) * 3;
      values[i + 0] = row[3 * x + 2];
      values[i + 1] = row[3 * x + 1];
      values[i + 2] = row[3 * x + 0];
    }
  }
  return image;
}

Texture loadPhotoTexture(const fs::path& colourPath, const fs::path& normalPath) {
  const Image colour = loadPhoto(colourPath);
  if (normalPath.empty()) {
    return textureFromImages(colour, colourPath.string());
  }
  const Image normal = loadPhoto(normalPath);
  return textureFromImages(colour, colourPath.string(), &normal, normalPath.string(), NormalGreen::Up);
}

void rotateNormal(float* texel, int quarterTurns) {
  const float x = texel[3];
  const float y = texel[4];
  switch (((quarterTurns % 4) + 4) % 4) {
  case 1:
    texel[3] = -y;
    texel[4] = x;
    break;
  case 2:
    texel[3] = -x;
    texel[4] = -y;
    break;
  case 3:
    texel[3] = y;
    texel[4] = -x;
    break;
  default:
    break;
  }
}

} // namespace sylva::texsynth
