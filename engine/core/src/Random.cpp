#include <sylva/core/Random.hpp>

namespace sylva {

Rng::Rng(std::uint64_t seed, std::uint64_t stream) : mInc((stream << 1u) | 1u) {
  nextU32();
  mState += seed;
  nextU32();
}

std::uint32_t Rng::nextU32() {
  const std::uint64_t old = mState;
  mState = old * 6364136223846793005ULL + mInc;
  const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
  const auto rot = static_cast<std::uint32_t>(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

float Rng::uniform() {
  // 24 random bits map exactly onto floats in [0, 1).
  return static_cast<float>(nextU32() >> 8) * (1.0f / 16777216.0f);
}

std::uint32_t Rng::below(std::uint32_t bound) {
  const std::uint32_t threshold = (0u - bound) % bound;
  for (;;) {
    const std::uint32_t r = nextU32();
    if (r >= threshold) {
      return r % bound;
    }
  }
}

std::uint64_t hash64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

} // namespace sylva
