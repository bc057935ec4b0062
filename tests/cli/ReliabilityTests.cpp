// Reliability of the `sylva` command as a process: runs killed with SIGKILL at seeded random moments leave
// every output either absent or complete (byte-identical to an uninterrupted run); SIGINT cancels cleanly
// with one line; and every command that writes files writes the same bytes twice and from two working
// directories. Label gl (render needs a context). SYLVA_FULL=1 runs many more kill moments (docs/testing.md).
#include "TempDir.hpp"

#include <sylva/core/Image.hpp>
#include <sylva/terrain/HeightSources.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

extern char** environ;

namespace sylva {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/** `sylva args...` started in `cwd`, stdout/stderr to files there. */
pid_t spawnSylva(const std::vector<std::string>& args, const fs::path& cwd) {
  std::vector<std::string> all{SYLVA_EXE};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) {
    argv.push_back(a.data());
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "stdout.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, "stderr.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, SYLVA_EXE, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    ADD_FAILURE() << "posix_spawn failed: " << rc;
    return -1;
  }
  return pid;
}

int waitFor(pid_t pid) {
  if (pid <= 0) {
    return -1;
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

/**
 * Waits until process `pid` catches SIGINT (its handler is installed first thing in main(), so from then on
 * a SIGINT is answered by sylva rather than by the default action during exec and library loading, which
 * takes a variable time on a loaded machine). Reads the SigCgt mask of /proc/<pid>/status; false when the
 * process ended first or 60 s passed.
 */
bool waitUntilCatchingSigint(pid_t pid) {
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < deadline) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(status, line);) {
      if (line.starts_with("State:") && line.find('Z') != std::string::npos) {
        return false;
      }
      if (line.starts_with("SigCgt:")) {
        const unsigned long long caught = std::stoull(line.substr(7), nullptr, 16);
        if ((caught >> (SIGINT - 1)) & 1ULL) {
          return true;
        }
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

/** Runs to completion; returns the exit status (-signal when killed) and the wall time. */
std::pair<int, double> runSylva(const std::vector<std::string>& args, const fs::path& cwd) {
  const auto start = Clock::now();
  const int status = waitFor(spawnSylva(args, cwd));
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status), seconds};
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.starts_with(".") && name.find(".tmp.") != std::string::npos) {
      names.push_back(name);
    }
  }
  return names;
}

/** A command that writes files, and the files it writes (relative to its working directory). */
struct Job {
  std::string name;
  std::vector<std::string> args;
  std::vector<std::string> outputs;
};

std::vector<Job> killJobs() {
  return {
      {"heightmap_png",
       {"terrain", "heightmap", "--seed", "11", "--size", "2049", "-o", "h.png"},
       {"h.png", "h.png.json"}},
      {"heightmap_tif", {"terrain", "heightmap", "--seed", "12", "--size", "2049", "-o", "h.tif"}, {"h.tif"}},
      {"normals_exr", {"terrain", "normals", "--seed", "13", "--size", "1537", "-o", "n.exr"}, {"n.exr"}},
      {"splat_png", {"terrain", "splat", "--seed", "14", "--size", "1537", "-o", "s.png"}, {"s.png"}},
      {"render_png",
       {"render", "--size", "513", "--width", "480", "--height", "270", "-o", "r.png"},
       {"r.png"}},
  };
}

/** The reference output is itself valid: loadable by our own readers. */
void expectLoadable(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".png" || ext == ".exr") {
    EXPECT_NO_THROW((void)loadImage(path)) << path;
  }
  if (ext == ".tif") {
    EXPECT_NO_THROW((void)terrain::loadHeightField(path)) << path;
  }
}

