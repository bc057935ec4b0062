#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

/**
 * The render farm (docs/farm.md): long frame sequences and batch jobs handed to Slurm as job arrays. Sylva
 * writes readable batch scripts and calls Slurm's own tools (`sbatch`, `scontrol`, `scancel`); it distributes
 * nothing itself. A farm is a folder: `OUT/farm/` holds `farm.json` (what was asked and every submission's
 * job ids), the job scripts, the task logs and, for batch jobs, one marker per finished item. Frames and
 * items are the truth for what is done: a task's state only explains what is not.
 *
 * CPU only: no GL. Planning, scripts and status are pure functions of their inputs (unit-tested); the Slurm
 * calls are in Slurm.hpp.
 */
namespace sylva::farm {

/** Slurm resources asked for each array task. */
struct Resources {
  std::string partition; ///< `--partition`; empty: the cluster's default
  int cpusPerTask = 2;   ///< `--cpus-per-task`
  int gpusPerTask = 0;   ///< `--gres=gpu:G` when > 0
  std::string time;      ///< `--time` (Slurm's forms: "30", "1:00:00", "1-0"); empty: the partition's limit
  int concurrent = 0;    ///< at most this many tasks at once (`--array=…%K`); 0: no cap
};

/** How work is cut into array tasks. */
struct Split {
  int tasks = 0;       ///< array tasks; 0: from `chunk`
  int chunk = 25;      ///< units (frames, items) per task when `tasks` is 0
  int retries = 2;     ///< attempts after the first before a task counts as failed
  int maxArray = 1001; ///< the site's MaxArraySize: more tasks is an error naming --chunk
};

/** `sylva farm submit SCENE …`: a scene file's frame range, rendered by shards. */
struct RenderRequest {
  std::string scene;   ///< the scene file
  std::string frames;  ///< "A-B[,C-D]"; empty: the file's output range
  std::string camera;  ///< empty: the file's output camera
  int width = 0;       ///< 0: the file's
  int height = 0;      ///< 0: the file's
  std::string out;     ///< the frames' folder; empty: out/<scene file's stem>
  std::string gif;     ///< encode job: an animated GIF here
  std::string mp4;     ///< encode job: an H.264 MP4 here
  Split split;         ///< how the frames become array tasks
  Resources resources; ///< what each task asks Slurm for
};

/** `sylva farm each LIST -o OUT -- COMMAND…`: one command per line of a list. */
struct EachRequest {
  std::string list; ///< text file: one item per line; blank lines and lines from '#' skipped
  std::string out;  ///< the farm's folder (its state, logs and done markers)
  std::vector<std::string>
      command;         ///< program and arguments with placeholders {} {stem} {name} {dir} {index}
  Split split;         ///< how the items become array tasks
  Resources resources; ///< what each task asks Slurm for
};

/** One `sbatch` of a farm's tasks (and its encode job). */
struct Submission {
  std::string arrayJob;   ///< the array's job id
  std::vector<int> tasks; ///< the array indices submitted
  std::string encodeJob;  ///< the dependent encode job's id; empty: none
};

/** A farm as submitted: the content of OUT/farm/farm.json. Paths are absolute. */
struct Farm {
  std::string kind;              ///< "render" or "each"
  std::string name;              ///< job name, "sylva-<scene or list name>"
  std::filesystem::path out;     ///< render: the frames' folder; each: the farm's folder
  std::filesystem::path workdir; ///< where tasks start (the submitting directory)
  std::filesystem::path sylva;   ///< the program the tasks run
  int tasks = 1;                 ///< array size (shards)
  int retries = 2;               ///< attempts after a task's first failure
  Resources resources;           ///< what each task asks Slurm for
  // render
  std::filesystem::path scene; ///< render: the scene file
  std::string frames;          ///< render: the range, as parsed ("0-11")
  std::string camera;          ///< render: the camera; empty: the file's output camera
  int width = 0;               ///< render: resolved output width, pixels
  int height = 0;              ///< render: resolved output height, pixels
  std::string gif;             ///< render: the GIF the encode job writes (absolute), or empty
  std::string mp4;             ///< render: the MP4 the encode job writes (absolute), or empty
  // each
  std::vector<std::string> items;      ///< the list's items, in order
  std::vector<std::string> commands;   ///< item k's shell command line
  std::vector<Submission> submissions; ///< every sbatch so far, first submission first

