#pragma once

#include <sylva/terrain/HeightField.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace sylva::terrain {

/**
 * Parameters of a procedural height function h(x, z) in world metres (the paper's Perlin-noise terrain).
 * Heights lie in [0, heightScale] metres: the noise value in [0, 1] (clamped) times heightScale, like the
 * paper's h·N with h ∈ [0, 1].
 */
struct ProceduralSpec {
  /** Noise flavour. */
  enum class Type {
    /** Fractional Brownian motion: Σ gainᵒ · perlin(p · frequency · lacunarityᵒ), mapped to [0, 1]. */
    Fbm,
    /** Ridged multifractal (Musgrave): sharp crests from (1 − |perlin|)², octaves weighted by the last. */
    Ridged,
    /** fBm sampled at p + warpStrength · (fBm₁(p), fBm₂(p)): domain warping, folded valleys. */
    Warped,
  };

  /** Seed of all permutation tables and octave offsets; the same seed gives the same heights everywhere. */
  std::uint64_t seed = 1;
  /** Which noise: plain fBm, ridged multifractal or domain-warped fBm. */
  Type type = Type::Fbm;
  /** Number of octaves, 1..16. */
  int octaves = 6;
  /** Base frequency, cycles per metre (> 0); 1/256 gives hills about 256 m apart. */
  float frequency = 1.0f / 256.0f;
  /** Frequency multiplier between octaves (≥ 1). */
  float lacunarity = 2.0f;
  /** Amplitude multiplier between octaves (0 < gain ≤ 1). */
  float gain = 0.5f;
  /** Domain-warp displacement, metres (≥ 0); used by Type::Warped only. */
  float warpStrength = 80.0f;
  /** Height of noise value 1, metres (> 0): heights lie in [0, heightScale]. */
  float heightScale = 200.0f;

  /** Every field equal. */
  bool operator==(const ProceduralSpec&) const = default;
};

/**
 * The default landscape of every command (`sylva terrain ...`, render, view, bench) when only a seed is
 * given: warped fBm, 8 octaves, features ~700 m apart, 150 m warp, 400 m relief; on a
 * kDefaultProceduralSize² grid at kDefaultProceduralSpacing metres.
 */
ProceduralSpec defaultLandscapeSpec(std::uint64_t seed = 7);
/** Samples per side of the default procedural field. */
inline constexpr int kDefaultProceduralSize = 1025;
/** Metres between samples of the default procedural field. */
inline constexpr float kDefaultProceduralSpacing = 2.0f;

/** "fbm", "ridged" or "warped". */
const char* procedureTypeName(ProceduralSpec::Type type);

/** Throws sylva::Error `WHERE: field 'NAME' ...` if a parameter is out of range. */
void validate(const ProceduralSpec& spec, const std::string& where = "procedural spec");

/**
 * A ProceduralSpec with its permutation tables built once (from the seed with sylva::Rng, so identical on
 * every platform and standard library). Immutable after construction: sample() may be called from many
 * threads.
 */
class ProceduralNoise {
public:
  /** Validates `spec` (throws sylva::Error naming the field) and builds the tables. */
  explicit ProceduralNoise(const ProceduralSpec& spec);

  /** The spec the noise was made from. */
  const ProceduralSpec& spec() const { return mSpec; }

  /**
   * Height in metres at world position (x, z) metres, in [0, heightScale]. A pure function of (spec, x, z):
   * computed in double precision from the world position alone, so any tiling gives bit-identical results.
   */
  float sample(double x, double z) const;

  /** Gradient (improved Perlin) noise of table `table` (0..2) at (x, z) in lattice units; about [-1, 1]. */
  double perlin(int table, double x, double z) const;

private:
  double fbm(int table, double x, double z) const;
  double ridged(double x, double z) const;

  ProceduralSpec mSpec;
  /** Three independent doubled permutation tables: height, warp x, warp z. */
  std::array<std::array<std::uint8_t, 512>, 3> mPerm{};
  /** Per-octave lattice offsets (lattice units), so octaves do not all vanish at the world origin. */
  std::array<std::array<double, 2>, 16> mOffsets{};
};

/** ProceduralNoise(spec).sample(x, z): builds the tables on every call; use ProceduralNoise in loops. */
float sample(const ProceduralSpec& spec, double x, double z);

/**
 * A width×height field of heights with `spacing` metres between samples. Sample (i, j) sits at world position
 * x = (k₀ + i)·spacing, z = (l₀ + j)·spacing where k₀ = originX / spacing, l₀ = originZ / spacing when those
 * are whole numbers (the tiling case: tiles whose origins lie on the same sample lattice agree bit for bit
 * with one big field), and x = originX + i·spacing (likewise z) otherwise. Runs on parallelFor;
 * deterministic. Throws sylva::Error for an invalid spec, size < 1 or > kMaxHeightFieldSide, or spacing not
 * finite and > 0.
 */
HeightField generate(const ProceduralSpec& spec, double originX, double originZ, int width, int height,
                     float spacing);

/**
 * JSON object {"version": 1, "seed", "type": "fbm"|"ridged"|"warped", "octaves", "frequency",
 * "lacunarity", "gain", "warpStrength", "heightScale"}.
 */
nlohmann::json toJson(const ProceduralSpec& spec);

/**
 * Parses a spec from JSON. `version` (1) is required; other fields default to ProceduralSpec's values;
 * unknown fields are errors (typos). Throws sylva::Error `WHERE: field 'NAME': REASON`.
 */
ProceduralSpec proceduralSpecFromJson(const nlohmann::json& json, const std::string& where);

/** Loads a spec file; errors name the file and the field. */
ProceduralSpec loadProceduralSpec(const std::filesystem::path& path);

/** Saves a spec file atomically. */
void saveProceduralSpec(const std::filesystem::path& path, const ProceduralSpec& spec);

} // namespace sylva::terrain
