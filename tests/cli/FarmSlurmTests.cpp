// `sylva farm` against a real Slurm (docs/farm.md): a single-node cluster started by scripts/slurm-local.sh
// (munged, slurmctld, slurmd under a state folder of its own) for the whole suite and stopped by its pid
// files afterwards, also when a test fails. A scene's frames rendered as a job array must equal a local run
// byte for byte, GIF included; a task made to fail (SYLVA_FAULT_FRAMES) is named by `status`, its encode job
// is cancelled, and `resubmit` renders only what is missing; a task killed with scancel resumes the same way;
// a batch job over a list reports its failed item and finishes after a resubmit. Skips where Slurm cannot run
// (no packages, not root) unless SYLVA_REQUIRE_SLURM=1 (CI).
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <thread>

namespace sylva {
namespace {

namespace fs = std::filesystem;
using test::quote;
using test::readAll;

const std::string kMeadow = std::string(SYLVA_SOURCE_DIR) + "/data/scenes/meadow.json";
// Small frames along the fly-over path: every frame differs (camera, wind, balls), each renders quickly.
const std::string kScene = quote(kMeadow) + " --camera flyover --width 160 --height 90";
const std::string kSequence = kScene + " --frames 0-11";
// The cluster's state: a fixed folder, so a run killed half-way is cleaned up by the next (pid files).
const fs::path kState = "/tmp/sylva-farm-slurm";

std::string frameFile(int frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%05d.png", frame);
  return name;
}

class FarmSlurm : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    // The local reference renders while the cluster starts.
    local = std::make_unique<test::TempDir>();
    std::future<test::RunResult> reference = std::async(std::launch::async, [] {
      return test::runSylva(*local, "render " + kSequence + " --out " + test::at(*local, "frames") +
                                        " --gif " + test::at(*local, "fly.gif"));
    });
    const std::string script = std::string(SYLVA_SOURCE_DIR) + "/scripts/slurm-local.sh";
    const std::string command = quote(script) + " start " + quote(kState.string()) + " > " +
                                quote((kState.string() + ".start.log")) + " 2>&1";
    const int rc = std::system(command.c_str());
    startStatus = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    if (startStatus == 0) {
      ::setenv("SLURM_CONF", (kState / "slurm.conf").c_str(), 1);
    }
    localRun = reference.get();
  }

  static void TearDownTestSuite() {
    const std::string command = quote(std::string(SYLVA_SOURCE_DIR) + "/scripts/slurm-local.sh") + " stop " +
                                quote(kState.string()) + " >/dev/null 2>&1";
    if (std::system(command.c_str()) != 0) {
      std::fprintf(stderr, "slurm-local.sh stop failed\n");
    }
    local.reset();
  }

  void SetUp() override {
    if (startStatus == 77 && std::getenv("SYLVA_REQUIRE_SLURM") == nullptr) {
      GTEST_SKIP() << "Slurm cannot run here: " << readAll(kState.string() + ".start.log")
                   << "(scripts/setup-debian.sh installs it; SYLVA_REQUIRE_SLURM=1 makes this a failure)";
    }
    ASSERT_EQ(startStatus, 0) << "scripts/slurm-local.sh start failed:\n"
                              << readAll(kState.string() + ".start.log");
    ASSERT_EQ(localRun.status, 0) << localRun.err;
  }

  /** `sylva farm wait` (bounded), its exit status. */
  static int waitFor(const test::TempDir& dir, const std::string& farm) {
    const test::RunResult r = test::runSylva(dir, "farm wait " + farm + " --timeout 120");
    return r.status;
  }

  static nlohmann::json status(const test::TempDir& dir, const std::string& farm) {
    const test::RunResult r = test::runSylva(dir, "farm status --json " + farm);
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out, nullptr, false);
  }

  static void expectSameAsLocal(const fs::path& frames, int last = 11) {
    for (int f = 0; f <= last; ++f) {
      ASSERT_TRUE(fs::exists(frames / frameFile(f))) << frames / frameFile(f);
      EXPECT_TRUE(readAll(local->path() / "frames" / frameFile(f)) == readAll(frames / frameFile(f)))
          << frameFile(f) << " differs from the local run";
    }
  }

  static inline int startStatus = -1;
  static inline std::unique_ptr<test::TempDir> local;
  static inline test::RunResult localRun;
};

