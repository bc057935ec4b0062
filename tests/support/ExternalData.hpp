#pragma once

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace sylva::test {

/** True when SYLVA_ALLOW_MISSING_DATA=1: missing third-party data then skips instead of failing. */
inline bool allowMissingData() {
  const char* env = std::getenv("SYLVA_ALLOW_MISSING_DATA");
  return env != nullptr && std::string(env) == "1";
}

/** Path of a file fetched by scripts/fetch-sample-data.sh (under data/external/). */
inline std::filesystem::path externalData(const std::string& name) {
  return sourcePath("data/external/" + name);
}

} // namespace sylva::test

/** Real third-party data: CI must have it (fail); SYLVA_ALLOW_MISSING_DATA=1 turns a missing file into a
 * skip. */
#define SYLVA_REQUIRE_EXTERNAL_DATA(path)                                                                    \
  do {                                                                                                       \
    if (!std::filesystem::exists(path)) {                                                                    \
      if (::sylva::test::allowMissingData()) {                                                               \
        GTEST_SKIP() << (path).string() << " is missing (SYLVA_ALLOW_MISSING_DATA=1)";                       \
      }                                                                                                      \
      FAIL() << (path).string() << " is missing: run scripts/fetch-sample-data.sh";                          \
    }                                                                                                        \
  } while (false)
