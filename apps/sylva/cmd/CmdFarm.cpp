// `sylva farm submit|each|status|wait|resubmit|cancel`: frame sequences and batch jobs as Slurm job arrays
// (docs/farm.md). The options are parsed here; planning, scripts and status are the farm module's.
#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/farm/Farm.hpp>
#include <sylva/farm/Slurm.hpp>

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

namespace sylva::app {

namespace {

namespace fs = std::filesystem;

/** The program the tasks run: this one, by its absolute path (every node must see it there). */
fs::path thisProgram() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) {
    fail("cannot find this program's path (/proc/self/exe): {}", ec.message());
  }
  return self;
}

void addSplit(CLI::App& c, farm::Split& s, const char* unit) {
  c.add_option("--tasks", s.tasks, fmt::format("Array tasks (default: {} / --chunk)", unit))
      ->check(CLI::Range(1, 1000000));
  c.add_option("--chunk", s.chunk,
               fmt::format("{} per task when --tasks is not given (a 3,000-frame job is 120 tasks, not 3,000 "
                           "allocations)",
                           unit))
      ->capture_default_str();
  c.add_option("--retries", s.retries, "Attempts after the first before a task counts as failed")
      ->capture_default_str();
  c.add_option("--max-array", s.maxArray,
               "The site's largest job array (Slurm's MaxArraySize): more tasks is an error naming --chunk")
      ->capture_default_str();
}

void addResources(CLI::App& c, farm::Resources& r) {
  c.add_option("--partition,-p", r.partition, "Slurm partition (default: the cluster's)");
  c.add_option("--cpus-per-task", r.cpusPerTask, "CPU cores per task")->capture_default_str();
  c.add_option("--gpus-per-task", r.gpusPerTask, "GPUs per task (--gres=gpu:G); 0: none")
      ->capture_default_str();
  c.add_option("--time,-t", r.time, "Time limit per task in Slurm's form (30, 1:00:00, 1-0)");
  c.add_option("--concurrent", r.concurrent, "At most this many tasks at once (--array=…%K); 0: no cap")
      ->capture_default_str();
}

/** Warns when the farm's folder is on a filesystem only this machine sees. */
void warnIfLocal(const farm::Farm& farm) {
  const farm::FilesystemKind fsKind = farm::filesystemOf(farm.out);
  if (!fsKind.shared) {
    log::warn("{} is on a local filesystem ({}): every node that runs a task must see it at this path (NFS, "
              "Lustre, GPFS, BeeGFS, …); fine when the cluster is this machine",
              farm.out.string(), fsKind.type);
  }
}

/** A farm's folder holds one farm: a second submit would render its frames twice. */
void refuseExistingFarm(const farm::Farm& farm) {
  std::error_code ec;
  if (fs::exists(farm.dir() / "farm.json", ec)) {
    fail("{} already holds a farm: `sylva farm status` or `resubmit` it, or remove {} to start over",
         farm.out.string(), farm.dir().string());
  }
}

/** Submits `farm`'s tasks and prints what was submitted. */
void submitAndSay(farm::Farm& farm, const std::vector<int>& tasks) {
  const farm::Submission s = farm::submit(farm, tasks, true);
  std::printf("submitted %s: array job %s (%zu task%s)%s\n", farm.name.c_str(), s.arrayJob.c_str(),
              tasks.size(), tasks.size() == 1 ? "" : "s",
              s.encodeJob.empty() ? "" : fmt::format(", encode job {} after it", s.encodeJob).c_str());
  std::printf("job script: %s\n", farm.taskScript().string().c_str());
  std::printf("status: sylva farm status %s\n", farm.out.string().c_str());
}

/** Every array index of a farm: 0 … tasks − 1. */
std::vector<int> allTasks(const farm::Farm& farm) {
  std::vector<int> all;
  for (int t = 0; t < farm.tasks; ++t) {
    all.push_back(t);
  }
  return all;
}

/** Prints the scripts a submission would write (--dry-run). */
void printScripts(const farm::Farm& farm) {
  std::printf("# %s\n%s", farm.taskScript().string().c_str(), farm::taskScriptText(farm).c_str());
  if (farm.encodes()) {
    std::printf("\n# %s (sbatch --dependency=afterok:<array job> --kill-on-invalid-dep=yes)\n%s",
                farm.encodeScript().string().c_str(), farm::encodeScriptText(farm).c_str());
  }
  std::printf("\n# would submit: sbatch --array=%s %s\n", farm::arrayList(allTasks(farm)).c_str(),
              farm.taskScript().string().c_str());
}

