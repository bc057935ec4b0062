#pragma once

// Helpers shared by the capture module's tests.

#include <sylva/core/Error.hpp>

#include <gtest/gtest.h>

#include <string>

namespace sylva::capture::testutil {

/** The message of the sylva::Error `body` throws ("" when it does not throw). */
template <typename F> std::string errorOf(F&& body) {
  try {
    body();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

} // namespace sylva::capture::testutil