TEST_F(FarmSlurm, AFailedTaskIsNamedItsEncodeCancelledAndResubmitRendersOnlyWhatIsMissing) {
  test::TempDir dir;
  const std::string out = test::at(dir, "frames");
  // Task 1 renders frames 1, 5, 9: frame 5 fails on purpose, in both of its attempts.
  ::setenv("SYLVA_FAULT_FRAMES", "5", 1);
  const test::RunResult submitted =
      test::runSylva(dir, "farm submit " + kSequence + " --tasks 4 --retries 1 --cpus-per-task 1 --out " +
                              out + " --gif " + test::at(dir, "fly.gif"));
  ::unsetenv("SYLVA_FAULT_FRAMES");
  ASSERT_EQ(submitted.status, 0) << submitted.err;
  EXPECT_NE(submitted.out.find("(4 tasks), encode job"), std::string::npos) << submitted.out;
  EXPECT_TRUE(fs::exists(dir / "frames" / "farm" / "tasks.sbatch"));
  EXPECT_EQ(waitFor(dir, out), 1) << "a frame is missing";

  const nlohmann::json failed = status(dir, out);
  ASSERT_TRUE(failed.is_object());
  EXPECT_EQ(failed["done"], 10);
  EXPECT_EQ(failed["failed"], nlohmann::json::array({1}));
  EXPECT_EQ(failed["tasks"][1]["missing"], nlohmann::json::array({5, 9}));
  EXPECT_EQ(failed["tasks"][1]["state"], "FAILED");
  EXPECT_EQ(failed["encode"]["state"], "CANCELLED") << "afterok with kill_invalid_depend: not left pending";
  EXPECT_FALSE(fs::exists(dir / "fly.gif"));
  const test::RunResult text = test::runSylva(dir, "farm status " + out);
  EXPECT_NE(text.out.find("failed task 1 (2 frames missing)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("frame 5: failed on purpose"), std::string::npos) << "the log's tail:\n"
                                                                            << text.out;
  EXPECT_NE(text.out.find("task 1, attempt 2 of 2"), std::string::npos) << "retried once:\n" << text.out;
  const auto firstFrame = fs::last_write_time(dir / "frames" / frameFile(1));

  const test::RunResult again = test::runSylva(dir, "farm resubmit " + out);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.out.find("2 frames missing in 1 task: 1"), std::string::npos) << again.out;
  EXPECT_EQ(waitFor(dir, out), 0);
  expectSameAsLocal(dir / "frames");
  EXPECT_TRUE(readAll(local->path() / "fly.gif") == readAll(dir / "fly.gif")) << "the GIFs differ";
  EXPECT_EQ(fs::last_write_time(dir / "frames" / frameFile(1)), firstFrame) << "a complete frame was redrawn";
  const nlohmann::json done = status(dir, out);
  EXPECT_EQ(done["done"], 12);
  EXPECT_EQ(done["encode"]["state"], "COMPLETED");
  EXPECT_EQ(test::runSylva(dir, "farm resubmit " + out).out, "nothing to resubmit: every frame is done\n");
}

TEST_F(FarmSlurm, ATaskKilledWithScancelResumes) {
  test::TempDir dir;
  const std::string out = test::at(dir, "frames");
  // Frames 0-5 in two tasks of three frames (the first six of the local run's twelve).
  const test::RunResult submitted = test::runSylva(
      dir, "farm submit " + kScene + " --frames 0-5 --tasks 2 --retries 0 --cpus-per-task 1 --out " + out);
  ASSERT_EQ(submitted.status, 0) << submitted.err;
  // Kill task 0 once it is running and has written a frame (it has three to draw).
  nlohmann::json st;
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    st = status(dir, out);
    ASSERT_TRUE(st.is_object());
    if (st["tasks"][0]["state"] == "RUNNING" && st["tasks"][0]["done"].get<int>() >= 1) {
      break;
    }
    ASSERT_NE(st["tasks"][0]["state"], "COMPLETED") << "task 0 finished before it could be killed";
    ASSERT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(60));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const std::string job = st["tasks"][0]["job"].get<std::string>();
  const test::RunResult killed = test::runProgram("scancel", dir.path(), job + "_0");
  ASSERT_EQ(killed.status, 0) << killed.err;
  EXPECT_EQ(waitFor(dir, out), 1);
  const nlohmann::json after = status(dir, out);
  EXPECT_EQ(after["tasks"][0]["state"], "CANCELLED");
  EXPECT_EQ(after["toResubmit"], nlohmann::json::array({0}));
  const test::RunResult again = test::runSylva(dir, "farm resubmit " + out);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(waitFor(dir, out), 0);
  expectSameAsLocal(dir / "frames", 5);
  for (const fs::directory_entry& e : fs::directory_iterator(dir / "frames")) {
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "a killed frame's temporary";
  }
}

