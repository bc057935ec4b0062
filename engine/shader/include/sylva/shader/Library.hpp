#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sylva::shader {

/**
 * The set of shader sources, keyed by path relative to the `shaders/` directory (e.g. "demo/scene.vert",
 * "common/noise.glsl", "shared/Frame.h"). By default reads the copies embedded in the binary at build time,
 * so `sylva` runs from any directory; with a disk directory set, reads that directory instead (the viewer's
 * "reload shaders" for development). Not thread-safe for concurrent setDirectory().
 */
class Library {
public:
  /** The embedded library. */
  Library() = default;
  /** A library reading from `directory` on disk. */
  explicit Library(std::filesystem::path directory) : mDirectory(std::move(directory)) {}

  /** The source of `path`, or nullopt if it does not exist. */
  std::optional<std::string> read(const std::string& path) const;
  /** All file paths, sorted. */
  std::vector<std::string> list() const;
  /** Switches to reading from `directory` (empty path = embedded copies). */
  void setDirectory(std::filesystem::path directory) { mDirectory = std::move(directory); }
  /** The disk directory read from; empty for the embedded copies. */
  const std::filesystem::path& directory() const { return mDirectory; }
  /** True when reading the copies embedded at build time. */
  bool embedded() const { return mDirectory.empty(); }

  /** The source tree's shaders/ directory recorded at build time (may not exist on an installed machine). */
  static std::filesystem::path sourceDirectory();

private:
  std::filesystem::path mDirectory;
};

} // namespace sylva::shader
