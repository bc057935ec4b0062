// The editor's workspace: polling file watcher (with real files, explicit polls and explicit times), the
// recent-files list, the external image editor's command line and detached launches.
#include <sylva/core/Files.hpp>
#include <sylva/folding/Workspace.hpp>

#include "TempDir.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <thread>
#include <unistd.h>

namespace sylva::folding {
namespace {

namespace fs = std::filesystem;
using Paths = std::vector<fs::path>;

void write(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

void append(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::app);
  out << text;
}

/** Sets the modification time to `seconds` after a fixed reference, so changes never hide in one tick. */
void setTime(const fs::path& path, int seconds) {
  static const fs::file_time_type reference = fs::file_time_type::clock::now() - std::chrono::hours(24);
  fs::last_write_time(path, reference + std::chrono::seconds(seconds));
}

/** Sets (or with nullopt unsets) an environment variable for the scope, then restores it. */
class EnvGuard {
public:
  EnvGuard(const char* name, std::optional<std::string> value) : mName(name) {
    if (const char* old = std::getenv(name)) {
      mOld = old;
    }
    set(value);
  }
  ~EnvGuard() { set(mOld); }
  EnvGuard(const EnvGuard&) = delete;
  EnvGuard& operator=(const EnvGuard&) = delete;

private:
  void set(const std::optional<std::string>& value) {
    if (value) {
      ::setenv(mName.c_str(), value->c_str(), 1);
    } else {
      ::unsetenv(mName.c_str());
    }
  }
  std::string mName;
  std::optional<std::string> mOld;
};

/** Reaps until `pid` has finished (polling every 2 ms, at most 20 s); keeps the others reaped meanwhile. */
ChildExit waitFor(int pid) {
  static std::map<int, ChildExit> finished;
  for (int i = 0; i < 10000; ++i) {
    for (const ChildExit& e : reapChildren()) {
      finished[e.pid] = e;
    }
    if (const auto it = finished.find(pid); it != finished.end()) {
      const ChildExit e = it->second;
      finished.erase(it);
      return e;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ADD_FAILURE() << "child " << pid << " did not finish";
  return {};
}

// ---------------------------------------------------------------------------------------------------------
// FileWatcher

TEST(FoldingWorkspace, WatcherReportsAWriteOnceItIsStable) {
  test::TempDir dir;
  const fs::path a = dir / "a.png";
  write(a, "aaaa");
  setTime(a, 0);
  FileWatcher watcher;
  watcher.watch(a);
  EXPECT_EQ(watcher.poll(), Paths{}) << "the state at watch() is the reference";
  write(a, "bbbbbb");
  setTime(a, 10);
  EXPECT_EQ(watcher.poll(), Paths{}) << "just changed: wait one poll";
  EXPECT_EQ(watcher.poll(), Paths{a});
  EXPECT_EQ(watcher.poll(), Paths{}) << "reported once";
  // Same size, only the time differs (an editor rewriting the same number of bytes).
  write(a, "cccccc");
  setTime(a, 20);
  EXPECT_EQ(watcher.poll(), Paths{});
  EXPECT_EQ(watcher.poll(), Paths{a});
  EXPECT_EQ(watcher.poll(), Paths{});
}

TEST(FoldingWorkspace, WatcherWaitsWhileAFileIsStillBeingWritten) {
  test::TempDir dir;
  const fs::path a = dir / "a.png";
  write(a, "start");
  setTime(a, 0);
  FileWatcher watcher;
  watcher.watch(a);
  // Truncate, then write in pieces with a poll in between each: nothing until it holds still.
  fs::resize_file(a, 0);
  setTime(a, 1);
  EXPECT_EQ(watcher.poll(), Paths{});
  for (int i = 0; i < 4; ++i) {
    append(a, "0123456789");
    setTime(a, 2 + i);
    EXPECT_EQ(watcher.poll(), Paths{}) << "still growing at piece " << i;
  }
  EXPECT_EQ(watcher.poll(), Paths{a});
  EXPECT_EQ(watcher.poll(), Paths{});
  EXPECT_EQ(fs::file_size(a), 40u);
}

TEST(FoldingWorkspace, WatcherSeesARenameOverTheFile) {
  // GIMP and Krita write a temporary file and rename it over the original: a new inode, possibly with the
  // same size and time.
  test::TempDir dir;
  const fs::path a = dir / "a.png";
  write(a, "original");
  setTime(a, 0);
  FileWatcher watcher;
  watcher.watch(a);
  const fs::path tmp = dir / ".a.png.tmp";
  write(tmp, "replaced"); // same size
  fs::last_write_time(tmp, fs::last_write_time(a));
  const FileWatcher::Signature old = FileWatcher::signature(a);
  fs::rename(tmp, a);
  const FileWatcher::Signature now = FileWatcher::signature(a);
  EXPECT_EQ(now.size, old.size);
  EXPECT_EQ(now.mtimeNs, old.mtimeNs);
  EXPECT_NE(now.inode, old.inode);
  EXPECT_EQ(watcher.poll(), Paths{});
  EXPECT_EQ(watcher.poll(), Paths{a});
  EXPECT_EQ(watcher.poll(), Paths{});
}

TEST(FoldingWorkspace, WatcherIgnoresAMissingFileUntilItReappears) {
  test::TempDir dir;
  const fs::path a = dir / "a.png";
  const fs::path b = dir / "b.png";
  write(a, "aaaa");
  setTime(a, 0);
  FileWatcher watcher;
  watcher.watch(a);
  watcher.watch(b); // missing from the start
  fs::remove(a);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(watcher.poll(), Paths{}) << "a deleted file is not a change";
  }
  write(a, "recreated");
  setTime(a, 5);
  write(b, "new");
  setTime(b, 5);
  EXPECT_EQ(watcher.poll(), Paths{});
  EXPECT_EQ(watcher.poll(), (Paths{a, b})) << "sorted, each once";
  EXPECT_EQ(watcher.poll(), Paths{});
  // Deleted and recreated between two polls: still one change.
  fs::remove(a);
  write(a, "again!!!!");
  setTime(a, 9);
  EXPECT_EQ(watcher.poll(), Paths{});
  EXPECT_EQ(watcher.poll(), Paths{a});
  // A directory in its place counts as missing.
  fs::remove(b);
  fs::create_directory(b);
  EXPECT_EQ(watcher.poll(), Paths{});
  EXPECT_EQ(watcher.poll(), Paths{});
}

TEST(FoldingWorkspace, WatcherWatchUnwatchClear) {
  test::TempDir dir;
  const fs::path a = dir / "a.png";
  const fs::path b = dir / "b.png";
  write(a, "a");
  write(b, "b");
  setTime(a, 0);
  setTime(b, 0);
  FileWatcher watcher;
  watcher.watch(b);
  watcher.watch(a);
  write(a, "aa");
  setTime(a, 1);
  watcher.watch(a); // already watched: keeps its state, so the change above is still seen
  EXPECT_EQ(watcher.paths(), (Paths{a, b}));
  EXPECT_EQ(watcher.poll(), Paths{});
  EXPECT_EQ(watcher.poll(), Paths{a});
  watcher.unwatch(b);
  EXPECT_EQ(watcher.paths(), Paths{a});
  write(b, "bb");
  setTime(b, 1);
  EXPECT_EQ(watcher.poll(), Paths{});
  EXPECT_EQ(watcher.poll(), Paths{}) << "b is no longer watched";
  watcher.clear();
  EXPECT_TRUE(watcher.paths().empty());
}

// ---------------------------------------------------------------------------------------------------------
// RecentFiles

TEST(FoldingWorkspace, RecentFilesKeepTenCanonicalPathsMostRecentFirst) {
  test::TempDir dir;
  fs::create_directories(dir / "sub");
  std::vector<fs::path> files;
  for (int i = 0; i < 12; ++i) {
    files.push_back(fs::canonical(dir.path()) / fmt::format("p{}.json", i));
    write(files.back(), "{}");
  }
  RecentFiles recent(dir / "config" / "recent.json");
  for (const fs::path& f : files) {
    recent.add(f);
  }
  ASSERT_EQ(recent.entries().size(), RecentFiles::kMax);
  EXPECT_EQ(recent.entries().front(), files[11]);
  EXPECT_EQ(recent.entries().back(), files[2]);
  // Re-adding moves to the front without a duplicate; a non-canonical spelling is the same file.
  recent.add(dir / "sub" / ".." / "p5.json");
  EXPECT_EQ(recent.entries().front(), files[5]);
  EXPECT_EQ(recent.entries().size(), RecentFiles::kMax);
  EXPECT_EQ(std::count(recent.entries().begin(), recent.entries().end(), files[5]), 1);
  // Symbolic links resolve to their target.
  fs::create_symlink(files[3], dir / "link.json");
  recent.add(dir / "link.json");
  EXPECT_EQ(recent.entries().front(), files[3]);
  recent.remove(files[3]);
  EXPECT_EQ(recent.entries().front(), files[5]);

  std::string warning = "x";
  ASSERT_TRUE(recent.save(&warning)) << warning;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "config"), fs::directory_iterator()), 1)
      << "no temporary file left";
  RecentFiles again(dir / "config" / "recent.json");
  again.load(&warning);
  EXPECT_EQ(warning, "");
  EXPECT_EQ(again.entries(), recent.entries());
  // Files that are gone are dropped when loading.
  fs::remove(files[5]);
  fs::remove(files[11]);
  again.load(&warning);
  EXPECT_EQ(warning, "");
  EXPECT_EQ(again.entries().size(), recent.entries().size() - 2);
  EXPECT_EQ(std::count(again.entries().begin(), again.entries().end(), files[5]), 0);
  EXPECT_EQ(again.entries().front(), files[10]);
}

