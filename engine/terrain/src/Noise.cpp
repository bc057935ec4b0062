#include <sylva/terrain/Noise.hpp>

#include <sylva/terrain/HeightSources.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/JsonNode.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Random.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sylva::terrain {
namespace {

constexpr int kMaxOctaves = 16;
constexpr int kNoiseFileVersion = 1;
// Largest |perlin| for the 8 gradients below is 1 (reached only at isolated points); scaling by this keeps
// the mapped value in [0, 1] before the safety clamp.
constexpr double kPerlinToUnit = 0.5;

/** Quintic fade 6t⁵ − 15t⁴ + 10t³ (improved Perlin noise, 2002). */
double fade(double t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}
double lerp(double a, double b, double t) {
  return a + t * (b - a);
}

/** Dot product of one of 8 lattice gradients with the offset (dx, dz). */
double grad(std::uint8_t hash, double dx, double dz) {
  switch (hash & 7u) {
  case 0:
    return dx + dz;
  case 1:
    return -dx + dz;
  case 2:
    return dx - dz;
  case 3:
    return -dx - dz;
  case 4:
    return dx;
  case 5:
    return -dx;
  case 6:
    return dz;
  default:
    return -dz;
  }
}

} // namespace

ProceduralSpec defaultLandscapeSpec(std::uint64_t seed) {
  ProceduralSpec spec;
  spec.seed = seed;
  spec.type = ProceduralSpec::Type::Warped;
  spec.octaves = 8;
  spec.frequency = 1.0f / 700.0f;
  spec.warpStrength = 150.0f;
  spec.heightScale = 400.0f;
  return spec;
}

const char* procedureTypeName(ProceduralSpec::Type type) {
  switch (type) {
  case ProceduralSpec::Type::Fbm:
    return "fbm";
  case ProceduralSpec::Type::Ridged:
    return "ridged";
  case ProceduralSpec::Type::Warped:
    return "warped";
  }
  return "?";
}

void validate(const ProceduralSpec& spec, const std::string& where) {
  const auto finite = [](float v) { return std::isfinite(v); };
  if (spec.octaves < 1 || spec.octaves > kMaxOctaves) {
    fail("{}: /octaves: {} is not in 1..{}", where, spec.octaves, kMaxOctaves);
  }
  if (!finite(spec.frequency) || spec.frequency <= 0.0f) {
    fail("{}: /frequency: {} must be finite and > 0 cycles per metre", where, spec.frequency);
  }
  if (!finite(spec.lacunarity) || spec.lacunarity < 1.0f) {
    fail("{}: /lacunarity: {} must be finite and >= 1", where, spec.lacunarity);
  }
  if (!finite(spec.gain) || spec.gain <= 0.0f || spec.gain > 1.0f) {
    fail("{}: /gain: {} must be in (0, 1]", where, spec.gain);
  }
  if (!finite(spec.warpStrength) || spec.warpStrength < 0.0f) {
    fail("{}: /warpStrength: {} must be finite and >= 0 metres", where, spec.warpStrength);
  }
  if (!finite(spec.heightScale) || spec.heightScale <= 0.0f) {
    fail("{}: /heightScale: {} must be finite and > 0 metres", where, spec.heightScale);
  }
  if (spec.type != ProceduralSpec::Type::Fbm && spec.type != ProceduralSpec::Type::Ridged &&
      spec.type != ProceduralSpec::Type::Warped) {
    fail("{}: /type: not fbm, ridged or warped", where);
  }
}

ProceduralNoise::ProceduralNoise(const ProceduralSpec& spec) : mSpec(spec) {
  validate(spec);
  for (std::size_t t = 0; t < mPerm.size(); ++t) {
    // Fisher–Yates with sylva::Rng::below: std:: shuffles and distributions differ between standard
    // libraries.
    Rng rng(hash64(spec.seed ^ (0x9e3779b97f4a7c15ULL * (t + 1))), 0x5eed0000ULL + t);
    std::array<std::uint8_t, 256> p{};
    for (std::size_t i = 0; i < p.size(); ++i) {
      p[i] = static_cast<std::uint8_t>(i);
    }
    for (std::uint32_t i = 255; i > 0; --i) {
      std::swap(p[i], p[rng.below(i + 1)]);
    }
    for (std::size_t i = 0; i < 512; ++i) {
      mPerm[t][i] = p[i & 255u];
    }
  }
  Rng offsets(hash64(spec.seed), 0x0ff5e75ULL);
  for (auto& offset : mOffsets) {
    offset = {256.0 * offsets.uniform(), 256.0 * offsets.uniform()};
  }
}

