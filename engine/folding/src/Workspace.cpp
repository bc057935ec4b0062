// The editor's workspace: file watching by polling, the recent-files list, and starting an external image
// editor (posix_spawnp, detached, reaped without blocking).
#include <sylva/folding/Workspace.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <mutex>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace sylva::folding {

namespace {

constexpr const char* kRecentFormat = "sylva-recent-files";
constexpr int kRecentVersion = 1;

std::int64_t nanoseconds(const timespec& t) {
  return static_cast<std::int64_t>(t.tv_sec) * 1000000000 + static_cast<std::int64_t>(t.tv_nsec);
}

/** `path` made absolute and canonical as far as the file system allows (missing parts stay lexical). */
std::filesystem::path canonicalPath(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  if (ec) {
    absolute = path;
  }
  std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

/** Pids started by launchDetached() and not reaped yet. */
struct Children {
  std::mutex mutex;
  std::vector<pid_t> pids;
};
Children& children() {
  static Children instance;
  return instance;
}

} // namespace

// ---------------------------------------------------------------------------------------------------------
// FileWatcher

FileWatcher::Signature FileWatcher::signature(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    return {};
  }
  Signature s;
  s.exists = true;
  s.device = static_cast<std::uint64_t>(st.st_dev);
  s.inode = static_cast<std::uint64_t>(st.st_ino);
  s.size = static_cast<std::int64_t>(st.st_size);
  s.mtimeNs = nanoseconds(st.st_mtim);
  s.ctimeNs = nanoseconds(st.st_ctim);
  return s;
}

void FileWatcher::watch(const std::filesystem::path& path) {
  if (mFiles.contains(path)) {
    return;
  }
  const Signature now = signature(path);
  mFiles.emplace(path, State{now, now});
}

void FileWatcher::unwatch(const std::filesystem::path& path) {
  mFiles.erase(path);
}

void FileWatcher::clear() {
  mFiles.clear();
}

std::vector<std::filesystem::path> FileWatcher::paths() const {
  std::vector<std::filesystem::path> out;
  out.reserve(mFiles.size());
  for (const auto& [path, state] : mFiles) {
    out.push_back(path);
  }
  return out;
}

std::vector<std::filesystem::path> FileWatcher::poll() {
  std::vector<std::filesystem::path> changed;
  for (auto& [path, state] : mFiles) {
    const Signature now = signature(path);
    if (!now.exists || now != state.last) {
      // Missing, or still changing since the previous poll: wait until it is there and stable.
      state.last = now;
      continue;
    }
    if (now != state.reported) {
      state.reported = now;
      changed.push_back(path);
    }
  }
  return changed;
}

// ---------------------------------------------------------------------------------------------------------
// RecentFiles

std::filesystem::path RecentFiles::defaultPath() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg != nullptr && xdg[0] == '/') {
    return std::filesystem::path(xdg) / "sylva" / "recent-folding.json";
  }
  const char* home = std::getenv("HOME");
  if (home != nullptr && home[0] == '/') {
    return std::filesystem::path(home) / ".config" / "sylva" / "recent-folding.json";
  }
  return {};
}

RecentFiles::RecentFiles(std::filesystem::path file) : mFile(std::move(file)) {}

void RecentFiles::add(const std::filesystem::path& path) {
  const std::filesystem::path p = canonicalPath(path);
  std::erase(mEntries, p);
  mEntries.insert(mEntries.begin(), p);
  if (mEntries.size() > kMax) {
    mEntries.resize(kMax);
  }
}

void RecentFiles::remove(const std::filesystem::path& path) {
  std::erase(mEntries, canonicalPath(path));
}

