#pragma once

#include <sylva/core/Image.hpp>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::texsynth {

/**
 * How the green channel of a normal-map picture is oriented. Texture rows are stored in file order (row 0 is
 * the first row of the picture file, which is uploaded first, so it is v = 0 in GL); a texture's normal y
 * therefore points towards increasing rows (+v).
 */
enum class NormalGreen {
  Up,        ///< green points up in the picture (towards row 0): OpenGL-style normal-map photos
  AlongRows, ///< green points towards increasing rows (+v): the tile atlases written by this module
};

/**
 * A float texture for synthesis: width × height texels of 3 or 6 interleaved channels, row y at index y
 * (row 0 = first row of the source file = v = 0 when uploaded first). Channels 0..2 are colour RGB in [0, 1]
 * as stored in the file (sRGB, not linearised). Optional channels 3..5 are a tangent-space normal as a
 * vector in [-1, 1]³ (n = 2c − 1 from the map's channel values c), x towards increasing columns, y towards
 * increasing rows, z out of the surface. Synthesis measures errors on the colour channels only and copies
 * all channels. `name` (usually the file name) is used in error messages. Value type; not thread-safe for
 * concurrent writes.
 */
struct Texture {
  int width = 0;             ///< texels
  int height = 0;            ///< texels
  int channels = 3;          ///< 3 (RGB) or 6 (RGB + normal)
  std::string name;          ///< for error messages
  std::vector<float> texels; ///< width × height × channels values, rows top to bottom

  /** An all-zero texture; throws sylva::Error for sizes outside 1..16384 or channels other than 3 or 6. */
  static Texture blank(int width, int height, int channels, std::string name = "texture");

  bool empty() const { return width == 0 || height == 0; } ///< no texels
  bool hasNormals() const { return channels == 6; }        ///< channels 3..5 hold a normal
  /** Pointer to the `channels` values of texel (x, y); no bounds checks. */
  float* at(int x, int y) { return texels.data() + (static_cast<std::size_t>(y) * width + x) * channels; }
  /** Read-only pointer to the `channels` values of texel (x, y); no bounds checks. */
  const float* at(int x, int y) const {
    return texels.data() + (static_cast<std::size_t>(y) * width + x) * channels;
  }
  /** Same size, channels, name and values. */
  bool operator==(const Texture& other) const = default;
};

/** Largest accepted texture side, texels. */
constexpr int kMaxTextureSide = 16384;

/**
 * A texture from a colour picture (1..4 channels: grey expands to RGB, alpha is dropped) and, if `normalMap`
 * is not null, a normal-map picture of the same size (its first three channels, n = 2c − 1, with y negated
 * for NormalGreen::Up so it points along rows). Throws sylva::Error naming `colourName` / `normalName` for
 * empty images, absurd sizes or a size mismatch.
 */
Texture textureFromImages(const Image& colour, const std::string& colourName,
                          const Image* normalMap = nullptr, const std::string& normalName = "",
                          NormalGreen green = NormalGreen::Up);

/** The colour channels as an 8-bit RGB image (clamped to [0, 1], rounded), rows in the texture's order. */
Image colourImage(const Texture& texture);

/**
 * The normal channels as an 8-bit RGB normal map, c = (n + 1) / 2 (y negated first for NormalGreen::Up).
 * Throws sylva::Error when the texture has no normals.
 */
Image normalImage(const Texture& texture, NormalGreen green);

/**
 * Loads a photo: JPEG through OpenCV, PNG and EXR through sylva::loadImage. Throws a one-line sylva::Error
 * naming the file when it is missing, unreadable or empty.
 */
Image loadPhoto(const std::filesystem::path& path);

/**
 * Loads a colour photo and, if `normalPath` is not empty, its normal map (OpenGL convention, green up) into
 * one texture named after the colour file.
 */
Texture loadPhotoTexture(const std::filesystem::path& colourPath,
                         const std::filesystem::path& normalPath = {});

/** Rotates a normal's xy by `quarterTurns` × 90° counter-clockwise (x towards y). */
void rotateNormal(float* texel, int quarterTurns);

} // namespace sylva::texsynth
