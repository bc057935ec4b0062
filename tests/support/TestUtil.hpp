#pragma once
// Small helpers shared by test files (one definition each, so test executables can be compiled as unity
// batches).

#include <sylva/core/Error.hpp>

#include <limits>
#include <string>

namespace sylva::test {

/** A quiet NaN, for nodata samples and invalid inputs. */
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

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
