#include <sylva/core/Files.hpp>
#include <sylva/core/JsonNode.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace sylva {

namespace {

/**
 * Temporaries of writes in progress, readable from a signal handler: fixed slots, each a path and a state
 * (0 free, 1 being filled in, 2 valid). No allocation, no locks.
 */
struct TempSlot {
  std::atomic<int> state{0};
  char path[4096] = {};
};
std::array<TempSlot, 32> gTempSlots;

int registerTemporary(const std::filesystem::path& tmp) {
  const std::string text = tmp.string();
  if (text.size() >= sizeof(TempSlot::path)) {
    return -1;
  }
  for (std::size_t i = 0; i < gTempSlots.size(); ++i) {
    int expected = 0;
    if (gTempSlots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(gTempSlots[i].path, text.c_str(), text.size() + 1);
      gTempSlots[i].state.store(2);
      return static_cast<int>(i);
    }
  }
  return -1; // more than 32 concurrent writes: that one is simply not cleaned up on a signal
}

void unregisterTemporary(int slot) {
  if (slot >= 0) {
    gTempSlots[static_cast<std::size_t>(slot)].state.store(0);
  }
}

/** `.<name>.tmp.` for `path` (built by appending: GCC 12 misreports `"." + string` under -Wrestrict). */
std::string temporaryPrefix(const std::filesystem::path& path) {
  std::string prefix(1, '.');
  prefix.append(path.filename().string()).append(".tmp.");
  return prefix;
}

/** Removes `.<name>.tmp.<pid>` files next to `path` whose writing process no longer exists. */
void removeStaleTemporaries(const std::filesystem::path& path) {
  const std::string prefix = temporaryPrefix(path);
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.starts_with(prefix)) {
      continue;
    }
    const std::string pidText = name.substr(prefix.size());
    if (pidText.empty() || pidText.size() > 9 ||
        !std::all_of(pidText.begin(), pidText.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      continue;
    }
    const auto pid = static_cast<pid_t>(std::stol(pidText));
    if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

} // namespace

namespace {
std::atomic<bool> gOutputsComplete{false};
static_assert(std::atomic<bool>::is_always_lock_free, "read from a signal handler");
} // namespace

void markOutputsComplete() noexcept {
  gOutputsComplete.store(true);
}

bool outputsComplete() noexcept {
  return gOutputsComplete.load();
}

void removeTemporaryFilesForSignal() noexcept {
  for (TempSlot& slot : gTempSlots) {
    if (slot.state.load() == 2) {
      ::unlink(slot.path);
    }
  }
}

std::filesystem::path dataDirectory() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("SYLVA_DATA_DIR"); env != nullptr && *env != '\0') {
    return fs::absolute(env).lexically_normal();
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = (exe.parent_path() / ".." / "share" / "sylva" / "data").lexically_normal();
    if (fs::is_directory(installed, ec)) {
      return installed;
    }
  }
  // A program built in the source tree uses the tree's data (so an installed copy never shadows what is being
  // worked on); a program linking the installed libraries finds the prefix's.
  const fs::path source = fs::path(SYLVA_SOURCE_DATA_DIR).lexically_normal();
  const fs::path prefix = fs::path(SYLVA_INSTALL_DATA_DIR).lexically_normal();
  if (!fs::is_directory(source, ec) && fs::is_directory(prefix, ec)) {
    return prefix;
  }
  return source;
}

std::filesystem::path dataPath(const std::filesystem::path& relative) {
  return dataDirectory() / relative;
}

void checkOutputFile(const std::filesystem::path& path, std::string_view option, std::string_view example) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    fail("{} {}: is a directory; give a file name (e.g. {})", option, path.string(),
         (path / example).string());
  }
  for (std::filesystem::path dir = path.parent_path(); !dir.empty() && dir != dir.root_path();
       dir = dir.parent_path()) {
    if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
      fail("{} {}: {} is a file, not a directory", option, path.string(), dir.string());
    }
  }
}

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& writer) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    fail("{}: cannot write: it is a directory", path.string());
  }
  if (path.has_parent_path()) {
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) {
      fail("{}: cannot create directory: {}", path.parent_path().string(), ec.message());
    }
  }
  // Writing into one of this process's own temporaries (a writer that itself calls an atomic save, as the
  // image + sidecar pair does): the outer rename already makes the result atomic, and a second temporary
  // would be one that stale-temporary cleanup cannot recognise.
  const std::string name = path.filename().string();
  const std::string ownSuffix = ".tmp." + std::to_string(::getpid());
  if (name.starts_with(".") && name.ends_with(ownSuffix)) {
    writer(path);
    return;
  }
  removeStaleTemporaries(path);
  // The temporary lives in the same directory so the rename is atomic on one filesystem.
  const std::filesystem::path tmp = path.parent_path() / (temporaryPrefix(path) + std::to_string(::getpid()));
  const int slot = registerTemporary(tmp);
  try {
    writer(tmp);
  } catch (...) {
    std::filesystem::remove(tmp, ec);
    unregisterTemporary(slot);
    throw;
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    unregisterTemporary(slot);
    fail("{}: cannot write: {}", path.string(), ec.message());
  }
  unregisterTemporary(slot);
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

void requireExtension(std::string_view option, const std::filesystem::path& path,
                      std::string_view extension) {
  if (!path.empty() && lowerExtension(path) != extension) {
    fail("{} {}: expected a {} file", option, path.string(), extension);
  }
}

std::filesystem::path findOnPath(const std::string& name) {
  const char* env = std::getenv("PATH");
  const std::string path = env != nullptr ? env : "";
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find(':', start), path.size());
    const std::string dir = path.substr(start, end - start);
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
    start = end + 1;
  }
  return {};
}

std::string readTextFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    fail("{}: is a directory, not a file", path.string());
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("{}: cannot open file (missing or unreadable)", path.string());
  }
  try {
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  } catch (const std::exception& e) {
    fail("{}: cannot read the file: {}", path.string(), e.what());
  }
}

nlohmann::json loadJsonFile(const std::filesystem::path& path) {
  return parseJsonStrict(readTextFile(path), path.string());
}

void requireJsonVersion(const nlohmann::json& json, int expected, const std::string& where) {
  const JsonNode root(json, where);
  if (!json.is_object()) {
    root.error(fmt::format("expected an object, got {}", json.type_name()));
  }
  const JsonNode version = root["version"];
  if (!json["version"].is_number_integer() || json["version"].get<long long>() != expected) {
    version.error(fmt::format("must be {}", expected));
  }
}

void saveJsonFile(const std::filesystem::path& path, const nlohmann::json& json) {
  writeTextFile(path, json.dump(2) + "\n");
}

} // namespace sylva
