// Procedural inputs of the shipped folding examples (their PNGs are committed under data/folding/).
#include <sylva/folding/Examples.hpp>

#include <sylva/core/Random.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::folding {

namespace {

/** Value noise in [0, 1) on an integer lattice of cell `scale` pixels, smoothstep-interpolated. */
double valueNoise(double x, double y, double scale, std::uint64_t seed) {
  x /= scale;
  y /= scale;
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  auto lattice = [&](double i, double j) {
    const auto key = static_cast<std::uint64_t>(static_cast<std::int64_t>(i) * 73856093LL) ^
                     static_cast<std::uint64_t>(static_cast<std::int64_t>(j) * 19349663LL);
    return static_cast<double>(hash64(key ^ hash64(seed)) >> 11) * 0x1.0p-53;
  };
  auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
  const double tx = smooth(x - fx);
  const double ty = smooth(y - fy);
  const double a = lattice(fx, fy) + (lattice(fx + 1, fy) - lattice(fx, fy)) * tx;
  const double b = lattice(fx, fy + 1) + (lattice(fx + 1, fy + 1) - lattice(fx, fy + 1)) * tx;
  return a + (b - a) * ty;
}

double fbm(double x, double y, double scale, std::uint64_t seed, int octaves = 4) {
  double sum = 0.0;
  double amp = 0.5;
  double norm = 0.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * valueNoise(x, y, scale, seed + static_cast<std::uint64_t>(o) * 977);
    norm += amp;
    amp *= 0.5;
    scale *= 0.5;
  }
  return sum / norm;
}

void put(Image& img, int x, int y, glm::dvec3 c, double alpha = 1.0) {
  auto* d = reinterpret_cast<std::uint8_t*>(img.data()) + (static_cast<std::size_t>(y) * img.width() + x) * 4;
  for (int i = 0; i < 3; ++i) {
    d[i] = static_cast<std::uint8_t>(std::clamp(std::lround(c[i] * 255.0), 0L, 255L));
  }
  d[3] = static_cast<std::uint8_t>(std::clamp(std::lround(alpha * 255.0), 0L, 255L));
}

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

} // namespace

double beachShoreline(double x, int width, int height) {
  const double u = x / width;
  return height * (0.46 + 0.035 * std::sin(2.0 * std::numbers::pi * (1.3 * u + 0.1)) +
                   0.02 * std::sin(2.0 * std::numbers::pi * 3.1 * u));
}

Image beachImage(int width, int height, std::uint64_t seed) {
  Image img(width, height, 4, PixelType::U8);
  const glm::dvec3 deep(0.05, 0.22, 0.36);
  const glm::dvec3 shallow(0.16, 0.50, 0.55);
  const glm::dvec3 foam(0.92, 0.95, 0.94);
  const glm::dvec3 wet(0.55, 0.45, 0.32);
  const glm::dvec3 dry(0.86, 0.76, 0.56);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double shore = beachShoreline(x + 0.5, width, height);
      const double d = (y + 0.5) - shore; // < 0: water
      const double n = fbm(x, y, 32.0, seed);
      const double grain = valueNoise(x, y, 1.5, seed + 5);
      glm::dvec3 c;
      if (d < 0.0) {
        // Water: deep to shallow towards the shore, ripples, and a foam band along the shore.
        const double depth = std::clamp(-d / (0.4 * height), 0.0, 1.0);
        c = glm::mix(shallow, deep, depth);
        c *= 0.9 + 0.2 * fbm(x * 0.5, y * 2.0, 24.0, seed + 11);
        const double ripple = 0.5 + 0.5 * std::sin(0.25 * y + 4.0 * n);
        c += 0.04 * ripple;
        const double foamBand = smoothstep(-0.12 * height, -0.01 * height, d);
        const double lace = smoothstep(0.45, 0.7, fbm(x, y * 1.5, 10.0, seed + 13));
        c = glm::mix(c, foam, foamBand * (0.35 + 0.65 * lace));
      } else {
        // Sand: wet near the water, dry further up, speckled.
        const double wetness = 1.0 - smoothstep(0.0, 0.14 * height * (0.7 + 0.6 * n), d);
        c = glm::mix(dry, wet, wetness);
        c *= 0.92 + 0.12 * n + 0.06 * (grain - 0.5);
      }
      put(img, x, y, c);
    }
  }
  // Shells on the wet sand: grey-white ellipses the swash will cover.
  Rng rng(seed + 101);
  for (int s = 0; s < 9; ++s) {
    const double cx = rng.uniform(0.05f, 0.95f) * width;
    const double cy = beachShoreline(cx, width, height) + rng.uniform(0.02f, 0.16f) * height;
    const double rx = rng.uniform(3.0f, 6.0f);
    const double ry = rx * 0.7;
    for (int y = static_cast<int>(cy - ry - 1); y <= static_cast<int>(cy + ry + 1); ++y) {
      for (int x = static_cast<int>(cx - rx - 1); x <= static_cast<int>(cx + rx + 1); ++x) {
        if (x < 0 || y < 0 || x >= width || y >= height) {
          continue;
        }
        const double q = std::pow((x + 0.5 - cx) / rx, 2.0) + std::pow((y + 0.5 - cy) / ry, 2.0);
        if (q <= 1.0) {
          const double ridge = 0.5 + 0.5 * std::cos(6.0 * std::atan2(y + 0.5 - cy, x + 0.5 - cx));
          put(img, x, y, glm::dvec3(0.80, 0.78, 0.74) * (0.8 + 0.2 * ridge) * (1.0 - 0.25 * q));
        }
      }
    }
  }
  return img;
}