double ProceduralNoise::perlin(int table, double x, double z) const {
  const double fx = std::floor(x);
  const double fz = std::floor(z);
  // Lattice indices wrap every 256 cells. Reducing in double first keeps the conversion in range for any
  // finite coordinate (negative ones included); the & absorbs a rounding to exactly 256.
  const auto wrap = [](double f) { return static_cast<unsigned>(f - 256.0 * std::floor(f / 256.0)) & 255u; };
  const unsigned ix = wrap(fx);
  const unsigned iz = wrap(fz);
  const double dx = x - fx;
  const double dz = z - fz;
  const auto& p = mPerm[static_cast<std::size_t>(table)];
  const std::uint8_t h00 = p[p[ix] + iz];
  const std::uint8_t h10 = p[p[ix + 1] + iz];
  const std::uint8_t h01 = p[p[ix] + iz + 1];
  const std::uint8_t h11 = p[p[ix + 1] + iz + 1];
  const double u = fade(dx);
  const double v = fade(dz);
  return lerp(lerp(grad(h00, dx, dz), grad(h10, dx - 1.0, dz), u),
              lerp(grad(h01, dx, dz - 1.0), grad(h11, dx - 1.0, dz - 1.0), u), v);
}

double ProceduralNoise::fbm(int table, double x, double z) const {
  double sum = 0.0;
  double norm = 0.0;
  double amplitude = 1.0;
  double frequency = mSpec.frequency;
  for (int o = 0; o < mSpec.octaves; ++o) {
    const auto& offset = mOffsets[static_cast<std::size_t>(o)];
    sum += amplitude * perlin(table, x * frequency + offset[0], z * frequency + offset[1]);
    norm += amplitude;
    amplitude *= mSpec.gain;
    frequency *= mSpec.lacunarity;
  }
  return sum / norm; // [-1, 1]
}

double ProceduralNoise::ridged(double x, double z) const {
  double sum = 0.0;
  double norm = 0.0;
  double amplitude = 1.0;
  double frequency = mSpec.frequency;
  double weight = 1.0;
  for (int o = 0; o < mSpec.octaves; ++o) {
    const auto& offset = mOffsets[static_cast<std::size_t>(o)];
    double signal = 1.0 - std::abs(perlin(0, x * frequency + offset[0], z * frequency + offset[1]));
    signal *= signal;
    // Musgrave's weighting: detail appears on the crests, valleys stay smooth.
    signal *= weight;
    weight = std::clamp(signal * 2.0, 0.0, 1.0);
    sum += amplitude * signal;
    norm += amplitude;
    amplitude *= mSpec.gain;
    frequency *= mSpec.lacunarity;
  }
  return sum / norm; // [0, 1]
}

float ProceduralNoise::sample(double x, double z) const {
  if (!std::isfinite(x) || !std::isfinite(z)) {
    return std::numeric_limits<float>::quiet_NaN();
  }
  double unit = 0.0;
  switch (mSpec.type) {
  case ProceduralSpec::Type::Fbm:
    unit = 0.5 + kPerlinToUnit * fbm(0, x, z);
    break;
  case ProceduralSpec::Type::Ridged:
    unit = ridged(x, z);
    break;
  case ProceduralSpec::Type::Warped: {
    const double wx = x + mSpec.warpStrength * fbm(1, x, z);
    const double wz = z + mSpec.warpStrength * fbm(2, x, z);
    unit = 0.5 + kPerlinToUnit * fbm(0, wx, wz);
    break;
  }
  }
  return static_cast<float>(std::clamp(unit, 0.0, 1.0) * mSpec.heightScale);
}

