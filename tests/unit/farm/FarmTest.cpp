// The render farm's decisions without a cluster (docs/farm.md): the split into array tasks, the scripts (run
// for real with a stand-in program, so the retry loop and the done markers are exercised), the manifest, the
// status from frames on disk and recorded `scontrol` lines. The real Slurm runs in
// tests/cli/FarmSlurmTests.cpp.
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Process.hpp>
#include <sylva/farm/Farm.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace sylva::farm {
namespace {

namespace fs = std::filesystem;

const std::string kMeadow = std::string(SYLVA_SOURCE_DIR) + "/data/scenes/meadow.json";

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

void writeExecutable(const fs::path& path, const std::string& text) {
  writeTextFile(path, text);
  fs::permissions(path, fs::perms::owner_all);
}

/** A render farm of frames 0-11 of the meadow at 8×6 in 4 tasks, in `dir`. */
Farm meadowFarm(const test::TempDir& dir, const fs::path& program = "/usr/bin/sylva") {
  RenderRequest r;
  r.scene = kMeadow;
  r.frames = "0-11";
  r.camera = "flyover";
  r.width = 8;
  r.height = 6;
  r.out = (dir / "frames").string();
  r.gif = (dir / "fly.gif").string();
  r.split.tasks = 4;
  return planRender(r, program);
}

TEST(Farm, TasksComeFromTheChunkAndStayWithinTheArrayLimit) {
  Split s;
  s.chunk = 25;
  EXPECT_EQ(taskCount(3000, s, "frames"), 120);
  EXPECT_EQ(taskCount(3001, s, "frames"), 121);
  s.tasks = 4;
  EXPECT_EQ(taskCount(12, s, "frames"), 4);
  s.tasks = 20;
  EXPECT_NE(errorOf([&] { taskCount(12, s, "frames"); }).find("--tasks 20: only 12 frames"),
            std::string::npos);
  s.tasks = 0;
  s.chunk = 1;
  const std::string tooMany = errorOf([&] { taskCount(3000, s, "frames"); });
  EXPECT_NE(tooMany.find("array limit of 1001"), std::string::npos) << tooMany;
  EXPECT_NE(tooMany.find("--chunk 3"), std::string::npos) << tooMany;
  s.chunk = 0;
  EXPECT_NE(errorOf([&] { taskCount(10, s, "frames"); }).find("--chunk 0"), std::string::npos);
  s.chunk = 5;
  s.retries = -1;
  EXPECT_NE(errorOf([&] { taskCount(10, s, "frames"); }).find("--retries"), std::string::npos);
}

TEST(Farm, ArrayListsRoundTripAndReadScontrolsForms) {
  EXPECT_EQ(arrayList({5, 0, 1, 2, 3, 7, 8, 3}), "0-3,5,7-8");
  EXPECT_EQ(arrayList({1}), "1");
  EXPECT_EQ(parseArrayList("0-3,5,7-8"), (std::vector<int>{0, 1, 2, 3, 5, 7, 8}));
  EXPECT_EQ(parseArrayList("0-3%2"), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(parseArrayList("1-9:4"), (std::vector<int>{1, 5, 9}));
  for (const char* bad : {"", "a", "3-1", "1,,2", "-1", "1-"}) {
    EXPECT_NE(errorOf([&] { parseArrayList(bad); }).find("array list"), std::string::npos) << bad;
  }
}

TEST(Farm, JobLinesGiveOneStatePerTaskAndPendingRangesExpand) {
  // Shortened `scontrol -o show job 12` output of Slurm 22.05 (one line per record).
  const std::string text =
      "JobId=13 ArrayJobId=12 ArrayTaskId=0 JobName=sylva-meadow JobState=COMPLETED Reason=None "
      "Dependency=(null) ExitCode=0:0 StdOut=/o/farm/logs/sylva-meadow-12_0.out\n"
      "JobId=14 ArrayJobId=12 ArrayTaskId=1 JobName=sylva-meadow JobState=FAILED Reason=NonZeroExitCode "
      "ExitCode=1:0\n"
      "JobId=12 ArrayJobId=12 ArrayTaskId=2-3%2 JobName=sylva-meadow JobState=PENDING "
      "Reason=JobArrayTaskLimit "
      "ExitCode=0:0\n"
      "JobId=16 JobName=sylva-meadow-encode JobState=CANCELLED Reason=DependencyNeverSatisfied ExitCode=0:0\n"
      "slurm_load_jobs error: Invalid job id specified\n";
  const std::vector<TaskState> states = parseJobLines(text);
  ASSERT_EQ(states.size(), 5u);
  EXPECT_EQ(states[0].job, "12");
  EXPECT_EQ(states[0].task, 0);
  EXPECT_EQ(states[0].state, "COMPLETED");
  EXPECT_EQ(states[1].state, "FAILED");
  EXPECT_EQ(states[1].exitCode, "1:0");
  EXPECT_EQ(states[2].task, 2);
  EXPECT_EQ(states[3].task, 3);
  EXPECT_EQ(states[3].state, "PENDING");
  EXPECT_EQ(states[4].job, "16");
  EXPECT_EQ(states[4].task, -1);
  EXPECT_EQ(states[4].reason, "DependencyNeverSatisfied");
  EXPECT_TRUE(stateActive("PENDING"));
  EXPECT_TRUE(stateActive("RUNNING"));
  EXPECT_FALSE(stateActive("FAILED"));
  EXPECT_FALSE(stateActive(""));
}

TEST(Farm, RenderPlansAreCheckedBeforeAnythingIsSubmitted) {
  test::TempDir dir;
  const Farm farm = meadowFarm(dir);
  EXPECT_EQ(farm.kind, "render");
  EXPECT_EQ(farm.name, "sylva-meadow");
  EXPECT_EQ(farm.tasks, 4);
  EXPECT_EQ(farm.unitCount(), 12);
  EXPECT_EQ(farm.unitsOf(1), (std::vector<int>{1, 5, 9}));
  EXPECT_TRUE(farm.out.is_absolute());
  EXPECT_TRUE(farm.scene.is_absolute());
  EXPECT_FALSE(fs::exists(farm.out)) << "planning writes nothing";

  RenderRequest r;
  r.scene = kMeadow;
  r.frames = "0-11";
  r.camera = "nowhere";
  EXPECT_NE(errorOf([&] { planRender(r, "/x"); }).find("--camera nowhere"), std::string::npos);
  r.camera.clear();
  r.frames = "9-2";
  EXPECT_NE(errorOf([&] { planRender(r, "/x"); }).find("--frames"), std::string::npos);
  r.frames = "0-11";
  r.split.tasks = 13;
  EXPECT_NE(errorOf([&] { planRender(r, "/x"); }).find("only 12 frames"), std::string::npos);
  r.split.tasks = 2;
  r.gif = (dir / "a.mp4").string();
  EXPECT_NE(errorOf([&] { planRender(r, "/x"); }).find("--gif"), std::string::npos);
  r.gif.clear();
  r.resources.partition = "gpu; rm -rf";
  EXPECT_NE(errorOf([&] { planRender(r, "/x"); }).find("--partition"), std::string::npos);
  r.resources.partition.clear();
  r.out = (dir / "with space").string();
  EXPECT_NE(errorOf([&] { planRender(r, "/x"); }).find("cannot hold a path with spaces"), std::string::npos);
  r.out.clear();
  r.scene = (dir / "missing.json").string();
  EXPECT_NE(errorOf([&] { planRender(r, "/x"); }).find("missing.json"), std::string::npos);
}

TEST(Farm, RenderTasksRetryAndResumeTheirShard) {
  test::TempDir dir;
  // A stand-in for sylva: records its arguments, fails the first attempt of each task.
  const fs::path program = dir / "fake-sylva";
  writeExecutable(program, "#!/bin/bash\necho \"$*\" >> " + shellQuote((dir / "calls").string()) +
                               "\nif [ ! -e " + shellQuote((dir / "again").string()) + " ]; then touch " +
                               shellQuote((dir / "again").string()) + "; exit 3; fi\nexit 0\n");
  Farm farm = meadowFarm(dir, program);
  farm.resources.partition = "render";
  farm.resources.gpusPerTask = 1;
  farm.resources.time = "1:00:00";
  farm.resources.concurrent = 2;
  const std::string script = taskScriptText(farm);
  for (const char* line : {"#SBATCH --job-name=sylva-meadow", "#SBATCH --array=0-3%2",
                           "#SBATCH --partition=render", "#SBATCH --gres=gpu:1", "#SBATCH --time=1:00:00",
                           "#SBATCH --cpus-per-task=2", "attempts=3", "--shard \"$task/4\""}) {
    EXPECT_NE(script.find(line), std::string::npos) << line << " in\n" << script;
  }
  EXPECT_NE(script.find("#SBATCH --output=" + (farm.dir() / "logs").string() + "/%x-%A_%a.out"),
            std::string::npos);
  EXPECT_NE(script.find("cd " + shellQuote(fs::current_path().string()) + " || exit 1"), std::string::npos);
  writeExecutable(dir / "task.sh", script);
  const ProgramResult ok = runProgram({"env", "SLURM_ARRAY_TASK_ID=1", (dir / "task.sh").string()});
  EXPECT_EQ(ok.exitCode, 0) << ok.err;
  EXPECT_NE(ok.err.find("task 1, attempt 2 of 3"), std::string::npos) << ok.err;
  const std::string calls = readTextFile(dir / "calls");
  EXPECT_NE(calls.find("render " + farm.scene.string() + " --frames 0-11 --out " + farm.out.string() +
                       " --shard 1/4 --camera flyover --width 8 --height 6"),
            std::string::npos)
      << calls;
  EXPECT_EQ(calls.find("--gif"), std::string::npos) << "tasks never encode";

  // Every attempt failing: the task fails after 1 + retries attempts.
  writeExecutable(program, "#!/bin/bash\nexit 3\n");
  const ProgramResult bad = runProgram({"env", "SLURM_ARRAY_TASK_ID=0", (dir / "task.sh").string()});
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("task 0 failed 3 times"), std::string::npos) << bad.err;
  const ProgramResult notArray = runProgram({"env", "-u", "SLURM_ARRAY_TASK_ID", (dir / "task.sh").string()});
  EXPECT_NE(notArray.exitCode, 0);
  EXPECT_NE(notArray.err.find("run this script as a Slurm array task"), std::string::npos) << notArray.err;

  const std::string encode = encodeScriptText(farm);
  EXPECT_NE(encode.find("#SBATCH --job-name=sylva-meadow-encode"), std::string::npos) << encode;
  EXPECT_NE(encode.find("--gif " + shellQuote((dir / "fly.gif").string())), std::string::npos) << encode;
  EXPECT_EQ(encode.find("--shard"), std::string::npos) << encode;
  EXPECT_EQ(encode.find("--gres"), std::string::npos) << "encoding needs no GPU";
}

TEST(Farm, BatchItemsAreSubstitutedQuotedAndMarkedDone) {
  test::TempDir dir;
  writeTextFile(dir / "list.txt", "# projects\nin/a b.json\n\n  in/c.json  \nx'y.json\n");
  EachRequest r;
  r.list = (dir / "list.txt").string();
  r.out = (dir / "farm").string();
  // Placeholders as arguments of their own (substituted quoted), not inside the shell snippet.
  r.command = {
      "sh",     "-c",      "case \"$2\" in c) exit 5;; esac; echo \"$1:$3:$4\" >> " + (dir / "ran").string(),
      "sh",     "{index}", "{stem}",
      "{name}", "{dir}",   "{}"};
  r.split.tasks = 2;
  r.split.retries = 1;
  Farm farm = planEach(r, "/usr/bin/sylva");
  ASSERT_EQ(farm.items, (std::vector<std::string>{"in/a b.json", "in/c.json", "x'y.json"}));
  EXPECT_EQ(farm.name, "sylva-list");
  EXPECT_EQ(farm.unitsOf(0), (std::vector<int>{0, 2}));
  EXPECT_NE(farm.commands[0].find(" 'in/a b.json'"), std::string::npos) << farm.commands[0];
  EXPECT_NE(farm.commands[0].find(" '0' 'a b' 'a b.json' 'in' "), std::string::npos) << farm.commands[0];
  EXPECT_NE(farm.commands[2].find(" 'x'\\''y.json'"), std::string::npos) << farm.commands[2];

  fs::create_directories(farm.dir());
  std::string lines;
  for (const std::string& c : farm.commands) {
    lines += c + "\n";
  }
  writeTextFile(farm.dir() / "commands.txt", lines);
  writeExecutable(dir / "task.sh", taskScriptText(farm));
  const ProgramResult t0 = runProgram({"env", "SLURM_ARRAY_TASK_ID=0", (dir / "task.sh").string()});
  EXPECT_EQ(t0.exitCode, 0) << t0.err;
  const ProgramResult t1 = runProgram({"env", "SLURM_ARRAY_TASK_ID=1", (dir / "task.sh").string()});
  EXPECT_EQ(t1.exitCode, 1) << "item 1 exits 5 every time";
  EXPECT_NE(t1.err.find("item 1 failed 2 times"), std::string::npos) << t1.err;
  EXPECT_EQ(readTextFile(dir / "ran"), "0:a b.json:in\n2:x'y.json:.\n");
  EXPECT_TRUE(farm.unitDone(0));
  EXPECT_FALSE(farm.unitDone(1));
  EXPECT_TRUE(farm.unitDone(2));
  // A second run of task 0 skips its done items.
  fs::remove(dir / "ran");
  EXPECT_EQ(runProgram({"env", "SLURM_ARRAY_TASK_ID=0", (dir / "task.sh").string()}).exitCode, 0);
  EXPECT_FALSE(fs::exists(dir / "ran"));

  r.command = {"echo", "{stm}"};
  EXPECT_NE(errorOf([&] { planEach(r, "/x"); }).find("unknown placeholder {stm}"), std::string::npos);
  r.command.clear();
  EXPECT_NE(errorOf([&] { planEach(r, "/x"); }).find("no command"), std::string::npos);
  writeTextFile(dir / "empty.txt", "# nothing\n\n");
  r.list = (dir / "empty.txt").string();
  r.command = {"true"};
  EXPECT_NE(errorOf([&] { planEach(r, "/x"); }).find("empty.txt: no items"), std::string::npos);
}

TEST(Farm, ManifestsRoundTripAndBadOnesNameTheField) {
  test::TempDir dir;
  Farm farm = meadowFarm(dir);
  farm.submissions.push_back({"12", {0, 1, 2, 3}, "13"});
  farm.submissions.push_back({"20", {1}, "21"});
  saveFarm(farm);
  const Farm back = loadFarm(farm.out);
  EXPECT_EQ(manifestText(back), manifestText(farm));
  EXPECT_EQ(back.submissions[1].tasks, std::vector<int>{1});

  std::string text = readTextFile(farm.dir() / "farm.json");
  const std::string old = "\"tasks\": 4";
  ASSERT_NE(text.find(old), std::string::npos);
  writeTextFile(farm.dir() / "farm.json", text.replace(text.find(old), old.size(), "\"tasks\": 40"));
  EXPECT_NE(errorOf([&] { loadFarm(farm.out); }).find("farm.json: /tasks: 40 tasks for 12 units"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { loadFarm(dir / "nothing"); }).find("not a farm"), std::string::npos);
}

TEST(Farm, StatusComesFromFramesOnDiskAndSlurmsStates) {
  test::TempDir dir;
  Farm farm = meadowFarm(dir);
  farm.submissions.push_back({"12", {0, 1, 2, 3}, "13"});
  fs::create_directories(farm.out);
  const Image frame(8, 6, 4, PixelType::U8);
  for (int f : {0, 4, 8, 1, 3, 7}) { // task 0 whole, task 1 only frame 1, task 3 two of three, task 2 none
    saveImage(farm.out / ("frame_0000" + std::to_string(f) + ".png"), frame);
  }
  savePng(farm.out / "frame_00011.png", Image(9, 6, 4, PixelType::U8)); // the wrong size is not done
  fs::create_directories(farm.dir() / "logs");
  writeTextFile(farm.logOf("12", 1),
                "render meadow  1/3\rrender meadow  2/3\nsylva: error: frame 5: failed\n");
  const std::vector<TaskState> known = parseJobLines(
      "JobId=13 ArrayJobId=12 ArrayTaskId=0 JobState=COMPLETED Reason=None ExitCode=0:0\n"
      "JobId=14 ArrayJobId=12 ArrayTaskId=1 JobState=FAILED Reason=NonZeroExitCode ExitCode=1:0\n"
      "JobId=15 ArrayJobId=12 ArrayTaskId=2 JobState=RUNNING Reason=None ExitCode=0:0\n"
      "JobId=16 ArrayJobId=12 ArrayTaskId=3 JobState=CANCELLED Reason=None ExitCode=0:15\n"
      "JobId=13 JobState=CANCELLED Reason=DependencyNeverSatisfied ExitCode=0:0\n");
  const FarmStatus st = farmStatus(farm, known);
  EXPECT_EQ(st.units, 12);
  EXPECT_EQ(st.done, 6);
  EXPECT_EQ(st.inProgress, 3);
  EXPECT_EQ(st.tasks[1].missing, (std::vector<int>{5, 9}));
  EXPECT_EQ(st.tasks[3].missing, (std::vector<int>{11}));
  EXPECT_EQ(st.failed(), (std::vector<int>{1, 3}));
  EXPECT_EQ(st.toResubmit(), (std::vector<int>{1, 3})) << "task 2 is still running";
  EXPECT_FALSE(st.settled());
  EXPECT_EQ(st.encodeState, "CANCELLED");
  EXPECT_FALSE(st.encodeWritten);
  const std::string text = statusText(farm, st);
  for (const char* part :
       {"frames: 6 of 12 done, 3 in progress, 3 missing", "FAILED 1:0", "12_1", "5, 9",
        "encode job 13: CANCELLED (DependencyNeverSatisfied)", "failed task 1 (2 frames missing)",
        "  | render meadow  2/3", "  | sylva: error: frame 5: failed", "sylva farm resubmit"}) {
    EXPECT_NE(text.find(part), std::string::npos) << part << " in\n" << text;
  }
  const nlohmann::json json = nlohmann::json::parse(statusJson(farm, st));
  EXPECT_EQ(json["done"], 6);
  EXPECT_EQ(json["failed"], nlohmann::json::array({1, 3}));

  // Slurm has forgotten the jobs (past MinJobAge): the frames still say what is missing.
  const FarmStatus forgotten = farmStatus(farm, {});
  EXPECT_TRUE(forgotten.settled());
  EXPECT_EQ(forgotten.toResubmit(), (std::vector<int>{1, 2, 3}));
  EXPECT_NE(statusText(farm, forgotten).find("ended"), std::string::npos);
}

TEST(Farm, FilesystemsAreNamed) {
  const FilesystemKind proc = filesystemOf("/proc/self");
  EXPECT_FALSE(proc.type.empty());
  test::TempDir dir;
  const FilesystemKind tmp = filesystemOf(dir / "not" / "yet");
  EXPECT_FALSE(tmp.type.empty()) << "a path still to be made is judged by its nearest existing parent";
  EXPECT_FALSE(filesystemOf("/dev/shm").shared) << filesystemOf("/dev/shm").type;
}

} // namespace
} // namespace sylva::farm
