#pragma once

// The editor's workspace outside the project model: watching input images for changes made by other
// programs, the recent-files list, and opening an image in an external image editor. GL-free; POSIX.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sylva::folding {

/**
 * Watches files for content changes by polling (no inotify, so it works on every file system and sees files
 * replaced by rename). A file's signature is its inode and device, size, and modification and status-change
 * times with nanoseconds, read with stat(2) (symbolic links are followed). Polling is explicit: the editor
 * calls poll() every few hundred milliseconds from its main loop.
 *
 * Debounce: a change is reported by the first poll that sees the same signature as the poll just before it,
 * so a file still being written (its size or times differ between two consecutive polls) is reported once,
 * after it has stayed the same for one poll. A file that is missing (or not a regular file) is never
 * reported; it is reported once it reappears and is stable, when it differs from what was last reported (an
 * editor that writes a temporary file and renames it over the original is seen as one change). Not
 * thread-safe.
 */
class FileWatcher {
public:
  /**
   * Starts watching `path` (as given; relative paths resolve against the working directory at each poll).
   * Its current state is the reference: it is not reported until it changes. Watching a path that is already
   * watched keeps its state.
   */
  void watch(const std::filesystem::path& path);
  /** Stops watching `path` (no effect when it is not watched). */
  void unwatch(const std::filesystem::path& path);
  /** Stops watching everything. */
  void clear();
  /** The watched paths, sorted. */
  std::vector<std::filesystem::path> paths() const;

  /**
   * Reads every watched file's signature and returns the paths (as passed to watch(), sorted) whose content
   * changed and has been stable since the previous poll; each change is reported once.
   */
  std::vector<std::filesystem::path> poll();

  /** What poll() compares (exposed for tests and diagnostics). */
  struct Signature {
    bool exists = false; ///< a regular file could be stat'ed
    /** Device of the file (st_dev). */
    std::uint64_t device = 0;
    /** Inode of the file (st_ino). */
    std::uint64_t inode = 0;
    std::int64_t size = 0;    ///< bytes
    std::int64_t mtimeNs = 0; ///< modification time, nanoseconds since the epoch
    std::int64_t ctimeNs = 0; ///< status-change time, nanoseconds since the epoch
    /** Every field equal. */
    bool operator==(const Signature&) const = default;
  };
  /** The signature of `path` now (exists = false when it is missing or not a regular file). */
  static Signature signature(const std::filesystem::path& path);

private:
  struct State {
    Signature reported; ///< what the caller last knew (at watch() or at the last report)
    Signature last;     ///< what the previous poll saw
  };
  std::map<std::filesystem::path, State> mFiles;
};

/**
 * The editor's list of recently opened project files, most recent first, at most kMax entries, stored as
 * JSON {"format": "sylva-recent-files", "version": 1, "files": ["/abs/path.json", …]}. Paths are absolute
 * and canonical (symbolic links and ".." resolved as far as the file system allows). Loading and saving never
 * throw: problems come back as one-line warnings naming the file.
 */
class RecentFiles {
public:
  /** Most entries kept. */
  static constexpr std::size_t kMax = 10;

  /**
   * The default location: `$XDG_CONFIG_HOME/sylva/recent-folding.json` when XDG_CONFIG_HOME is set to an
   * absolute path, else `$HOME/.config/sylva/recent-folding.json`; empty when neither is usable.
   */
  static std::filesystem::path defaultPath();

  /** A list stored at `file` (empty: kept in memory only). Starts empty; call load(). */
  explicit RecentFiles(std::filesystem::path file = defaultPath());

  /** Where the list is stored (empty: memory only). */
  const std::filesystem::path& file() const { return mFile; }
  /** The entries, most recent first. */
  const std::vector<std::filesystem::path>& entries() const { return mEntries; }

  /** Puts `path` (made absolute and canonical) at the front, removing an older copy; keeps at most kMax. */
  void add(const std::filesystem::path& path);
  /** Removes `path` (compared after making it absolute and canonical). */
  void remove(const std::filesystem::path& path);
  /** Empties the list (save() to store that). */
  void clear() { mEntries.clear(); }

  /**
   * Replaces the entries with the file's, dropping entries whose files no longer exist and entries that are
   * not absolute paths (the first kMax are kept). A missing file gives an empty list without a warning; a
   * corrupt one (not JSON, wrong format or version, wrong types) gives an empty list and a one-line warning
   * in `warning` (when given). Never throws.
   */
  void load(std::string* warning = nullptr);
  /**
   * Writes the entries atomically (temporary file + rename; parent directories created). Returns false and
   * sets `warning` (when given) when it fails or there is no file. Never throws.
   */
  bool save(std::string* warning = nullptr) const;

private:
  std::filesystem::path mFile;
  std::vector<std::filesystem::path> mEntries;
};

/**
 * The command line that opens `image` in the user's image editor, as argv words:
 *  - `$SYLVA_IMAGE_EDITOR` when set and not blank: a command line split on spaces and tabs, with 'single'
 *    quotes (literal), "double" quotes (\" and \\ escaped) and backslash escapes outside quotes; every `{}`
 *    inside a word is replaced by the image's absolute path, and without any `{}` the path is appended as the
 *    last word. An unterminated quote or a trailing backslash gives nullopt with the reason in `why`.
 *  - else `gimp`, when an executable of that name is on PATH (its full path, then the image).
 *  - else nullopt, with `why` (when given) a one-line message saying to install GIMP or set
 *    SYLVA_IMAGE_EDITOR.
 */
std::optional<std::vector<std::string>> imageEditorCommand(const std::filesystem::path& image,
                                                           std::string* why = nullptr);

/** The argv words of a command line, split as imageEditorCommand splits SYLVA_IMAGE_EDITOR (no `{}`). */
std::optional<std::vector<std::string>> splitCommandLine(const std::string& line, std::string* why = nullptr);

/**
 * Starts `argv` (argv[0] looked up on PATH unless it contains a '/') with posix_spawnp and returns its pid
 * without waiting. The child gets its own process group (so Ctrl-C in the editor's terminal does not reach
 * it), standard input from /dev/null, the default action for SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE and
 * SIGCHLD and an empty signal mask; it inherits the environment, working directory and standard output and
 * error. The pid is remembered for reapChildren(). Returns −1 and sets `error` (when given) to one line
 * naming the program when it cannot be started (empty argv, not found, not executable).
 */
int launchDetached(const std::vector<std::string>& argv, std::string* error = nullptr);

/** A child started by launchDetached() that has finished. */
struct ChildExit {
  /** The child's process id. */
  int pid = 0;
  int exitCode = -1; ///< exit status when it exited normally, else −1
  int signal = 0;    ///< the signal that ended it, else 0
};
/**
 * Reaps the children started by launchDetached() that have finished, without blocking (waitpid with
 * WNOHANG for each remembered pid), and returns them. Children reaped elsewhere (SIGCHLD ignored, or another
 * waitpid) are forgotten and reported with exitCode −1 and signal 0. Thread-safe.
 */
std::vector<ChildExit> reapChildren();
/** The pids started by launchDetached() that have not been reaped yet. Thread-safe. */
std::vector<int> runningChildren();

} // namespace sylva::folding
