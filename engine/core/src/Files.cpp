#include <sylva/core/Files.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <unistd.h>

namespace sylva {

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& writer) {
  std::error_code ec;
  if (path.has_parent_path()) {
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) {
      fail("{}: cannot create directory: {}", path.parent_path().string(), ec.message());
    }
  }
  // The temporary lives in the same directory so the rename is atomic on one filesystem.
  std::filesystem::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid());
  try {
    writer(tmp);
  } catch (...) {
    std::filesystem::remove(tmp, ec);
    throw;
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    fail("{}: cannot write: {}", path.string(), ec.message());
  }
}

void writeTextFile(const std::filesystem::path& path, std::string_view text) {
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) {
      fail("{}: write failed", path.string());
    }
  });
}

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string readTextFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("{}: cannot open file (missing or unreadable)", path.string());
  }
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

nlohmann::json loadJsonFile(const std::filesystem::path& path) {
  const std::string text = readTextFile(path);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based; report line and column, which people can jump to.
    std::size_t line = 1;
    std::size_t column = 1;
    for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    fail("{}:{}:{}: invalid JSON", path.string(), line, column);
  }
}

void requireJsonVersion(const nlohmann::json& json, int expected, const std::string& where) {
  if (!json.is_object()) {
    fail("{}: expected a JSON object", where);
  }
  if (!json.contains("version")) {
    fail("{}: missing field 'version'", where);
  }
  if (!json["version"].is_number_integer() || json["version"].get<long long>() != expected) {
    fail("{}: field 'version' must be {}", where, expected);
  }
}

void saveJsonFile(const std::filesystem::path& path, const nlohmann::json& json) {
  writeTextFile(path, json.dump(2) + "\n");
}

} // namespace sylva