float sample(const ProceduralSpec& spec, double x, double z) {
  return ProceduralNoise(spec).sample(x, z);
}

HeightField generate(const ProceduralSpec& spec, double originX, double originZ, int width, int height,
                     float spacing) {
  const ProceduralNoise noise(spec);
  if (width < 1 || height < 1 || width > kMaxHeightFieldSide || height > kMaxHeightFieldSide) {
    fail("generate: size {}x{} is out of range (1..{} per side)", width, height, kMaxHeightFieldSide);
  }
  if (!std::isfinite(spacing) || spacing <= 0.0f) {
    fail("generate: spacing {} must be finite and > 0 metres", spacing);
  }
  if (!std::isfinite(originX) || !std::isfinite(originZ)) {
    fail("generate: origin ({}, {}) must be finite", originX, originZ);
  }
  const double step = spacing;
  // World position of sample n along one axis. On the lattice, (k0 + n) · step is evaluated from the global
  // sample index, so every tiling computes the same double for the same sample.
  const auto axis = [step](double origin) {
    const double k = origin / step;
    const double r = std::round(k);
    const bool onLattice = std::abs(k - r) <= 1e-9 * std::max(1.0, std::abs(k)) && std::abs(r) < 0x1p52;
    return [=](int n) { return onLattice ? (r + n) * step : origin + n * step; };
  };
  const auto worldX = axis(originX);
  const auto worldZ = axis(originZ);
  HeightField field(width, height, spacing, spacing);
  float* out = field.samples().data();
  parallelFor(
      static_cast<std::size_t>(height),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
          const double z = worldZ(static_cast<int>(j));
          for (int i = 0; i < width; ++i) {
            out[j * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)] =
                noise.sample(worldX(i), z);
          }
        }
      },
      std::max<std::size_t>(1, 4096 / static_cast<std::size_t>(width)));
  return field;
}

nlohmann::json toJson(const ProceduralSpec& spec) {
  return {{"version", kNoiseFileVersion},
          {"seed", spec.seed},
          {"type", procedureTypeName(spec.type)},
          {"octaves", spec.octaves},
          {"frequency", spec.frequency},
          {"lacunarity", spec.lacunarity},
          {"gain", spec.gain},
          {"warpStrength", spec.warpStrength},
          {"heightScale", spec.heightScale}};
}

ProceduralSpec proceduralSpecFromJson(const nlohmann::json& json, const std::string& where) {
  requireJsonVersion(json, kNoiseFileVersion, where);
  const JsonNode root(json, where);
  root.object({"version", "seed", "type", "octaves", "frequency", "lacunarity", "gain", "warpStrength",
               "heightScale"});
  ProceduralSpec spec;
  const float limit = std::numeric_limits<float>::max();
  if (root.has("seed")) {
    spec.seed = root["seed"].unsignedInteger();
  }
  if (root.has("type")) {
    const std::string name = root["type"].choice({"fbm", "ridged", "warped"});
    spec.type = name == "fbm"      ? ProceduralSpec::Type::Fbm
                : name == "ridged" ? ProceduralSpec::Type::Ridged
                                   : ProceduralSpec::Type::Warped;
  }
  if (root.has("octaves")) {
    spec.octaves = root["octaves"].integer(1, kMaxOctaves);
  }
  for (auto [key, out] : {std::pair{"frequency", &spec.frequency},
                          {"lacunarity", &spec.lacunarity},
                          {"gain", &spec.gain},
                          {"warpStrength", &spec.warpStrength},
                          {"heightScale", &spec.heightScale}}) {
    if (root.has(key)) {
      *out = root[key].real(-limit, limit);
    }
  }
  validate(spec, where);
  return spec;
}

ProceduralSpec loadProceduralSpec(const std::filesystem::path& path) {
  return proceduralSpecFromJson(loadJsonFile(path), path.string());
}

void saveProceduralSpec(const std::filesystem::path& path, const ProceduralSpec& spec) {
  validate(spec, path.string());
  saveJsonFile(path, toJson(spec));
}

} // namespace sylva::terrain
