#pragma once
// One wind field for everything that moves in it (grass, trees): a mean flow, coherent gusts that travel
// downwind, and turbulence. windVelocity() here and windVelocity() in shaders/common/wind.glsl perform the
// same float operations, so a blade bent on the GPU and a simulated one on the CPU feel the same wind.

#include <shared/Wind.h>

#include <nlohmann/json_fwd.hpp>

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <string>

namespace sylva::wind {

/** What a user sets (scene files, the viewer, the CLI). Directions in world (x, z); y is up. */
struct WindSettings {
  /** Direction the wind blows towards, world (x, z); normalised on use. */
  glm::vec2 direction{1.0f, 0.0f};
  /** Mean speed, m/s (3: a gentle breeze, 10: strong). */
  float speed = 3.0f;
  /** Speed added at a gust's peak, as a fraction of the mean speed. */
  float gustStrength = 0.8f;
  /** Gust size along the wind, metres. */
  float gustLength = 20.0f;
  /** Gust size across the wind, metres. */
  float gustWidth = 10.0f;
  /** Gusts travel downwind at this fraction of the mean speed. */
  float gustTravel = 1.0f;
  /** Turbulence strength as a fraction of the mean speed. */
  float turbulence = 0.25f;
  /** Turbulence eddy size, metres. */
  float turbulenceScale = 2.0f;
  /** Turbulence rate, Hz. */
  float turbulenceRate = 0.7f;
  /** Seed of the gust and turbulence noise (the same seed gives the same wind everywhere). */
  std::uint32_t seed = 1;
};

/**
 * Throws sylva::Error "<where>.<field>: …" for non-finite values, a zero direction, negative speeds or
 * strengths, and non-positive sizes or rates.
 */
void validate(const WindSettings& settings, const std::string& where = "wind");

/** The uniforms for time `seconds` (validated settings). */
gpu::WindUniforms toUniforms(const WindSettings& settings, float seconds);

/** Wind velocity in m/s, world (x, z), at world position (x, z) metres: the same operations as wind.glsl. */
glm::vec2 windVelocity(const gpu::WindUniforms& wind, glm::vec2 position);

/**
 * windVelocity() at many points, each at its own time: out[i] = windVelocity(wind with flow.w +
 * timeOffsets[i], positions[i]), bit for bit the same values (the same float operations, eight points at a
 * time in vector registers; AVX2 where the CPU has it). `timeOffsets` empty: no offsets. Throws sylva::Error
 * when the sizes differ. Thread-safe.
 */
void windVelocities(const gpu::WindUniforms& wind, std::span<const glm::vec2> positions,
                    std::span<const float> timeOffsets, std::span<glm::vec2> out);

/** The mean-flow-plus-gust part alone (no turbulence), m/s along the mean direction; ≥ the mean speed. */
float gustSpeed(const gpu::WindUniforms& wind, glm::vec2 position);

/** 3D value noise in [−1, 1] on an integer lattice with smoothstep blending (shared with wind.glsl). */
float valueNoise(glm::vec3 p, std::uint32_t seed);

/** JSON object of the settings (scene files); fromJson validates with errors naming `where`. */
nlohmann::json toJson(const WindSettings& settings);
/** The settings of a scene file's wind object; errors name `where` and the field. */
WindSettings windSettingsFromJson(const nlohmann::json& json, const std::string& where);

} // namespace sylva::wind
