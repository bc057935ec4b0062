// The wind field. Every operation here has a twin in shaders/common/wind.glsl, written in the same order with
// the same float types, so CPU and GPU agree to float rounding (the GL test checks 1e-4 m/s).
#include <sylva/wind/Wind.hpp>

#include <sylva/core/Random.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/JsonNode.hpp>

#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::wind {
namespace {

/** Lattice value in [−1, 1] at integer point (i, j, k). */
float lattice(std::int32_t i, std::int32_t j, std::int32_t k, std::uint32_t seed) {
  const std::uint32_t h =
      lowbias32(static_cast<std::uint32_t>(i) * 73856093u ^ static_cast<std::uint32_t>(j) * 19349663u ^
                static_cast<std::uint32_t>(k) * 83492791u ^ lowbias32(seed));
  return static_cast<float>(h & 0xffffu) * (2.0f / 65535.0f) - 1.0f;
}

float smooth(float t) {
  return t * t * (3.0f - 2.0f * t);
}

float mix(float a, float b, float t) {
  return a + (b - a) * t;
}

void requireFinite(float v, const std::string& where, const char* field) {
  if (!std::isfinite(v)) {
    fail("{}.{}: must be a finite number", where, field);
  }
}

} // namespace

float valueNoise(glm::vec3 p, std::uint32_t seed) {
  const glm::vec3 f(std::floor(p.x), std::floor(p.y), std::floor(p.z));
  const std::int32_t i = static_cast<std::int32_t>(f.x);
  const std::int32_t j = static_cast<std::int32_t>(f.y);
  const std::int32_t k = static_cast<std::int32_t>(f.z);
  const float u = smooth(p.x - f.x);
  const float v = smooth(p.y - f.y);
  const float w = smooth(p.z - f.z);
  const float x00 = mix(lattice(i, j, k, seed), lattice(i + 1, j, k, seed), u);
  const float x10 = mix(lattice(i, j + 1, k, seed), lattice(i + 1, j + 1, k, seed), u);
  const float x01 = mix(lattice(i, j, k + 1, seed), lattice(i + 1, j, k + 1, seed), u);
  const float x11 = mix(lattice(i, j + 1, k + 1, seed), lattice(i + 1, j + 1, k + 1, seed), u);
  return mix(mix(x00, x10, v), mix(x01, x11, v), w);
}

void validate(const WindSettings& s, const std::string& where) {
  requireFinite(s.direction.x, where, "direction");
  requireFinite(s.direction.y, where, "direction");
  if (glm::length(s.direction) < 1e-6f) {
    fail("{}.direction: must not be zero", where);
  }
  const std::pair<float, const char*> nonNegative[] = {{s.speed, "speed"},
                                                       {s.gustStrength, "gustStrength"},
                                                       {s.gustTravel, "gustTravel"},
                                                       {s.turbulence, "turbulence"}};
  for (const auto& [v, name] : nonNegative) {
    requireFinite(v, where, name);
    if (v < 0.0f) {
      fail("{}.{}: must be ≥ 0, got {}", where, name, v);
    }
  }
  const std::pair<float, const char*> positive[] = {{s.gustLength, "gustLength"},
                                                    {s.gustWidth, "gustWidth"},
                                                    {s.turbulenceScale, "turbulenceScale"},
                                                    {s.turbulenceRate, "turbulenceRate"}};
  for (const auto& [v, name] : positive) {
    requireFinite(v, where, name);
    if (v <= 0.0f) {
      fail("{}.{}: must be > 0, got {}", where, name, v);
    }
  }
}

gpu::WindUniforms toUniforms(const WindSettings& s, float seconds) {
  validate(s);
  const glm::vec2 d = glm::normalize(s.direction);
  gpu::WindUniforms u{};
  u.flow = {d.x, d.y, s.speed, seconds};
  u.gusts = {s.gustStrength, s.gustLength, s.gustWidth, s.gustTravel * s.speed};
  u.turbulence = {s.turbulence, s.turbulenceScale, s.turbulenceRate, 0.0f};
  u.seed = {s.seed, 0u, 0u, 0u};
  return u;
}

float gustSpeed(const gpu::WindUniforms& wind, glm::vec2 position) {
  const glm::vec2 dir(wind.flow.x, wind.flow.y);
  const glm::vec2 across(-dir.y, dir.x);
  const float time = wind.flow.w;
  // Gust pattern in the wind's frame, advected downwind: the same gust reaches a point further downwind
  // later.
  const float along = (glm::dot(position, dir) - wind.gusts.w * time) / wind.gusts.y;
  const float side = glm::dot(position, across) / wind.gusts.z;
  const float n = valueNoise(glm::vec3(along, side, time * 0.05f), wind.seed.x);
  // Only the upper part of the noise makes gusts: calm between them.
  const float gust = glm::clamp(n * 1.6f - 0.2f, 0.0f, 1.0f);
  return wind.flow.z * (1.0f + wind.gusts.x * gust * gust);
}

