#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace sylva {

/**
 * Writes a file atomically: `writer` fills a temporary file next to `path` (named .NAME.tmp.PID), which
 * is then renamed over `path`. So `path` is either absent, its old content, or the complete new content, even
 * if the process is killed. If `writer` throws, the temporary is removed and the exception propagates.
 * Temporaries left by killed processes (SIGKILL, power loss) for the same `path` are removed on the next
 * write. Parent directories are created.
 */
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& writer);

/**
 * Removes the temporary files of writes in progress; async-signal-safe (only unlink(2)), for SIGINT/SIGTERM
 * handlers that then end the process.
 */
void removeTemporaryFilesForSignal() noexcept;

/**
 * Marks the command's outputs as all written: from here on the `sylva` program ignores SIGINT (the work is
 * done), so an interrupted command leaves either no output or every output, never finished files with a
 * failed exit. Call it last, while the final step's Progress is still active.
 */
void markOutputsComplete() noexcept;
/** Whether markOutputsComplete() was called; async-signal-safe. */
bool outputsComplete() noexcept;

/**
 * Sylva's data folder (scenes, blade models, folding projects, fetched sample data), whatever the working
 * directory: $SYLVA_DATA_DIR when set, else `share/sylva/data` beside the running program's directory (an
 * installed layout: PREFIX/bin/sylva, PREFIX/share/sylva/data), else the source tree's data/ the libraries
 * were built from when it exists, else the data folder of the prefix they were built to be installed in
 * (CMAKE_INSTALL_PREFIX: /usr for the Debian packages), which is how a program linking the installed
 * libraries finds it. Absolute.
 */
std::filesystem::path dataDirectory();
/** `relative` (e.g. "external/ez-tree/bark") inside dataDirectory(). */
std::filesystem::path dataPath(const std::filesystem::path& relative);

/**
 * Checks, before any expensive work, that a file can be written at `path` later: throws sylva::Error
 * "`option` PATH: ..." when it is a directory (suggesting PATH/`example`) or when a part of its parent path
 * is an existing file.
 */
void checkOutputFile(const std::filesystem::path& path, std::string_view option,
                     std::string_view example = "image.png");

/** Writes `text` to `path` atomically; throws sylva::Error naming the file. */
void writeTextFile(const std::filesystem::path& path, std::string_view text);

/** The extension of `path` in lower case, with its dot (".png"), or "" when there is none. */
std::string lowerExtension(const std::filesystem::path& path);

/**
 * Throws sylva::Error "`option` PATH: expected a `extension` file" when `path` is given (not empty) and does
 * not end in `extension` (lower case, with its dot: ".gif"; compared case-insensitively).
 */
void requireExtension(std::string_view option, const std::filesystem::path& path, std::string_view extension);

/** The executable `name` in a directory of $PATH (an empty entry is "."), or an empty path when none holds
 * it. */
std::filesystem::path findOnPath(const std::string& name);

/** Reads a whole file; throws sylva::Error naming the file if it is missing or unreadable. */
std::string readTextFile(const std::filesystem::path& path);

/**
 * Parses a JSON file with parseJsonStrict (JsonNode.hpp): throws sylva::Error naming the file, line and
 * column on syntax errors, and the JSON Pointer of a duplicate key.
 */
nlohmann::json loadJsonFile(const std::filesystem::path& path);

/**
 * Checks the envelope of a versioned Sylva JSON document: an object whose integer field `version` equals
 * `expected`. Throws sylva::Error `WHERE: expected a JSON object`, `WHERE: missing field 'version'` or
 * `WHERE: field 'version' must be EXPECTED`.
 */
void requireJsonVersion(const nlohmann::json& json, int expected, const std::string& where);

/** Writes JSON (2-space indent, trailing newline) atomically. */
void saveJsonFile(const std::filesystem::path& path, const nlohmann::json& json);

} // namespace sylva