Image meadowImage(int width, int height, std::uint64_t seed) {
  Image img(width, height, 4, PixelType::U8);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) / width;
      const double v = (y + 0.5) / height;
      const double hill = 0.62 + 0.06 * std::sin(2.0 * std::numbers::pi * (1.2 * u + 0.2)) +
                          0.03 * std::sin(2.0 * std::numbers::pi * 3.7 * u);
      glm::dvec3 c;
      if (v < hill) {
        c = glm::mix(glm::dvec3(0.33, 0.55, 0.85), glm::dvec3(0.75, 0.86, 0.95), v / hill);
        const double cloud = smoothstep(0.55, 0.75, fbm(x * 0.6, y * 1.6, 48.0, seed + 3));
        c = glm::mix(c, glm::dvec3(0.97), cloud * (1.0 - v / hill));
      } else {
        const double n = fbm(x, y, 16.0, seed + 7);
        c = glm::mix(glm::dvec3(0.30, 0.52, 0.20), glm::dvec3(0.18, 0.38, 0.12), (v - hill) / (1.0 - hill));
        c *= 0.85 + 0.3 * n;
        if (valueNoise(x, y, 2.0, seed + 9) > 0.93) {
          c = glm::dvec3(0.95, 0.85, 0.3); // flowers
        }
      }
      put(img, x, y, c);
    }
  }
  return img;
}

Image birdImage(int width, int height) {
  Image img(width, height, 4, PixelType::U8);
  const double w = width;
  const double h = height;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double px = (x + 0.5) / w;
      const double py = (y + 0.5) / h;
      // Body: an ellipse; head: a circle at the front (right); wing: a triangle up and back; tail: a wedge.
      const bool body = std::pow((px - 0.5) / 0.30, 2.0) + std::pow((py - 0.68) / 0.14, 2.0) <= 1.0;
      const bool head = std::pow((px - 0.80) / 0.10, 2.0) + std::pow((py - 0.56) / 0.16, 2.0) <= 1.0;
      // Wing raised and swept back: between a parabola through its tip and the back, above the body.
      const double wingTop = 0.06 + 4.5 * (px - 0.36) * (px - 0.36) + 0.25 * std::max(0.0, px - 0.36);
      const bool wing = px > 0.22 && px < 0.64 && py > wingTop && py < 0.62 - 0.2 * (px - 0.45);
      const bool tail = px < 0.24 && px > 0.06 && std::abs(py - 0.66) < 0.5 * (0.24 - px) + 0.03;
      const bool beak = px > 0.88 && px < 0.98 && std::abs(py - 0.58) < 0.4 * (0.98 - px);
      if (beak) {
        put(img, x, y, glm::dvec3(0.95, 0.65, 0.10));
      } else if (head || body || wing || tail) {
        const double shade = wing ? 0.75 + 0.25 * py : 1.0;
        put(img, x, y, glm::dvec3(0.20, 0.18, 0.22) * shade + (head ? glm::dvec3(0.05) : glm::dvec3(0.0)));
        if (head && std::pow((px - 0.83) / 0.025, 2.0) + std::pow((py - 0.50) / 0.05, 2.0) <= 1.0) {
          put(img, x, y, glm::dvec3(0.95));
        }
      } else {
        put(img, x, y, glm::dvec3(0.0), 0.0);
      }
    }
  }
  return img;
}

} // namespace sylva::folding