glm::vec2 windVelocity(const gpu::WindUniforms& wind, glm::vec2 position) {
  const glm::vec2 dir(wind.flow.x, wind.flow.y);
  const float time = wind.flow.w;
  const glm::vec2 mean = dir * gustSpeed(wind, position);
  const glm::vec2 q = position / wind.turbulence.y;
  const float t = time * wind.turbulence.z;
  const float tx = valueNoise(glm::vec3(q.x, q.y, t), wind.seed.x + 1u);
  const float tz = valueNoise(glm::vec3(q.x + 31.7f, q.y - 17.3f, t), wind.seed.x + 2u);
  return mean + glm::vec2(tx, tz) * (wind.flow.z * wind.turbulence.x);
}

// ---- windVelocities: windVelocity eight points at a time
// ----------------------------------------------------- GCC/Clang vector types, operation for operation the
// scalar code above (no contractions: the x86-64 baseline and the AVX2 clone have no FMA), so every lane
// gives the scalar result bit for bit. Selects are done on the bits and floor by truncation (exact for |x| <
// 2^31). Vectors cross the helpers by reference only: passing 32-byte vectors by value would depend on
// whether AVX is enabled (an ABI difference both compilers reject).
namespace {

using F8 = float __attribute__((vector_size(32)));
using I8 = std::int32_t __attribute__((vector_size(32)));
using U8 = std::uint32_t __attribute__((vector_size(32)));

[[gnu::always_inline]] inline void floor8(const F8& x, F8& out) {
  const F8 t = __builtin_convertvector(__builtin_convertvector(x, I8), F8);
  // Truncation rounds negative non-integers up: one less there (the comparison's lanes are 0 or −1).
  out = t + __builtin_convertvector(static_cast<I8>(t > x), F8);
}

/** lattice() of eight lattice points. */
[[gnu::always_inline]] inline void lattice8(const U8& i, const U8& j, const U8& k, std::uint32_t hashedSeed,
                                            F8& out) {
  U8 h = i * 73856093u ^ j * 19349663u ^ k * 83492791u ^ hashedSeed;
  h ^= h >> 16; // lowbias32
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  out = __builtin_convertvector(h & 0xffffu, F8) * (2.0f / 65535.0f) - 1.0f;
}

/** valueNoise() at eight points (`hashedSeed`: lowbias32 of the seed). */
[[gnu::always_inline]] inline void valueNoise8(const F8& px, const F8& py, const F8& pz,
                                               std::uint32_t hashedSeed, F8& out) {
  F8 fx;
  F8 fy;
  F8 fz;
  floor8(px, fx);
  floor8(py, fy);
  floor8(pz, fz);
  const auto i = reinterpret_cast<U8>(__builtin_convertvector(fx, I8));
  const auto j = reinterpret_cast<U8>(__builtin_convertvector(fy, I8));
  const auto k = reinterpret_cast<U8>(__builtin_convertvector(fz, I8));
  const F8 du = px - fx;
  const F8 dv = py - fy;
  const F8 dw = pz - fz;
  const F8 u = du * du * (3.0f - 2.0f * du); // smooth
  const F8 v = dv * dv * (3.0f - 2.0f * dv);
  const F8 w = dw * dw * (3.0f - 2.0f * dw);
  const std::uint32_t s = hashedSeed;
  F8 l000;
  F8 l100;
  F8 l010;
  F8 l110;
  F8 l001;
  F8 l101;
  F8 l011;
  F8 l111;
  lattice8(i, j, k, s, l000);
  lattice8(i + 1u, j, k, s, l100);
  lattice8(i, j + 1u, k, s, l010);
  lattice8(i + 1u, j + 1u, k, s, l110);
  lattice8(i, j, k + 1u, s, l001);
  lattice8(i + 1u, j, k + 1u, s, l101);
  lattice8(i, j + 1u, k + 1u, s, l011);
  lattice8(i + 1u, j + 1u, k + 1u, s, l111);
  // mix(a, b, t) = a + (b − a)·t
  const F8 x00 = l000 + (l100 - l000) * u;
  const F8 x10 = l010 + (l110 - l010) * u;
  const F8 x01 = l001 + (l101 - l001) * u;
  const F8 x11 = l011 + (l111 - l011) * u;
  const F8 y0 = x00 + (x10 - x00) * v;
  const F8 y1 = x01 + (x11 - x01) * v;
  out = y0 + (y1 - y0) * w;
}

// target_clones dispatches through an ifunc resolver, which runs before ThreadSanitizer's runtime is up and
// crashes every TSan binary at load; TSan builds take the baseline code (same results, bit for bit).
#if defined(__SANITIZE_THREAD__)
#define SYLVA_WIND_NO_CLONES 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define SYLVA_WIND_NO_CLONES 1
#endif
#endif
#if defined(__x86_64__) && !defined(SYLVA_WIND_NO_CLONES)
__attribute__((target_clones("avx2", "default")))
#endif
void windBatch(const gpu::WindUniforms& wind, const glm::vec2* positions, const float* offsets, glm::vec2* out,
               std::size_t count) {
  const float dx = wind.flow.x;
  const float dz = wind.flow.y;
  const std::uint32_t gustSeed = lowbias32(wind.seed.x);
  const std::uint32_t seedX = lowbias32(wind.seed.x + 1u);
  const std::uint32_t seedZ = lowbias32(wind.seed.x + 2u);
  const float turbulence = wind.flow.z * wind.turbulence.x;
  const I8 one = reinterpret_cast<I8>(F8{} + 1.0f);
  for (std::size_t first = 0; first < count; first += 8) {
    F8 px{};
    F8 pz{};
    F8 offset{};
    for (std::size_t l = 0; l < 8; ++l) {
      const std::size_t i = std::min(first + l, count - 1);
      px[l] = positions[i].x;
      pz[l] = positions[i].y;
      offset[l] = offsets != nullptr ? offsets[i] : 0.0f;
    }
    const F8 time = wind.flow.w + offset; // flow.w + 0 is flow.w
    // gustSpeed
    const F8 along = (px * dx + pz * dz - wind.gusts.w * time) / wind.gusts.y;
    const F8 side = (px * -dz + pz * dx) / wind.gusts.z;
    F8 n;
    valueNoise8(along, side, time * 0.05f, gustSeed, n);
    F8 gust = n * 1.6f - 0.2f;
    // clamp(gust, 0, 1): max(x, 0) then min(x, 1), as glm::clamp (+0 where below).
    gust = reinterpret_cast<F8>(~static_cast<I8>(gust < 0.0f) & reinterpret_cast<I8>(gust));
    const I8 above = static_cast<I8>(1.0f < gust);
    gust = reinterpret_cast<F8>((above & one) | (~above & reinterpret_cast<I8>(gust)));
    const F8 speed = wind.flow.z * (1.0f + wind.gusts.x * gust * gust);
    // windVelocity
    const F8 qx = px / wind.turbulence.y;
    const F8 qy = pz / wind.turbulence.y;
    const F8 t = time * wind.turbulence.z;
    F8 tx;
    F8 tz;
    valueNoise8(qx, qy, t, seedX, tx);
    valueNoise8(qx + 31.7f, qy - 17.3f, t, seedZ, tz);
    const F8 ux = dx * speed + tx * turbulence;
    const F8 uz = dz * speed + tz * turbulence;
    for (std::size_t l = 0; l < 8 && first + l < count; ++l) {
      out[first + l] = glm::vec2(ux[l], uz[l]);
    }
  }
}

} // namespace

