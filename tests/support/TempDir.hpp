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

/** Path of a file in the source tree, e.g. sourcePath("data/x.png"). */
std::filesystem::path sourcePath(const std::string& relative);

} // namespace sylva::test
