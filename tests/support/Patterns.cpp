#include "Patterns.hpp"

#include <cstdint>

namespace sylva::test {

Image patternImage(int width, int height, bool varyAlpha) {
  Image img(width, height, 4, PixelType::U8);
  auto* d = reinterpret_cast<std::uint8_t*>(img.data());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = d + (static_cast<std::size_t>(y) * width + x) * 4;
      p[0] = static_cast<std::uint8_t>(x * 7 + y * 3);
      p[1] = static_cast<std::uint8_t>(y * 13 + x);
      p[2] = static_cast<std::uint8_t>((x * y) & 255);
      p[3] = varyAlpha ? static_cast<std::uint8_t>(200 + (x + y) % 56) : 255;
    }
  }
  return img;
}

} // namespace sylva::test