TEST(FoldingWorkspace, RecentFilesNeverThrowOnBadFiles) {
  test::TempDir dir;
  const fs::path file = dir / "recent.json";
  write(dir / "p.json", "{}");
  RecentFiles recent(file);
  std::string warning = "x";
  recent.add(dir / "p.json");
  recent.load(&warning);
  EXPECT_TRUE(recent.entries().empty());
  EXPECT_EQ(warning, "") << "a missing file is simply an empty list";
  for (const std::string& bad :
       {std::string("{not json"), std::string("[1, 2]"), std::string(R"({"format": "other", "version": 1})"),
        std::string(R"({"format": "sylva-recent-files", "version": 2, "files": []})"),
        std::string(R"({"format": "sylva-recent-files", "version": 1, "files": [3]})"),
        std::string(R"({"format": "sylva-recent-files", "version": 1, "files": "a"})"), std::string("")}) {
    SCOPED_TRACE(bad);
    write(file, bad);
    recent.add(dir / "p.json");
    warning.clear();
    EXPECT_NO_THROW(recent.load(&warning));
    EXPECT_TRUE(recent.entries().empty());
    EXPECT_NE(warning.find(file.string()), std::string::npos) << warning;
    EXPECT_EQ(warning.find('\n'), std::string::npos) << "one line";
    EXPECT_NO_THROW(recent.load());
  }
  // Relative entries are not valid and are dropped; the rest loads.
  const std::string abs = fs::canonical(dir / "p.json").string();
  write(file, R"({"format": "sylva-recent-files", "version": 1, "files": ["p.json", ")" + abs + "\"]}");
  recent.load(&warning);
  EXPECT_EQ(warning, "");
  EXPECT_EQ(recent.entries(), Paths{abs});
  // A location that cannot be written: false and a warning, no throw.
  write(dir / "blocker", "file");
  RecentFiles blocked(dir / "blocker" / "recent.json");
  blocked.add(dir / "p.json");
  EXPECT_FALSE(blocked.save(&warning));
  EXPECT_NE(warning.find("blocker"), std::string::npos) << warning;
  EXPECT_FALSE(RecentFiles(fs::path()).save(&warning));
}

