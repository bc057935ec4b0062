#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/gl/Object.hpp>

namespace sylva::gl {

/** Sampling parameters applied with glTextureParameteri. */
struct SamplerState {
  GLenum minFilter = GL_LINEAR;   ///< GL_TEXTURE_MIN_FILTER
  GLenum magFilter = GL_LINEAR;   ///< GL_TEXTURE_MAG_FILTER
  GLenum wrap = GL_CLAMP_TO_EDGE; ///< GL_TEXTURE_WRAP_S/T/R
};

/**
 * Immutable-storage texture (glTextureStorage2D/3D): 2D, 2D array (layers = texture array slices), or 3D.
 * Sizes are in texels. Move-only.
 */
class Texture : public Object<detail::deleteTexture> {
public:
  /** An empty wrapper (no GL object; no context needed), to be assigned later. */
  explicit Texture(NoCreateT) {}
  /** A 2D texture with `levels` mip levels of `internalFormat` (e.g. GL_RGBA8, GL_R32F). */
  static Texture create2D(GLenum internalFormat, int width, int height, int levels = 1);
  /** A 2D array texture of `layers` slices. */
  static Texture create2DArray(GLenum internalFormat, int width, int height, int layers, int levels = 1);
  /** A 2D texture holding `image` (R/RG/RGB/RGBA of 8-bit, 16-bit unorm or float), optionally with mips. */
  static Texture fromImage(const Image& image, bool mipmaps = false);

  GLenum target() const { return mTarget; }         ///< GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY or GL_TEXTURE_3D
  GLenum internalFormat() const { return mFormat; } ///< e.g. GL_RGBA8
  int width() const { return mWidth; }              ///< texels of level 0
  int height() const { return mHeight; }            ///< texels of level 0
  int layers() const { return mLayers; }            ///< array slices (or depth); 1 for 2D

  /** Uploads `image` into mip `level` (and `layer` for arrays); sizes must match that level. */
  void upload(const Image& image, int level = 0, int layer = 0);
  /** Sets the filters and wrap mode. */
  void setSampler(const SamplerState& state);
  /** Fills the mip levels below 0 from level 0 (glGenerateTextureMipmap). */
  void generateMipmaps();
  /** Binds for sampling at texture unit `unit`. */
  void bind(GLuint unit) const;
  /** Binds level `level` as an image for load/store; `format` defaults to the internal format. */
  void bindImage(GLuint unit, GLenum access, int level = 0, GLenum format = 0) const;
  /**
   * Reads mip `level` (layer 0, or `layer` for arrays) back to an Image with `channels` channels of `type`
   * (rows bottom-up as GL stores them; call Image::flipVertically() for file order).
   */
  Image download(int channels, PixelType type, int level = 0, int layer = 0) const;

private:
  Texture(GLenum target, GLenum format, int width, int height, int layers);
  GLenum mTarget = GL_TEXTURE_2D;
  GLenum mFormat = 0;
  int mWidth = 0;
  int mHeight = 0;
  int mLayers = 1;
};

/** GL pixel format/type for `channels` channels of `type` (e.g. 3 × U8 → GL_RGB, GL_UNSIGNED_BYTE). */
GLenum pixelFormatFor(int channels);
/** GL pixel type for channel type `type` (U8 → GL_UNSIGNED_BYTE, …). */
GLenum pixelTypeFor(PixelType type);
/** A sized internal format that stores `channels` × `type` losslessly (e.g. GL_RGBA16, GL_R32F). */
GLenum internalFormatFor(int channels, PixelType type);

} // namespace sylva::gl
