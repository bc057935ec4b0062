// `sylva farm` without a cluster (docs/farm.md): the job scripts it would submit (--dry-run), and its
// one-line errors, each before anything is written or submitted: no Slurm on PATH, a scene that does not
// load, more tasks than frames, a folder that is not a farm. The real Slurm runs in FarmSlurmTests.cpp.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <filesystem>

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

} // namespace
} // namespace sylva
