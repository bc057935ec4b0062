#pragma once

#include <filesystem>
#include <string>

namespace sylva::test {

/** A fresh directory under the build tree, removed on destruction; unique per test case. */
class TempDir {
public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return mPath; }
  std::filesystem::path operator/(const std::string& name) const { return mPath / name; }

private:
  std::filesystem::path mPath;
};

/**
 * True when SYLVA_FULL=1: heavy property tests (crack proofs, kill tests, soak) then run their full case
 * counts instead of the CI-sized ones (docs/testing.md).
 */
bool fullMode();

/** Path of a file in the source tree, e.g. sourcePath("data/x.png"). */
std::filesystem::path sourcePath(const std::string& relative);

} // namespace sylva::test