TEST(Reliability, KilledRunsLeaveNoPartialOutputs) {
  const int killsPerJob = test::fullMode() ? 40 : 4;
  std::mt19937 random(20261130u); // seeded: the same moments every run
  const test::TempDir dir;
  int absent = 0;
  int complete = 0;
  int mixed = 0;
  for (const Job& job : killJobs()) {
    SCOPED_TRACE(job.name);
    const fs::path ref = dir / (job.name + "_ref");
    fs::create_directories(ref);
    const auto [status, seconds] = runSylva(job.args, ref);
    ASSERT_EQ(status, 0) << readAll(ref / "stderr.txt");
    std::vector<std::string> expected;
    for (const std::string& output : job.outputs) {
      expectLoadable(ref / output);
      expected.push_back(readAll(ref / output));
      ASSERT_FALSE(expected.back().empty()) << output;
    }
    // Half the moments anywhere in the run, half in its last quarter, where the outputs are written.
    std::uniform_real_distribution<double> anywhere(0.0, 1.1 * seconds);
    std::uniform_real_distribution<double> writing(0.75 * seconds, 1.05 * seconds);
    fs::path lastKilled;
    for (int k = 0; k < killsPerJob; ++k) {
      const fs::path run = dir / (job.name + "_kill" + std::to_string(k));
      fs::create_directories(run);
      const double delay = k % 2 == 0 ? anywhere(random) : writing(random);
      const pid_t pid = spawnSylva(job.args, run);
      ASSERT_GT(pid, 0); // never kill(-1, ...): that would signal every process we may signal
      std::this_thread::sleep_for(std::chrono::duration<double>(delay));
      ::kill(pid, SIGKILL);
      waitFor(pid);
      int present = 0;
      for (std::size_t i = 0; i < job.outputs.size(); ++i) {
        const fs::path out = run / job.outputs[i];
        if (fs::exists(out)) {
          ++present;
          EXPECT_TRUE(readAll(out) == expected[i]) << job.outputs[i] << " exists after SIGKILL at " << delay
                                                   << " s but differs from the complete file";
        }
      }
      (present == 0 ? absent : present == static_cast<int>(job.outputs.size()) ? complete : mixed)++;
      if (!temporaries(run).empty()) {
        lastKilled = run;
      }
    }
    // A killed run can leave its temporary behind (nothing runs after SIGKILL); the next write of the same
    // output removes it.
    if (!lastKilled.empty()) {
      const auto [again, unused] = runSylva(job.args, lastKilled);
      EXPECT_EQ(again, 0);
      EXPECT_TRUE(temporaries(lastKilled).empty()) << temporaries(lastKilled).front();
    }
  }
  RecordProperty("kills", std::to_string(killsPerJob * static_cast<int>(killJobs().size())));
  RecordProperty("outputs_absent", std::to_string(absent));
  RecordProperty("outputs_complete", std::to_string(complete));
  RecordProperty("outputs_some", std::to_string(mixed));
  std::printf("kill test: %d kills: %d with no output yet, %d with every output complete, %d with some\n",
              killsPerJob * static_cast<int>(killJobs().size()), absent, complete, mixed);
}

/**
 * SIGINT after `fraction` of the command's usual time: one line on stderr, none of `outputs` (files or
 * directories), no temporary. A run that ends before the signal arrives (the machine was less loaded than
 * for the reference run) proves nothing; it is retried with half the delay, up to five times.
 */
