#include <sylva/shader/Library.hpp>

#include <sylva/core/Files.hpp>

#include <algorithm>
#include <map>
#include <string_view>

namespace sylva::shader {

namespace detail {
const std::map<std::string, std::string_view>& embeddedFiles();
} // namespace detail

std::optional<std::string> Library::read(const std::string& path) const {
  if (mDirectory.empty()) {
    const auto& files = detail::embeddedFiles();
    const auto it = files.find(path);
    if (it == files.end()) {
      return std::nullopt;
    }
    return std::string(it->second);
  }
  const std::filesystem::path file = mDirectory / path;
  // The error_code overload: a name the filesystem refuses (too long, bad characters) is simply not there,
  // rather than a filesystem_error escaping the preprocessor (found by fuzzing).
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    return std::nullopt;
  }
  return readTextFile(file);
}

std::vector<std::string> Library::list() const {
  std::vector<std::string> out;
  if (mDirectory.empty()) {
    for (const auto& [name, text] : detail::embeddedFiles()) {
      out.push_back(name);
    }
  } else if (std::filesystem::is_directory(mDirectory)) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(mDirectory)) {
      if (entry.is_regular_file()) {
        out.push_back(std::filesystem::relative(entry.path(), mDirectory).generic_string());
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::filesystem::path Library::sourceDirectory() {
  return SYLVA_SHADER_SOURCE_DIR;
}

} // namespace sylva::shader