void windVelocities(const gpu::WindUniforms& wind, std::span<const glm::vec2> positions,
                    std::span<const float> timeOffsets, std::span<glm::vec2> out) {
  if (out.size() != positions.size() || (!timeOffsets.empty() && timeOffsets.size() != positions.size())) {
    fail("windVelocities: {} positions, {} time offsets and {} outputs", positions.size(), timeOffsets.size(),
         out.size());
  }
  if (positions.empty()) {
    return;
  }
  windBatch(wind, positions.data(), timeOffsets.empty() ? nullptr : timeOffsets.data(), out.data(),
            positions.size());
}

nlohmann::json toJson(const WindSettings& s) {
  return {{"direction", {s.direction.x, s.direction.y}},
          {"speed", s.speed},
          {"gustStrength", s.gustStrength},
          {"gustLength", s.gustLength},
          {"gustWidth", s.gustWidth},
          {"gustTravel", s.gustTravel},
          {"turbulence", s.turbulence},
          {"turbulenceScale", s.turbulenceScale},
          {"turbulenceRate", s.turbulenceRate},
          {"seed", s.seed}};
}

WindSettings windSettingsFromJson(const nlohmann::json& json, const std::string& where) {
  const JsonNode root(json, where, "");
  root.object({"direction", "speed", "gustStrength", "gustLength", "gustWidth", "gustTravel", "turbulence",
               "turbulenceScale", "turbulenceRate", "seed"});
  WindSettings s;
  if (root.has("direction")) {
    const JsonNode d = root["direction"];
    d.arrayOf(2, "x, z");
    s.direction = {static_cast<float>(d[std::size_t{0}].number()), static_cast<float>(d[1].number())};
  }
  const std::pair<const char*, float*> fields[] = {{"speed", &s.speed},
                                                   {"gustStrength", &s.gustStrength},
                                                   {"gustLength", &s.gustLength},
                                                   {"gustWidth", &s.gustWidth},
                                                   {"gustTravel", &s.gustTravel},
                                                   {"turbulence", &s.turbulence},
                                                   {"turbulenceScale", &s.turbulenceScale},
                                                   {"turbulenceRate", &s.turbulenceRate}};
  for (const auto& [name, value] : fields) {
    if (root.has(name)) {
      *value = static_cast<float>(root[name].number());
    }
  }
  if (root.has("seed")) {
    s.seed = static_cast<std::uint32_t>(root["seed"].integer(0, 2147483647));
  }
  validate(s, where);
  return s;
}

} // namespace sylva::wind
