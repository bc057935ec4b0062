#include <sylva/gl/Texture.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <bit>

namespace sylva::gl {

GLenum pixelFormatFor(int channels) {
  static constexpr GLenum kFormats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  if (channels < 1 || channels > 4) {
    fail("gl: unsupported channel count {}", channels);
  }
  return kFormats[channels - 1];
}

GLenum pixelTypeFor(PixelType type) {
  switch (type) {
  case PixelType::U8:
    return GL_UNSIGNED_BYTE;
  case PixelType::U16:
    return GL_UNSIGNED_SHORT;
  case PixelType::F32:
    return GL_FLOAT;
  }
  return GL_UNSIGNED_BYTE;
}

GLenum internalFormatFor(int channels, PixelType type) {
  static constexpr GLenum kU8[] = {GL_R8, GL_RG8, GL_RGB8, GL_RGBA8};
  static constexpr GLenum kU16[] = {GL_R16, GL_RG16, GL_RGB16, GL_RGBA16};
  static constexpr GLenum kF32[] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
  pixelFormatFor(channels); // validates
  switch (type) {
  case PixelType::U8:
    return kU8[channels - 1];
  case PixelType::U16:
    return kU16[channels - 1];
  case PixelType::F32:
    return kF32[channels - 1];
  }
  return GL_RGBA8;
}

Texture::Texture(GLenum target, GLenum format, int width, int height, int layers)
    : mTarget(target), mFormat(format), mWidth(width), mHeight(height), mLayers(layers) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  static_cast<Object&>(*this) = Object(id);
}

static void checkSize(int width, int height, int layers) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (width <= 0 || height <= 0 || width > maxSize || height > maxSize || layers <= 0) {
    fail("gl::Texture: size {}x{}x{} is out of range (max {} per side)", width, height, layers, maxSize);
  }
}

Texture Texture::create2D(GLenum internalFormat, int width, int height, int levels) {
  checkSize(width, height, 1);
  Texture texture(GL_TEXTURE_2D, internalFormat, width, height, 1);
  glTextureStorage2D(texture.id(), std::max(levels, 1), internalFormat, width, height);
  texture.setSampler({});
  return texture;
}

Texture Texture::create2DArray(GLenum internalFormat, int width, int height, int layers, int levels) {
  checkSize(width, height, layers);
  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  if (layers > maxLayers) {
    fail("gl::Texture: {} array layers exceed the driver's limit of {}", layers, maxLayers);
  }
  Texture texture(GL_TEXTURE_2D_ARRAY, internalFormat, width, height, layers);
  glTextureStorage3D(texture.id(), std::max(levels, 1), internalFormat, width, height, layers);
  texture.setSampler({});
  return texture;
}

Texture Texture::fromImage(const Image& image, bool mipmaps) {
  const int levels =
      mipmaps
          ? static_cast<int>(std::bit_width(static_cast<unsigned>(std::max(image.width(), image.height()))))
          : 1;
  Texture texture =
      create2D(internalFormatFor(image.channels(), image.type()), image.width(), image.height(), levels);
  texture.upload(image);
  if (mipmaps) {
    texture.generateMipmaps();
    texture.setSampler({GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT});
  }
  return texture;
}

void Texture::upload(const Image& image, int level, int layer) {
  const int w = std::max(1, mWidth >> level);
  const int h = std::max(1, mHeight >> level);
  if (image.width() != w || image.height() != h) {
    fail("gl::Texture: upload of {}x{} into level {} of size {}x{}", image.width(), image.height(), level, w,
         h);
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const GLenum format = pixelFormatFor(image.channels());
  const GLenum type = pixelTypeFor(image.type());
  if (mTarget == GL_TEXTURE_2D_ARRAY) {
    glTextureSubImage3D(id(), level, 0, 0, layer, w, h, 1, format, type, image.data());
  } else {
    glTextureSubImage2D(id(), level, 0, 0, w, h, format, type, image.data());
  }
}

void Texture::setSampler(const SamplerState& state) {
  glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, static_cast<GLint>(state.minFilter));
  glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, static_cast<GLint>(state.magFilter));
  glTextureParameteri(id(), GL_TEXTURE_WRAP_S, static_cast<GLint>(state.wrap));
  glTextureParameteri(id(), GL_TEXTURE_WRAP_T, static_cast<GLint>(state.wrap));
}

void Texture::generateMipmaps() {
  glGenerateTextureMipmap(id());
}

void Texture::bind(GLuint unit) const {
  glBindTextureUnit(unit, id());
}

void Texture::bindImage(GLuint unit, GLenum access, int level, GLenum format) const {
  glBindImageTexture(unit, id(), level, mTarget == GL_TEXTURE_2D_ARRAY ? GL_TRUE : GL_FALSE, 0, access,
                     format != 0 ? format : mFormat);
}

Image Texture::download(int channels, PixelType type, int level, int layer) const {
  const int w = std::max(1, mWidth >> level);
  const int h = std::max(1, mHeight >> level);
  Image image(w, h, channels, type);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureSubImage(id(), level, 0, 0, mTarget == GL_TEXTURE_2D_ARRAY ? layer : 0, w, h, 1,
                       pixelFormatFor(channels), pixelTypeFor(type), static_cast<GLsizei>(image.byteSize()),
                       image.data());
  return image;
}

} // namespace sylva::gl