void expectCleanInterrupt(const std::vector<std::string>& args, const std::vector<std::string>& outputs,
                          double fraction, const test::TempDir& dir, const std::string& name) {
  // The command's usual time is counted from the moment it catches SIGINT, and the signal is sent that
  // fraction after the interrupted run reaches the same moment: process start-up (exec, loading libraries)
  // varies with the machine's load and would otherwise decide whether sylva or the kernel answers.
  const fs::path ref = dir / (name + "_ref");
  fs::create_directories(ref);
  const pid_t refPid = spawnSylva(args, ref);
  ASSERT_GT(refPid, 0);
  ASSERT_TRUE(waitUntilCatchingSigint(refPid)) << readAll(ref / "stderr.txt");
  const auto refStart = Clock::now();
  const int refStatus = waitFor(refPid);
  const double seconds = std::chrono::duration<double>(Clock::now() - refStart).count();
  ASSERT_TRUE(WIFEXITED(refStatus) && WEXITSTATUS(refStatus) == 0) << readAll(ref / "stderr.txt");
  for (int attempt = 0; attempt < 5; ++attempt, fraction *= 0.5) {
    SCOPED_TRACE("SIGINT after " + std::to_string(fraction * seconds) + " s");
    const fs::path run = dir / (name + std::to_string(attempt));
    fs::create_directories(run);
    const pid_t pid = spawnSylva(args, run);
    ASSERT_GT(pid, 0);
    ASSERT_TRUE(waitUntilCatchingSigint(pid)) << readAll(run / "stderr.txt");
    std::this_thread::sleep_for(std::chrono::duration<double>(fraction * seconds));
    ::kill(pid, SIGINT);
    const int raw = waitFor(pid);
    // Progress lines (`<step>: 25% ...` and `<step>: done (N/N) in …`, printed when stderr is not a terminal)
    // are not messages: drop them.
    std::string err;
    {
      std::istringstream lines(readAll(run / "stderr.txt"));
      for (std::string line; std::getline(lines, line);) {
        if (line.find("%) ") == std::string::npos && line.find("% (") == std::string::npos &&
            line.find(": done (") == std::string::npos) {
          err += line + "\n";
        }
      }
    }
    if (WIFEXITED(raw) && WEXITSTATUS(raw) == 0 && err.empty()) {
      // Finished before the signal: the outputs must be the complete ones, and the next try signals sooner.
      for (const std::string& output : outputs) {
        if (fs::is_regular_file(ref / output)) {
          EXPECT_EQ(readAll(run / output), readAll(ref / output));
        }
      }
      continue;
    }
    for (const std::string& output : outputs) {
      EXPECT_FALSE(fs::exists(run / output)) << "interrupted run wrote " << output;
    }
    EXPECT_TRUE(temporaries(run).empty());
    ASSERT_FALSE(err.empty()) << "no message on SIGINT";
    EXPECT_EQ(err.find('\n'), err.size() - 1) << "more than one line: " << err;
    if (WIFEXITED(raw)) {
      EXPECT_EQ(WEXITSTATUS(raw), 2) << err;
      EXPECT_NE(err.find("cancelled"), std::string::npos) << err;
    } else {
      EXPECT_EQ(WTERMSIG(raw), SIGINT) << err;
      EXPECT_NE(err.find("interrupted"), std::string::npos) << err;
    }
    return;
  }
  ADD_FAILURE() << "every run finished before SIGINT arrived (the reference took " << seconds << " s)";
}

TEST(Reliability, SigintCancelsLongGenerationWithOneLine) {
  const test::TempDir dir;
  // Progress-reporting work (generation in strips) cancels and the command fails with its own message.
  expectCleanInterrupt({"terrain", "heightmap", "--seed", "3", "--size", "4097", "-o", "big.png"},
                       {"big.png"}, 0.3, dir, "heightmap");
}

TEST(Reliability, SigintInterruptsRenderWithOneLine) {
  const test::TempDir dir;
  expectCleanInterrupt({"render", "--size", "513", "--width", "480", "--height", "270", "-o", "r.png"},
                       {"r.png"}, 0.5, dir, "render");
}

// A folding render writes a GIF and then a folder of PNG frames, the last part of its run: a SIGINT while
// they are written (first at 90 % of the usual time) once left the complete GIF and some frames. Now it
// leaves none of them.
TEST(Reliability, SigintWhileAFoldRenderWritesLeavesNoOutput) {
  const test::TempDir dir;
  const std::string project = test::sourcePath("data/folding/beach.json").string();
  expectCleanInterrupt({"fold", "render", project, "--fps", "50", "--gif", "b.gif", "-o", "frames"},
                       {"b.gif", "frames"}, 0.9, dir, "fold");
}

/** Every command that writes files, with relative paths only (so the working directory is all that differs).
 */