TEST(FoldingWorkspace, RecentFilesDefaultLocation) {
  {
    EnvGuard xdg("XDG_CONFIG_HOME", "/xdg/config");
    EXPECT_EQ(RecentFiles::defaultPath(), fs::path("/xdg/config/sylva/recent-folding.json"));
  }
  {
    EnvGuard xdg("XDG_CONFIG_HOME", "relative/ignored");
    EnvGuard home("HOME", "/home/artist");
    EXPECT_EQ(RecentFiles::defaultPath(), fs::path("/home/artist/.config/sylva/recent-folding.json"));
    EXPECT_EQ(RecentFiles().file(), RecentFiles::defaultPath());
  }
  {
    EnvGuard xdg("XDG_CONFIG_HOME", std::nullopt);
    EnvGuard home("HOME", std::nullopt);
    EXPECT_EQ(RecentFiles::defaultPath(), fs::path());
  }
}

// ---------------------------------------------------------------------------------------------------------
// External image editor

TEST(FoldingWorkspace, CommandLinesSplitWithSimpleQuoting) {
  using Words = std::vector<std::string>;
  EXPECT_EQ(splitCommandLine("  gimp   -n\t--x "), (Words{"gimp", "-n", "--x"}));
  EXPECT_EQ(splitCommandLine(R"('a b' "p \"q\" \\r" z\ w '' x'y'"z")"),
            (Words{"a b", R"(p "q" \r)", "z w", "", "xyz"}));
  EXPECT_EQ(splitCommandLine(R"("it's" 'say "hi"')"), (Words{"it's", R"(say "hi")"}));
  EXPECT_EQ(splitCommandLine(""), Words{});
  std::string why;
  EXPECT_FALSE(splitCommandLine("gimp 'open", &why));
  EXPECT_NE(why.find("unterminated single quote"), std::string::npos) << why;
  EXPECT_FALSE(splitCommandLine("gimp \"open", &why));
  EXPECT_NE(why.find("unterminated double quote"), std::string::npos) << why;
  EXPECT_FALSE(splitCommandLine("gimp open\\", &why));
  EXPECT_NE(why.find("trailing backslash"), std::string::npos) << why;
}

TEST(FoldingWorkspace, ImageEditorCommandFromTheEnvironmentOrGimp) {
  test::TempDir dir;
  const fs::path image = fs::canonical(dir.path()) / "cat image.png";
  write(image, "png");
  using Words = std::vector<std::string>;
  {
    EnvGuard editor("SYLVA_IMAGE_EDITOR", "krita --file={} --nosplash '{}.bak'");
    EXPECT_EQ(imageEditorCommand(image),
              (Words{"krita", "--file=" + image.string(), "--nosplash", image.string() + ".bak"}));
  }
  {
    EnvGuard editor("SYLVA_IMAGE_EDITOR", "'/opt/my editor/bin/edit' -n");
    EXPECT_EQ(imageEditorCommand(image), (Words{"/opt/my editor/bin/edit", "-n", image.string()}));
    // A relative image becomes absolute.
    const fs::path cwd = fs::current_path();
    fs::current_path(dir.path());
    const auto words = imageEditorCommand("cat image.png");
    fs::current_path(cwd);
    EXPECT_EQ(words, (Words{"/opt/my editor/bin/edit", "-n", image.string()}));
  }
  {
    EnvGuard editor("SYLVA_IMAGE_EDITOR", "edit 'broken");
    std::string why;
    EXPECT_FALSE(imageEditorCommand(image, &why));
    EXPECT_EQ(why.rfind("SYLVA_IMAGE_EDITOR: unterminated single quote", 0), 0u) << why;
  }
  // Unset or blank: GIMP from PATH.
  fs::create_directories(dir / "bin");
  fs::create_directories(dir / "empty");
  write(dir / "bin" / "gimp", "#!/bin/sh\n");
  fs::permissions(dir / "bin" / "gimp", fs::perms::owner_all);
  for (const std::optional<std::string>& unset :
       {std::optional<std::string>(), std::optional<std::string>(" ")}) {
    EnvGuard editor("SYLVA_IMAGE_EDITOR", unset);
    {
      EnvGuard path("PATH", (dir / "empty").string() + ":" + (dir / "bin").string());
      EXPECT_EQ(imageEditorCommand(image), (Words{(dir / "bin" / "gimp").string(), image.string()}));
    }
    {
      EnvGuard path("PATH", (dir / "empty").string());
      std::string why;
      EXPECT_FALSE(imageEditorCommand(image, &why));
      EXPECT_NE(why.find("install GIMP"), std::string::npos) << why;
      EXPECT_NE(why.find("SYLVA_IMAGE_EDITOR"), std::string::npos) << why;
      EXPECT_EQ(why.find('\n'), std::string::npos);
    }
  }
}

TEST(FoldingWorkspace, LaunchDetachedRunsTheConfiguredEditor) {
  test::TempDir dir;
  const fs::path image = dir / "a.png";
  const fs::path copy = dir / "b.png";
  write(image, "pixels");
  // The editor copies the image, as a stand-in for an editor that saves it somewhere.
  EnvGuard editor("SYLVA_IMAGE_EDITOR", "sh -c 'cp \"$0\" \"$1\"' {} '" + copy.string() + "'");
  std::string why;
  const auto command = imageEditorCommand(image, &why);
  ASSERT_TRUE(command) << why;
  std::string error;
  const int pid = launchDetached(*command, &error);
  ASSERT_GT(pid, 0) << error;
  // Its own process group (a zombie keeps it until reaped, so this does not race with its exit).
  EXPECT_EQ(::getpgid(pid), pid);
  EXPECT_NE(::getpgid(pid), ::getpgrp());
  const ChildExit exit = waitFor(pid);
  EXPECT_EQ(exit.exitCode, 0);
  EXPECT_EQ(exit.signal, 0);
  EXPECT_EQ(readTextFile(copy), "pixels");
  const std::vector<int> running = runningChildren();
  EXPECT_EQ(std::count(running.begin(), running.end(), pid), 0) << "reaped and forgotten";
}

TEST(FoldingWorkspace, LaunchDetachedChildrenReadNothingAndReportHowTheyEnded) {
  test::TempDir dir;
  const fs::path out = dir / "stdin.txt";
  {
    EnvGuard editor("SYLVA_IMAGE_EDITOR", "sh -c 'readlink /proc/self/fd/0 > \"$0\"'");
    const int pid = launchDetached(*imageEditorCommand(out));
    ASSERT_GT(pid, 0);
    EXPECT_EQ(waitFor(pid).exitCode, 0);
    EXPECT_EQ(readTextFile(out), "/dev/null\n");
  }
  // Several at once, each reaped with its own status; the signal's default action is restored.
  const int three = launchDetached({"sh", "-c", "exit 3"});
  const int killed = launchDetached({"sh", "-c", "kill -TERM $$; sleep 5"});
  const int sleeper = launchDetached({"sh", "-c", "sleep 0.05"});
  ASSERT_GT(three, 0);
  ASSERT_GT(killed, 0);
  ASSERT_GT(sleeper, 0);
  EXPECT_EQ(waitFor(killed).signal, SIGTERM);
  EXPECT_EQ(waitFor(three).exitCode, 3);
  EXPECT_EQ(waitFor(sleeper).exitCode, 0);
  // Programs that cannot start: −1 and one line naming them.
  std::string error;
  EXPECT_EQ(launchDetached({"/nonexistent/sylva-no-such-editor", "x.png"}, &error), -1);
  EXPECT_NE(error.find("sylva-no-such-editor"), std::string::npos) << error;
  EXPECT_EQ(launchDetached({}, &error), -1);
  EXPECT_NE(error.find("empty command"), std::string::npos) << error;
}

} // namespace
} // namespace sylva::folding