/** `submit` and `each`: prints the scripts (--dry-run), or checks and submits every task of a new farm. */
void submitNew(farm::Farm farm, bool dryRun) {
  if (dryRun) {
    printScripts(farm);
    return;
  }
  farm::requireSlurm();
  refuseExistingFarm(farm);
  warnIfLocal(farm);
  submitAndSay(farm, allTasks(farm));
}

} // namespace

void registerFarm(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "farm", "Render frame sequences and run batch jobs on a Slurm cluster as job arrays (docs/farm.md)");
  cmd->require_subcommand(1);

  auto render = std::make_shared<farm::RenderRequest>();
  auto dryRun = std::make_shared<bool>(false);
  CLI::App* submit = cmd->add_subcommand(
      "submit", "Render a scene file's frames as a Slurm job array (sylva render --shard per task), then "
                "encode them in a job that runs when every task has succeeded");
  submit->add_option("scene", render->scene, "Scene file (data/scenes/*.json)")->required();
  submit->add_option("--frames", render->frames, "Frames A-B (or A-B,C-D); default: the file's output range");
  submit->add_option("--camera", render->camera, "Camera (default: the file's output camera)");
  submit->add_option("--width", render->width, "Width, pixels (default: the file's)")
      ->check(CLI::Range(1, 16384));
  submit->add_option("--height", render->height, "Height, pixels (default: the file's)")
      ->check(CLI::Range(1, 16384));
  submit->add_option(
      "--out,-o", render->out,
      "The frames' folder, shared by every node (default: out/<scene file name>, e.g. out/meadow)");
  submit->add_option("--gif", render->gif, "Encode job: an animated GIF of the range");
  submit->add_option("--mp4", render->mp4, "Encode job: an H.264 MP4 of the range (ffmpeg on the node)");
  addSplit(*submit, render->split, "frames");
  addResources(*submit, render->resources);
  submit->add_flag("--dry-run", *dryRun,
                   "Print the job scripts and the sbatch call; submit and write nothing");
  submit->footer(
      "Examples:\n"
      "  sylva farm submit data/scenes/jacksboro.json --frames 0-2999 --chunk 25 --mp4 out/fly.mp4\n"
      "  sylva farm submit data/scenes/meadow.json --frames 0-11 --tasks 4 --dry-run\n");
  submit->callback([render, dryRun] { submitNew(farm::planRender(*render, thisProgram()), *dryRun); });

  auto each = std::make_shared<farm::EachRequest>();
  CLI::App* eachCmd = cmd->add_subcommand(
      "each", "Run a command for every line of a list as a Slurm job array ({} the item, {stem} {name} {dir} "
              "{index}); an item is done when its command exits 0");
  eachCmd->add_option("list", each->list, "Text file: one item per line ('#' lines and blank lines skipped)")
      ->required();
  eachCmd->add_option("command", each->command, "The command, after --, with placeholders");
  eachCmd->add_option("--out,-o", each->out, "The farm's folder (state, logs, done markers)")->required();
  addSplit(*eachCmd, each->split, "items");
  addResources(*eachCmd, each->resources);
  eachCmd->add_flag("--dry-run", *dryRun,
                    "Print the job script and the sbatch call; submit and write nothing");
  eachCmd->footer(
      "Example:\n"
      "  sylva farm each projects.txt -o out/fold-farm -- sylva fold render {} --gif out/{stem}.gif\n");
  eachCmd->callback([each, dryRun] { submitNew(farm::planEach(*each, thisProgram()), *dryRun); });

  auto folder = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* status = cmd->add_subcommand(
      "status", "A farm's frames (or items) done, in progress and missing, each task's Slurm state, the "
                "failed tasks with their log tails");
  status->add_option("folder", *folder, "The farm's folder (submit's --out, each's -o)")->required();
  status->add_flag("--json", *json, "Machine-readable JSON instead of the table");
  status->callback([folder, json] {
    const farm::Farm farm = farm::loadFarm(*folder);
    const std::vector<farm::TaskState> known =
        farm::slurmAvailable() ? farm::queryFarm(farm) : std::vector<farm::TaskState>{};
    const farm::FarmStatus st = farm::farmStatus(farm, known);
    const std::string text = *json ? farm::statusJson(farm, st) : farm::statusText(farm, st);
    std::fputs(text.c_str(), stdout);
  });

  auto timeout = std::make_shared<double>(0.0);
  CLI::App* wait = cmd->add_subcommand(
      "wait", "Wait until no task of a farm is pending or running, with progress; exit 0 when every frame "
              "(or item) and the encode are done, 1 otherwise (then `status` says why)");
  wait->add_option("folder", *folder, "The farm's folder")->required();
  wait->add_option("--timeout", *timeout, "Give up after this many seconds (exit 1); 0: no limit")
      ->capture_default_str();
  wait->callback([folder, timeout] {
    farm::requireSlurm();
    const farm::Farm farm = farm::loadFarm(*folder);
    const auto start = std::chrono::steady_clock::now();
    farm::FarmStatus st = farm::farmStatus(farm, farm::queryFarm(farm));
    Progress progress(farm.name, static_cast<std::size_t>(st.units));
    progress.advance(static_cast<std::size_t>(st.done));
    int shown = st.done;
    while (!st.settled()) {
      if (progress.cancelled()) {
        fail("interrupted: the farm's jobs go on (sylva farm cancel {} stops them)", farm.out.string());
      }
      const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (*timeout > 0.0 && waited > *timeout) {
        std::fprintf(stderr, "sylva farm wait: still running after %.0f s\n", waited);
        exitCode() = 1;
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      st = farm::farmStatus(farm, farm::queryFarm(farm));
      if (st.done > shown) {
        progress.advance(static_cast<std::size_t>(st.done - shown));
        shown = st.done;
      }
    }
    const bool complete = st.done == st.units && (!farm.encodes() || st.encodeWritten);
    std::printf("%s: %d of %d %s done%s\n", farm.name.c_str(), st.done, st.units,
                farm.kind == "render" ? "frames" : "items",
                farm.encodes() ? (st.encodeWritten ? ", encoded" : ", not encoded") : "");
    exitCode() = complete ? 0 : 1;
  });

  CLI::App* resubmit = cmd->add_subcommand(
      "resubmit",
      "Submit again the tasks of a farm that have frames (or items) missing and are not pending or "
      "running, with a new encode job; or the encode job alone when only it is missing");
  resubmit->add_option("folder", *folder, "The farm's folder")->required();
  resubmit->add_flag("--dry-run", *dryRun, "Say what would be submitted; submit nothing");
  resubmit->callback([folder, dryRun] {
    farm::requireSlurm();
    farm::Farm farm = farm::loadFarm(*folder);
    const farm::FarmStatus st = farm::farmStatus(farm, farm::queryFarm(farm));
    const std::vector<int> tasks = st.toResubmit();
    if (tasks.empty()) {
      if (st.done < st.units) {
        std::printf("nothing to resubmit: every task with work missing is pending or running\n");
      } else if (farm.encodes() && !st.encodeWritten && !farm::stateActive(st.encodeState)) {
        if (*dryRun) {
          std::printf("every frame is done: would submit the encode job (%s)\n",
                      farm.encodeScript().string().c_str());
        } else {
          const farm::Submission s = farm::submitEncode(farm);
          std::printf("every frame is done: submitted the encode job %s\n", s.encodeJob.c_str());
        }
      } else {
        std::printf("nothing to resubmit: every %s is done\n", farm.kind == "render" ? "frame" : "item");
      }
      return;
    }
    int units = 0;
    for (int t : tasks) {
      units += static_cast<int>(st.tasks[static_cast<std::size_t>(t)].missing.size());
    }
    std::printf("%d %s missing in %zu task%s: %s\n", units, farm.kind == "render" ? "frames" : "items",
                tasks.size(), tasks.size() == 1 ? "" : "s", farm::arrayList(tasks).c_str());
    if (!*dryRun) {
      submitAndSay(farm, tasks);
    }
  });

  CLI::App* cancel = cmd->add_subcommand("cancel", "Cancel every pending or running job of a farm (scancel)");
  cancel->add_option("folder", *folder, "The farm's folder")->required();
  cancel->callback([folder] {
    farm::requireSlurm();
    const farm::Farm farm = farm::loadFarm(*folder);
    const std::vector<std::string> ids = farm::cancelFarm(farm);
    std::printf("cancelled %zu job%s%s\n", ids.size(), ids.size() == 1 ? "" : "s",
                ids.empty() ? " (none was pending or running)" : "");
  });
}

} // namespace sylva::app