const std::vector<Job>& deterministicJobs() {
  static const std::vector<Job> jobs = {
      {"heightmap",
       {"terrain", "heightmap", "--seed", "5", "--size", "257", "-o", "h.png"},
       {"h.png", "h.png.json"}},
      {"heightmap_exr",
       {"terrain", "heightmap", "--seed", "5", "--size", "257", "-o", "h.exr"},
       {"h.exr", "h.exr.json"}},
      {"heightmap_npy",
       {"terrain", "heightmap", "--seed", "5", "--type", "ridged", "--size", "257", "-o", "h.npy"},
       {"h.npy"}},
      {"heightmap_tif",
       {"terrain", "heightmap", "--seed", "5", "--type", "fbm", "--size", "257", "-o", "h.tif"},
       {"h.tif"}},
      {"normals_from_dem", {"terrain", "normals", "--dem", "h.npy", "-o", "n.png"}, {"n.png"}},
      {"normals_exr", {"terrain", "normals", "--seed", "5", "--size", "257", "-o", "n.exr"}, {"n.exr"}},
      {"splat", {"terrain", "splat", "--dem", "h.tif", "-o", "s.png"}, {"s.png"}},
      {"layers",
       {"terrain", "splat", "--seed", "5", "--size", "129", "--write-default-layers", "l.json"},
       {"l.json"}},
      {"info_json", {"terrain", "info", "--dem", "h.npy", "--json"}, {"stdout.txt"}},
      {"render",
       {"render", "--seed", "5", "--size", "257", "--width", "320", "--height", "180", "-o", "r.png"},
       {"r.png"}},
      {"render_dem",
       {"render", "--dem", "h.tif", "--width", "320", "--height", "180", "-o", "r2.png"},
       {"r2.png"}},
  };
  return jobs;
}

std::map<std::string, std::string> runAll(const fs::path& cwd) {
  std::map<std::string, std::string> files;
  for (const Job& job : deterministicJobs()) {
    const auto [status, seconds] = runSylva(job.args, cwd);
    EXPECT_EQ(status, 0) << job.name << ": " << readAll(cwd / "stderr.txt");
    for (const std::string& output : job.outputs) {
      files[job.name + "/" + output] = readAll(cwd / output);
      EXPECT_FALSE(files[job.name + "/" + output].empty()) << job.name << " wrote no " << output;
    }
  }
  return files;
}

TEST(Reliability, OutputsAreByteIdenticalAcrossRunsAndWorkingDirectories) {
  const test::TempDir dir;
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "elsewhere/b");
  const auto first = runAll(dir / "a");
  const auto again = runAll(dir / "a");
  const auto other = runAll(dir / "elsewhere/b");
  ASSERT_EQ(first.size(), again.size());
  for (const auto& [name, bytes] : first) {
    EXPECT_TRUE(bytes == again.at(name)) << name << " differs between two runs in the same directory";
    EXPECT_TRUE(bytes == other.at(name)) << name << " differs between two working directories";
  }
  RecordProperty("files_compared", std::to_string(first.size()));
}

TEST(Reliability, SoakKeepsMemoryFlatWithoutGlErrors) {
  const test::TempDir dir;
  const std::string frames = test::fullMode() ? "10000" : "1000";
  const auto [status, seconds] = runSylva({"bench", "soak", "--frames", frames, "--warmup", "100", "--size",
                                           "257", "--width", "320", "--height", "180", "-o", "soak.json"},
                                          dir.path());
  EXPECT_EQ(status, 0) << readAll(dir / "stderr.txt") << readAll(dir / "stdout.txt");
  const nlohmann::json report = nlohmann::json::parse(readAll(dir / "soak.json"));
  EXPECT_EQ(report.at("gl_errors").get<int>(), 0);
  EXPECT_LT(report.at("rss_growth_percent").get<double>(), 1.0);
  EXPECT_TRUE(report.at("passed").get<bool>());
  EXPECT_EQ(report.at("frame_ms").at("count").get<int>(), std::stoi(frames));
  RecordProperty("rss_growth_percent", std::to_string(report.at("rss_growth_percent").get<double>()));
  RecordProperty("frame_time_drift_percent",
                 std::to_string(report.at("frame_time_drift_percent").get<double>()));
}

} // namespace
} // namespace sylva
