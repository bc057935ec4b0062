#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include <unistd.h>

namespace sylva::test {

TempDir::TempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info != nullptr ? std::string(info->test_suite_name()) + "." + info->name() : "tmp";
  for (char& c : name) {
    if (c == '/') {
      c = '_';
    }
  }
  mPath = std::filesystem::path(SYLVA_BINARY_DIR) / "test-tmp" / (name + "." + std::to_string(::getpid()));
  std::filesystem::remove_all(mPath);
  std::filesystem::create_directories(mPath);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(mPath, ec);
}

std::filesystem::path sourcePath(const std::string& relative) {
  return std::filesystem::path(SYLVA_SOURCE_DIR) / relative;
}

bool fullMode() {
  const char* value = std::getenv("SYLVA_FULL");
  return value != nullptr && std::string(value) == "1";
}

} // namespace sylva::test
