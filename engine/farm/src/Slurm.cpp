// The farm's calls to Slurm's client commands (docs/farm.md). Each is one program run; its message is passed
// on in the error when it fails.
#include <sylva/farm/Slurm.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Process.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace sylva::farm {

namespace {

/** The last non-empty line of a program's message, for one-line errors. */
std::string lastLine(const std::string& text) {
  std::string s = text;
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) {
    s.pop_back();
  }
  const std::size_t nl = s.find_last_of('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

/** Runs `sbatch --parsable ARGS`; the job id. */
std::string sbatch(const std::vector<std::string>& args) {
  std::vector<std::string> argv{"sbatch", "--parsable"};
  argv.insert(argv.end(), args.begin(), args.end());
  const ProgramResult r = runProgram(argv);
  // --parsable prints "JOBID" or "JOBID;CLUSTER".
  std::string id = lastLine(r.out);
  id = id.substr(0, id.find(';'));
  if (r.exitCode != 0 || id.empty() || !std::all_of(id.begin(), id.end(), ::isdigit)) {
    const std::string why = lastLine(r.err.empty() ? r.out : r.err);
    fail("sbatch failed (exit {}): {}", r.exitCode, why.empty() ? "no message" : why);
  }
  return id;
}

void writeScripts(const Farm& farm) {
  std::filesystem::create_directories(farm.dir() / "logs");
  writeTextFile(farm.taskScript(), taskScriptText(farm));
  std::filesystem::permissions(farm.taskScript(), std::filesystem::perms::owner_exec,
                               std::filesystem::perm_options::add);
  if (farm.kind == "each") {
    std::string lines;
    for (const std::string& c : farm.commands) {
      lines += c + "\n";
    }
    writeTextFile(farm.dir() / "commands.txt", lines);
  }
  if (farm.encodes()) {
    writeTextFile(farm.encodeScript(), encodeScriptText(farm));
    std::filesystem::permissions(farm.encodeScript(), std::filesystem::perms::owner_exec,
                                 std::filesystem::perm_options::add);
  }
}

std::string submitEncodeAfter(const Farm& farm, const std::string& after) {
  std::vector<std::string> args;
  if (!after.empty()) {
    args.push_back("--dependency=afterok:" + after);
    args.push_back("--kill-on-invalid-dep=yes");
  }
  args.push_back(farm.encodeScript().string());
  return sbatch(args);
}

} // namespace

void requireSlurm() {
  for (const char* program : {"sbatch", "scontrol", "scancel"}) {
    if (findOnPath(program).empty()) {
      fail(
          "{} not found on PATH: sylva farm needs Slurm's client commands (Debian: apt install slurm-client; "
          "on a cluster: the login node's module), or --dry-run to see the job scripts",
          program);
    }
  }
}

bool slurmAvailable() {
  return !findOnPath("sbatch").empty() && !findOnPath("scontrol").empty();
}

Submission submit(Farm& farm, const std::vector<int>& tasks, bool encode) {
  writeScripts(farm);
  Submission s;
  s.tasks = tasks;
  std::string array = arrayList(tasks);
  if (farm.resources.concurrent > 0) {
    array += fmt::format("%{}", farm.resources.concurrent);
  }
  s.arrayJob = sbatch({"--array=" + array, farm.taskScript().string()});
  if (encode && farm.encodes()) {
    try {
      s.encodeJob = submitEncodeAfter(farm, s.arrayJob);
    } catch (const Error&) {
      runProgram({"scancel", s.arrayJob});
      throw;
    }
  }
  farm.submissions.push_back(s);
  saveFarm(farm);
  return s;
}

Submission submitEncode(Farm& farm) {
  writeScripts(farm);
  Submission s;
  s.encodeJob = submitEncodeAfter(farm, "");
  // Recorded with the tasks of the latest submission, so their states stay where status looks for them.
  if (!farm.submissions.empty()) {
    s.arrayJob = farm.submissions.back().arrayJob;
    s.tasks = farm.submissions.back().tasks;
  }
  farm.submissions.push_back(s);
  saveFarm(farm);
  return s;
}

std::vector<TaskState> queryFarm(const Farm& farm) {
  std::vector<std::string> ids;
  for (const Submission& s : farm.submissions) {
    for (const std::string& id : {s.arrayJob, s.encodeJob}) {
      if (!id.empty() && std::find(ids.begin(), ids.end(), id) == ids.end()) {
        ids.push_back(id);
      }
    }
  }
  std::vector<TaskState> out;
  for (const std::string& id : ids) {
    // Exit 1 "Invalid job id specified": Slurm no longer holds the job.
    const ProgramResult r = runProgram({"scontrol", "-o", "show", "job", id});
    if (r.exitCode == 0) {
      const std::vector<TaskState> found = parseJobLines(r.out);
      out.insert(out.end(), found.begin(), found.end());
    }
  }
  return out;
}

std::vector<std::string> cancelFarm(const Farm& farm) {
  std::vector<std::string> active;
  for (const TaskState& t : queryFarm(farm)) {
    const std::string id = t.task >= 0 ? fmt::format("{}_{}", t.job, t.task) : t.job;
    if (stateActive(t.state) && std::find(active.begin(), active.end(), id) == active.end()) {
      active.push_back(id);
    }
  }
  if (active.empty()) {
    return {};
  }
  std::vector<std::string> argv{"scancel"};
  argv.insert(argv.end(), active.begin(), active.end());
  const ProgramResult r = runProgram(argv);
  if (r.exitCode != 0) {
    fail("scancel failed (exit {}): {}", r.exitCode, lastLine(r.err));
  }
  return active;
}

} // namespace sylva::farm
