// The wind field. Every operation here has a twin in shaders/common/wind.glsl, written in the same order with
// the same float types, so CPU and GPU agree to float rounding (the GL test checks 1e-4 m/s).
#include <sylva/wind/Wind.hpp>

#include <sylva/core/Random.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/JsonNode.hpp>

#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

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