void RecentFiles::load(std::string* warning) {
  mEntries.clear();
  if (warning) {
    warning->clear();
  }
  std::error_code ec;
  if (mFile.empty() || !std::filesystem::exists(mFile, ec)) {
    return;
  }
  std::vector<std::filesystem::path> loaded;
  try {
    const nlohmann::json json = loadJsonFile(mFile);
    if (!json.is_object() || json.value("format", nlohmann::json()) != kRecentFormat ||
        json.value("version", nlohmann::json()) != kRecentVersion || !json.contains("files") ||
        !json["files"].is_array()) {
      fail("{}: not a recent-files list (expected format '{}', version {}, files [...]); ignored",
           mFile.string(), kRecentFormat, kRecentVersion);
    }
    for (const nlohmann::json& entry : json["files"]) {
      if (!entry.is_string()) {
        fail("{}: files: expected strings; ignored", mFile.string());
      }
      const std::filesystem::path p(entry.get<std::string>());
      if (!p.is_absolute() || !std::filesystem::is_regular_file(p, ec)) {
        continue; // gone since (or never a valid entry): dropped
      }
      const std::filesystem::path c = canonicalPath(p);
      if (std::find(loaded.begin(), loaded.end(), c) == loaded.end() && loaded.size() < kMax) {
        loaded.push_back(c);
      }
    }
  } catch (const std::exception& e) {
    if (warning) {
      *warning = e.what();
      if (warning->find(mFile.string()) == std::string::npos) {
        *warning = mFile.string() + ": " + *warning;
      }
    }
    return;
  }
  mEntries = std::move(loaded);
}

