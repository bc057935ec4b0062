#pragma once

#include <cstdint>

namespace sylva {

/**
 * Small, fast, seedable generator (PCG32, O'Neill 2014). Same seed and stream give the same sequence on every
 * platform, so procedural content and tests are reproducible. Not thread-safe; use one per thread.
 */
class Rng {
public:
  /** The sequence of `seed` on `stream` (PCG32's defaults when omitted). */
  explicit Rng(std::uint64_t seed = 0x853c49e6748fea9bULL, std::uint64_t stream = 0xda3e39cb94b95bdbULL);

  /** Uniform 32-bit value. */
  std::uint32_t nextU32();
  /** Uniform float in [0, 1). */
  float uniform();
  /** Uniform float in [lo, hi). */
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  /** Uniform integer in [0, bound) without modulo bias; bound > 0. */
  std::uint32_t below(std::uint32_t bound);

private:
  std::uint64_t mState = 0;
  std::uint64_t mInc = 0;
};

/** Stateless 64-bit mix (SplitMix64 finaliser); use to derive per-item seeds from (seed, index). */
std::uint64_t hash64(std::uint64_t x);

/**
 * Stateless 32-bit integer hash (Chris Wellons' lowbias32). Wrapping uint arithmetic is the same in C++ and
 * GLSL: lowbias32() in shaders/common/hash.glsl is its twin, for CPU references of shaders.
 */
constexpr std::uint32_t lowbias32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

} // namespace sylva