  /** OUT/farm: farm.json, the scripts, logs/ and done/. */
  std::filesystem::path dir() const { return out / "farm"; }
  /** The array task script. */
  std::filesystem::path taskScript() const { return dir() / "tasks.sbatch"; }
  /** The encode job's script (render farms with --gif or --mp4). */
  std::filesystem::path encodeScript() const { return dir() / "encode.sbatch"; }
  /** Units (frames or items) in all. */
  int unitCount() const;
  /** Task `task`'s units: frames (render) or item indices (each), unit k to task k mod tasks. */
  std::vector<int> unitsOf(int task) const;
  /**
   * Whether unit `unit` is done: its frame on disk as a PNG of the farm's size (read from its header; frames
   * are written whole, and `sylva render` decodes each fully before skipping it), or its item's done marker
   * (each).
   */
  bool unitDone(int unit) const;
  /** Where task `task` of array job `job` logs (Slurm's `%x-%A_%a.out`). */
  std::filesystem::path logOf(const std::string& job, int task) const;
  /** Whether the farm encodes a GIF or MP4 after its frames. */
  bool encodes() const { return !gif.empty() || !mp4.empty(); }
};

/**
 * Array tasks for `units` units: `split.tasks`, else ceil(units / chunk). Errors (sylva::Error, one line):
 * more tasks than units ("--tasks 20: only 12 frames, a task would have none"), more than maxArray tasks
 * (naming --chunk), values out of range.
 */
int taskCount(long long units, const Split& split, std::string_view unitName);

/**
 * Checks a render request and resolves it into a farm, before anything is submitted: the scene loads, the
 * camera exists, frames parse, the outputs can be written, the split fits. `sylva` is the program tasks run.
 * Writes nothing.
 */
Farm planRender(const RenderRequest& request, const std::filesystem::path& sylva);

/**
 * Checks a batch request and resolves it: the list reads and holds items, the command is given, every
 * placeholder is known ({} the item, {stem} its file name without extension, {name} its file name, {dir} its
 * folder, {index} its line's index among the items), the split fits. Items are substituted shell-quoted.
 */
Farm planEach(const EachRequest& request, const std::filesystem::path& sylva);

/** The array task script: `#SBATCH` lines for the resources, a retry loop round the unit work. */
std::string taskScriptText(const Farm& farm);

/** The encode job's script (afterok on the array; `sylva render … --gif/--mp4` over the complete frames). */
std::string encodeScriptText(const Farm& farm);

/** "0-3,5,7-8": sorted distinct indices as Slurm's --array list. */
std::string arrayList(std::vector<int> indices);

/** The indices of an --array list or of scontrol's ArrayTaskId ("0-3,5", "0-7%2", "1-9:2"). Errors start
 * "array list: ". */
std::vector<int> parseArrayList(std::string_view text);

/** farm.json as JSON text and back (version 1). Loading errors name the file and field. */
std::string manifestText(const Farm& farm);
/** The farm whose folder is `out` (reads out/farm/farm.json; errors name the file and field). */
Farm loadFarm(const std::filesystem::path& out);
/** farm.json's text (named `where` in errors) as a farm; what loadFarm reads. */
Farm parseFarm(std::string_view text, const std::string& where);
/** Writes the manifest atomically into farm.dir(). */
void saveFarm(const Farm& farm);

/** One array task (or one job) as Slurm knows it (`scontrol -o show job`). */
struct TaskState {
  std::string job;      ///< the array (or plain) job id
  int task = -1;        ///< array index; -1 for a plain job
  std::string state;    ///< JobState: PENDING, RUNNING, COMPLETED, FAILED, CANCELLED, TIMEOUT, …
  std::string reason;   ///< Reason (DependencyNeverSatisfied, NonZeroExitCode, …)
  std::string exitCode; ///< "1:0": exit status and signal
};

/**
 * Parses `scontrol -o show job` output: one line per job or array task; a line of pending tasks
 * ("ArrayTaskId=2-3") gives one entry each. Lines that are not job records are skipped.
 */
std::vector<TaskState> parseJobLines(std::string_view text);

/** Whether a Slurm job state is still to run or running (PENDING, RUNNING, CONFIGURING, COMPLETING, …). */
bool stateActive(std::string_view state);

/** A task's place in a farm's status. */
struct TaskStatus {
  int task = 0;              ///< array index
  int units = 0;             ///< its frames or items
  int done = 0;              ///< of those, done on disk
  std::vector<int> missing;  ///< the frames (render) or item indices (each) not done
  std::string job;           ///< the latest submission's array job holding it ("" never submitted)
  std::string state;         ///< Slurm's state of that task; "" when Slurm no longer knows it
  std::string reason;        ///< Slurm's reason for that state
  std::string exitCode;      ///< Slurm's "status:signal" of its last run
  std::filesystem::path log; ///< its log file (farm/logs/)
};

/** A farm's status: units done and missing, per task, the encode job. */
struct FarmStatus {
  int units = 0;                 ///< frames or items in all
  int done = 0;                  ///< of those, done on disk
  int inProgress = 0;            ///< missing units of tasks that are running
  std::vector<TaskStatus> tasks; ///< every array task, by index
  std::string encodeJob;         ///< the latest encode job's id; "" when none
  std::string encodeState;       ///< "" when none or unknown
  std::string encodeReason;      ///< Slurm's reason for that state
  bool encodeWritten = false;    ///< every --gif/--mp4 file exists
  /** Tasks with missing units and not pending or running: what `resubmit` submits. */
  std::vector<int> toResubmit() const;
  /** Tasks that ran and failed (or were cancelled, timed out, lost their node) with units missing. */
  std::vector<int> failed() const;
  /** No task pending or running and the encode job (if any) ended. */
  bool settled() const;
};

/** The status from the files on disk and `known` (parseJobLines of the farm's jobs). */
FarmStatus farmStatus(const Farm& farm, const std::vector<TaskState>& known);

/** The status as text for people: totals, one row per task, the failed tasks' log tails, what to do next. */
std::string statusText(const Farm& farm, const FarmStatus& status);

/** The status as JSON (machine-readable: `sylva farm status --json`). */
std::string statusJson(const Farm& farm, const FarmStatus& status);

/** The last `lines` lines of a text file; "" when it cannot be read. */
std::string tailOf(const std::filesystem::path& file, int lines);

/**
 * The filesystem holding `path` (its nearest existing parent): its type name ("nfs", "lustre", "ext4", …) and
 * whether it is one that several machines mount (network or cluster filesystems).
 */
struct FilesystemKind {
  std::string type;    ///< e.g. "nfs", "lustre", "ext4"; the magic number ("0x1234") for others
  bool shared = false; ///< a network or cluster filesystem (also assumed for unknown ones)
};
/** What filesystem holds `path` (statfs of its nearest existing parent). */
FilesystemKind filesystemOf(const std::filesystem::path& path);

} // namespace sylva::farm