bool RecentFiles::save(std::string* warning) const {
  if (mFile.empty()) {
    if (warning) {
      *warning = "recent files: no location (neither XDG_CONFIG_HOME nor HOME is set); not saved";
    }
    return false;
  }
  nlohmann::json files = nlohmann::json::array();
  for (const std::filesystem::path& p : mEntries) {
    files.push_back(p.string());
  }
  try {
    saveJsonFile(mFile, {{"format", kRecentFormat}, {"version", kRecentVersion}, {"files", files}});
  } catch (const std::exception& e) {
    if (warning) {
      *warning = e.what();
      if (warning->find(mFile.string()) == std::string::npos) {
        *warning = mFile.string() + ": " + *warning;
      }
    }
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------------------
// External image editor

std::optional<std::vector<std::string>> splitCommandLine(const std::string& line, std::string* why) {
  std::vector<std::string> words;
  std::string word;
  bool inWord = false;
  const auto error = [&](const char* reason) -> std::optional<std::vector<std::string>> {
    if (why) {
      *why = std::string(reason) + " in command line: " + line;
    }
    return std::nullopt;
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ' ' || c == '\t' || c == '\n') {
      if (inWord) {
        words.push_back(std::move(word));
        word.clear();
        inWord = false;
      }
      continue;
    }
    inWord = true;
    if (c == '\'') {
      const std::size_t close = line.find('\'', i + 1);
      if (close == std::string::npos) {
        return error("unterminated single quote");
      }
      word += line.substr(i + 1, close - i - 1);
      i = close;
    } else if (c == '"') {
      std::size_t j = i + 1;
      for (; j < line.size() && line[j] != '"'; ++j) {
        if (line[j] == '\\' && j + 1 < line.size() && (line[j + 1] == '"' || line[j + 1] == '\\')) {
          ++j;
        }
        word += line[j];
      }
      if (j >= line.size()) {
        return error("unterminated double quote");
      }
      i = j;
    } else if (c == '\\') {
      if (i + 1 >= line.size()) {
        return error("trailing backslash");
      }
      word += line[++i];
    } else {
      word += c;
    }
  }
  if (inWord) {
    words.push_back(std::move(word));
  }
  return words;
}

std::optional<std::vector<std::string>> imageEditorCommand(const std::filesystem::path& image,
                                                           std::string* why) {
  std::error_code ec;
  std::filesystem::path absolute = std::filesystem::absolute(image, ec);
  const std::string file = (ec ? image : absolute).string();
  const char* configured = std::getenv("SYLVA_IMAGE_EDITOR");
  const std::string line = configured != nullptr ? configured : "";
  if (line.find_first_not_of(" \t\n") != std::string::npos) {
    std::string reason;
    std::optional<std::vector<std::string>> words = splitCommandLine(line, &reason);
    if (!words) {
      if (why) {
        *why = "SYLVA_IMAGE_EDITOR: " + reason;
      }
      return std::nullopt;
    }
    bool placed = false;
    for (std::string& w : *words) {
      for (std::size_t at = w.find("{}"); at != std::string::npos; at = w.find("{}", at + file.size())) {
        w.replace(at, 2, file);
        placed = true;
      }
    }
    if (!placed) {
      words->push_back(file);
    }
    return words;
  }
  const std::filesystem::path gimp = findOnPath("gimp");
  if (!gimp.empty()) {
    return std::vector<std::string>{gimp.string(), file};
  }
  if (why) {
    *why = "no image editor: install GIMP (apt install gimp) or set SYLVA_IMAGE_EDITOR to a command, e.g. "
           "SYLVA_IMAGE_EDITOR='krita {}' ({} is replaced by the image file)";
  }
  return std::nullopt;
}

int launchDetached(const std::vector<std::string>& argv, std::string* error) {
  if (argv.empty() || argv[0].empty()) {
    if (error) {
      *error = "cannot start a program: empty command";
    }
    return -1;
  }
  posix_spawnattr_t attr;
  posix_spawn_file_actions_t actions;
  if (int rc = posix_spawnattr_init(&attr); rc != 0) {
    if (error) {
      *error = "cannot start '" + argv[0] + "': " + std::strerror(rc);
    }
    return -1;
  }
  if (int rc = posix_spawn_file_actions_init(&actions); rc != 0) {
    posix_spawnattr_destroy(&attr);
    if (error) {
      *error = "cannot start '" + argv[0] + "': " + std::strerror(rc);
    }
    return -1;
  }
  sigset_t mask;
  sigemptyset(&mask);
  sigset_t defaults;
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGCHLD}) {
    sigaddset(&defaults, s);
  }
  int rc =
      posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  if (rc == 0) {
    rc = posix_spawnattr_setpgroup(&attr, 0); // a new group led by the child
  }
  if (rc == 0) {
    rc = posix_spawnattr_setsigmask(&attr, &mask);
  }
  if (rc == 0) {
    rc = posix_spawnattr_setsigdefault(&attr, &defaults);
  }
  if (rc == 0) {
    rc = posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  }
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const std::string& a : argv) {
    args.push_back(const_cast<char*>(a.c_str()));
  }
  args.push_back(nullptr);
  pid_t pid = -1;
  // Hold the lock across the spawn, so a concurrent reapChildren() never sees the pid unregistered.
  std::lock_guard lock(children().mutex);
  if (rc == 0) {
    rc = posix_spawnp(&pid, argv[0].c_str(), &actions, &attr, args.data(), environ);
  }
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    if (error) {
      *error = "cannot start '" + argv[0] + "': " + std::strerror(rc);
    }
    return -1;
  }
  children().pids.push_back(pid);
  return static_cast<int>(pid);
}

std::vector<ChildExit> reapChildren() {
  std::vector<ChildExit> done;
  std::lock_guard lock(children().mutex);
  std::vector<pid_t>& pids = children().pids;
  for (auto it = pids.begin(); it != pids.end();) {
    int status = 0;
    pid_t r = -1;
    do {
      r = ::waitpid(*it, &status, WNOHANG);
    } while (r == -1 && errno == EINTR);
    if (r == 0) {
      ++it; // still running
      continue;
    }
    ChildExit exit;
    exit.pid = static_cast<int>(*it);
    if (r == *it) {
      if (WIFEXITED(status)) {
        exit.exitCode = WEXITSTATUS(status);
      } else if (WIFSIGNALED(status)) {
        exit.signal = WTERMSIG(status);
      } else {
        ++it; // stopped or continued: not finished
        continue;
      }
    }
    done.push_back(exit); // r == −1 (ECHILD): reaped elsewhere, forgotten
    it = pids.erase(it);
  }
  return done;
}

std::vector<int> runningChildren() {
  std::lock_guard lock(children().mutex);
  return {children().pids.begin(), children().pids.end()};
}

} // namespace sylva::folding