TEST_F(FarmSlurm, BatchItemsReportTheFailedOneAndFinishAfterAResubmit) {
  test::TempDir dir;
  // `sylva scene check` over a list: the second scene is missing until it is written.
  std::ofstream(dir / "scenes.txt") << kMeadow << "\n" << (dir / "late.json").string() << "\n";
  const std::string out = test::at(dir, "checks");
  const test::RunResult submitted = test::runSylva(
      dir, "farm each " + test::at(dir, "scenes.txt") + " -o " + out +
               " --tasks 2 --retries 0 --cpus-per-task 1 -- " + quote(SYLVA_EXE) + " scene check {}");
  ASSERT_EQ(submitted.status, 0) << submitted.err;
  EXPECT_EQ(waitFor(dir, out), 1);
  const nlohmann::json failed = status(dir, out);
  EXPECT_EQ(failed["done"], 1);
  EXPECT_EQ(failed["failed"], nlohmann::json::array({1}));
  EXPECT_NE(test::runSylva(dir, "farm status " + out).out.find("late.json"), std::string::npos);
  // The meadow with its files named from the data folder, so it checks from the test's folder.
  std::string scene = readAll(kMeadow);
  for (std::size_t at; (at = scene.find("\"../")) != std::string::npos;) {
    scene.replace(at, 4, "\"" + std::string(SYLVA_SOURCE_DIR) + "/data/");
  }
  std::ofstream(dir / "late.json") << scene;
  ASSERT_EQ(test::runSylva(dir, "farm resubmit " + out).status, 0);
  EXPECT_EQ(waitFor(dir, out), 0);
  EXPECT_EQ(status(dir, out)["done"], 2);
}

TEST_F(FarmSlurm, APyramidBuiltAsAJobArrayEqualsOneLocalBuild) {
  test::TempDir dir;
  // docs/terrain-data.md: level 0 split over the array's tasks with --shard, the coarser levels by one last
  // run that keeps every tile the tasks wrote.
  ASSERT_EQ(test::runSylva(dir, "terrain heightmap --seed 5 --type ridged --size 600 -o " +
                                    test::at(dir, "dem.tif"))
                .status,
            0);
  const std::string dem = test::at(dir, "dem.tif");
  std::ofstream(dir / "shards.txt") << "0/3\n1/3\n2/3\n";
  const std::string out = test::at(dir, "farm");
  const test::RunResult submitted =
      test::runSylva(dir, "farm each " + test::at(dir, "shards.txt") + " -o " + out +
                              " --tasks 3 --cpus-per-task 1 -- " + quote(SYLVA_EXE) + " terrain pyramid " +
                              dem + " -o " + test::at(dir, "array") + " --tile-size 64 --shard {}");
  ASSERT_EQ(submitted.status, 0) << submitted.err;
  EXPECT_EQ(waitFor(dir, out), 0);
  const test::RunResult finish =
      test::runSylva(dir, "terrain pyramid " + dem + " -o " + test::at(dir, "array") + " --tile-size 64");
  ASSERT_EQ(finish.status, 0) << finish.err;
  EXPECT_NE(finish.out.find("100 kept"), std::string::npos) << finish.out; // 10 x 10 level-0 tiles
  const test::RunResult one =
      test::runSylva(dir, "terrain pyramid " + dem + " -o " + test::at(dir, "one") + " --tile-size 64");
  ASSERT_EQ(one.status, 0) << one.err;
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "one")) {
    if (entry.is_regular_file() && entry.path().extension() != ".json") {
      ++files;
      EXPECT_TRUE(readAll(entry.path()) == readAll(dir / "array" / fs::relative(entry.path(), dir / "one")))
          << entry.path();
    }
  }
  EXPECT_EQ(files, 100u + 25u + 9u + 4u + 1u + 5u); // tiles of levels 0..4 and their 5 indexes
}

} // namespace
} // namespace sylva
