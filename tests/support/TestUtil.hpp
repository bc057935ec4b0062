#pragma once
// Small helpers shared by test files (one definition each, so test executables can be compiled as unity
// batches).

#include <sylva/core/Error.hpp>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace sylva::test {

/** A quiet NaN, for nodata samples and invalid inputs. */
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/** Whether two floats have the same bits (NaN equals the same NaN, 0 differs from -0). */
inline bool sameBits(float a, float b) {
  std::uint32_t x = 0;
  std::uint32_t y = 0;
  std::memcpy(&x, &a, 4);
  std::memcpy(&y, &b, 4);
  return x == y;
}

/** The message of the sylva::Error that `call()` throws, or "(no error)". */
template <class Call> std::string errorOf(const Call& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

} // namespace sylva::test
