// `sylva farm` without a cluster (docs/farm.md): the job scripts it would submit (--dry-run), and its
// one-line errors, each before anything is written or submitted: no Slurm on PATH, a scene that does not
// load, more tasks than frames, a folder that is not a farm. The real Slurm runs in FarmSlurmTests.cpp.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace sylva {
namespace {

namespace fs = std::filesystem;
using test::quote;

const std::string kMeadow = quote(std::string(SYLVA_SOURCE_DIR) + "/data/scenes/meadow.json");

/** `sylva ARGS` with PATH holding no Slurm (nor anything else). */
test::RunResult withoutSlurm(const test::TempDir& dir, const std::string& args) {
  return test::runProgram("/usr/bin/env", dir.path(),
                          "PATH=/nonexistent-sylva-path " + quote(SYLVA_EXE) + " " + args);
}

TEST(FarmCli, DryRunPrintsTheScriptsAndWritesNothing) {
  test::TempDir dir;
  const test::RunResult r = withoutSlurm(
      dir, "farm submit " + kMeadow + " --frames 0-11 --tasks 4 --gif " + test::at(dir, "a.gif") + " --out " +
               test::at(dir, "frames") + " --partition render --gpus-per-task 1 --dry-run");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* part :
       {"#SBATCH --array=0-3", "#SBATCH --partition=render", "#SBATCH --gres=gpu:1", "--shard \"$task/4\"",
        "attempts=3", "sylva-meadow-encode", "--gif", "would submit: sbatch --array=0-3"}) {
    EXPECT_NE(r.out.find(part), std::string::npos) << part << " in\n" << r.out;
  }
  EXPECT_FALSE(fs::exists(dir / "frames"));
}

TEST(FarmCli, ErrorsComeBeforeAnythingIsWrittenOrSubmitted) {
  test::TempDir dir;
  const std::string out = " --out " + test::at(dir, "frames");
  struct Case {
    std::string args;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"farm submit " + kMeadow + " --frames 0-11 --tasks 4" + out, "sbatch not found on PATH"},
      {"farm submit " + test::at(dir, "nothing.json") + " --frames 0-11" + out, "nothing.json"},
      {"farm submit " + kMeadow + " --frames 0-11 --tasks 20" + out, "--tasks 20: only 12 frames"},
      {"farm submit " + kMeadow + " --frames 0-2999 --chunk 1" + out, "--chunk 3"},
      {"farm submit " + kMeadow + " --frames 0-11 --camera nowhere" + out, "--camera nowhere"},
      {"farm submit " + kMeadow + " --frames 0-11 --gif " + test::at(dir, "a.png") + out, "--gif"},
      {"farm status " + test::at(dir, "frames"), "not a farm"},
      {"farm each " + kMeadow + " -o " + test::at(dir, "each"), "no command"},
  };
  for (const Case& c : cases) {
    const test::RunResult r = withoutSlurm(dir, c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(test::lineCount(r.err), 1u) << r.err;
    EXPECT_FALSE(fs::exists(dir / "frames")) << c.args;
    EXPECT_FALSE(fs::exists(dir / "each")) << c.args;
  }
}

/** A folder of stand-ins for Slurm's commands: sbatch answers `sbatchOut` with `sbatchStatus`. */
void fakeSlurm(const fs::path& bin, const std::string& sbatchOut, int sbatchStatus,
               const std::string& scontrolOut) {
  fs::create_directories(bin);
  const auto write = [&](const char* name, const std::string& body) {
    std::ofstream(bin / name) << "#!/bin/sh\n" << body;
    fs::permissions(bin / name, fs::perms::owner_all);
  };
  write("sbatch", "echo " + quote(sbatchOut) + (sbatchStatus ? " >&2" : "") + "\nexit " +
                      std::to_string(sbatchStatus) + "\n");
  write("scontrol", "printf '%s\\n' " + quote(scontrolOut) + "\n");
  write("scancel", "exit 0\n");
}

TEST(FarmCli, SubmissionsGoThroughSbatchAndAFolderHoldsOneFarm) {
  test::TempDir dir;
  const std::string out = " --out " + test::at(dir, "frames");
  const std::string submit =
      "farm submit " + kMeadow + " --frames 0-11 --tasks 4 --gif " + test::at(dir, "a.gif") + out;
  const auto run = [&](const std::string& args) {
    return test::runProgram("/usr/bin/env", dir.path(),
                            "PATH=" + quote((dir / "bin").string()) + ":/usr/bin:/bin " + quote(SYLVA_EXE) +
                                " " + args);
  };
  fakeSlurm(dir / "bin", "sbatch: error: Batch job submission failed: Invalid partition name specified", 1,
            "");
  const test::RunResult refused = run(submit + " --partition nowhere");
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find(
                "sbatch failed (exit 1): sbatch: error: Batch job submission failed: Invalid partition"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir / "frames" / "farm" / "farm.json")) << "nothing recorded as submitted";

  fakeSlurm(dir / "bin", "42;cluster", 0,
            "JobId=43 ArrayJobId=42 ArrayTaskId=0 JobState=RUNNING Reason=None ExitCode=0:0\n"
            "JobId=42 ArrayJobId=42 ArrayTaskId=1-3 JobState=PENDING Reason=Resources ExitCode=0:0");
  const test::RunResult submitted = run(submit);
  ASSERT_EQ(submitted.status, 0) << submitted.err;
  EXPECT_NE(submitted.out.find("array job 42 (4 tasks), encode job 42 after it"), std::string::npos)
      << submitted.out;
  const test::RunResult status = run("farm status " + test::at(dir, "frames"));
  EXPECT_EQ(status.status, 0) << status.err;
  EXPECT_NE(status.out.find("RUNNING      42_0"), std::string::npos) << status.out;
  EXPECT_NE(status.out.find("PENDING      42_3"), std::string::npos) << status.out;
  EXPECT_EQ(run("farm resubmit " + test::at(dir, "frames")).out,
            "nothing to resubmit: every task with work missing is pending or running\n");
  // A folder holds one farm: submitting again would render its frames twice.
  const test::RunResult twice = run(submit);
  EXPECT_EQ(twice.status, 2);
  EXPECT_NE(twice.err.find("already holds a farm"), std::string::npos) << twice.err;
}

} // namespace
} // namespace sylva
