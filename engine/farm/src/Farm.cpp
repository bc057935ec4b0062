// The render farm's decisions (docs/farm.md): how a job is split into array tasks, the scripts Slurm runs,
// the manifest a farm folder keeps, and its status from the files on disk and Slurm's records. No Slurm calls
// here.
#include <sylva/farm/Farm.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/ImageHeader.hpp>
#include <sylva/core/JsonNode.hpp>
#include <sylva/core/Process.hpp>
#include <sylva/scene/Sequence.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <sys/vfs.h>

namespace sylva::farm {

namespace fs = std::filesystem;

namespace {

/** The scheduler states of a task that ended without finishing its work. */
bool stateEndedBadly(std::string_view s) {
  return s == "FAILED" || s == "CANCELLED" || s == "TIMEOUT" || s == "NODE_FAIL" || s == "OUT_OF_MEMORY" ||
         s == "BOOT_FAIL" || s == "DEADLINE" || s == "PREEMPTED";
}

void checkResources(const Resources& r) {
  if (r.cpusPerTask < 1 || r.cpusPerTask > 1024) {
    fail("--cpus-per-task {}: expected 1 to 1024", r.cpusPerTask);
  }
  if (r.gpusPerTask < 0 || r.gpusPerTask > 64) {
    fail("--gpus-per-task {}: expected 0 to 64", r.gpusPerTask);
  }
  if (r.concurrent < 0) {
    fail("--concurrent {}: expected 0 (no cap) or more", r.concurrent);
  }
  // Values go into #SBATCH lines: nothing that could end the line or the option.
  for (const auto& [option, value] : {std::pair{"--partition", &r.partition}, std::pair{"--time", &r.time}}) {
    if (value->find_first_of(" \t\r\n'\"\\$`;") != std::string::npos) {
      fail("{} '{}': expected a name without spaces or shell characters", option, *value);
    }
  }
}

/** "sylva-<stem>": a job name of letters, digits, '.', '_' and '-' only (it goes into #SBATCH lines and log
 * file names). */
std::string jobName(const fs::path& file) {
  std::string name = fmt::format("sylva-{}", file.stem().string());
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') {
      c = '-';
    }
  }
  return name;
}

/** Absolute and normal, not resolving links (so the path the user sees is the one in the scripts). */
fs::path absoluteOf(const fs::path& p) {
  return fs::absolute(p).lexically_normal();
}

/**
 * Checks a folder that goes into #SBATCH lines (the logs' --output): Slurm splits those lines at spaces and
 * reads '%' as a file name pattern.
 */
void checkSbatchPath(const fs::path& p, std::string_view option) {
  if (p.string().find_first_of(" \t\r\n'\"\\%") != std::string::npos) {
    fail("{} {}: Slurm's #SBATCH lines cannot hold a path with spaces, quotes, backslashes or '%': choose "
         "another folder",
         option, p.string());
  }
}

/** The #SBATCH lines every script of a farm shares (name, resources). */
std::string commonDirectives(const Farm& farm, const std::string& name, bool gpus) {
  std::string s;
  s += fmt::format("#SBATCH --job-name={}\n", name);
  s += fmt::format("#SBATCH --cpus-per-task={}\n", farm.resources.cpusPerTask);
  if (!farm.resources.partition.empty()) {
    s += fmt::format("#SBATCH --partition={}\n", farm.resources.partition);
  }
  if (gpus && farm.resources.gpusPerTask > 0) {
    s += fmt::format("#SBATCH --gres=gpu:{}\n", farm.resources.gpusPerTask);
  }
  if (!farm.resources.time.empty()) {
    s += fmt::format("#SBATCH --time={}\n", farm.resources.time);
  }
  return s;
}

/** The render command of a farm's frames (one shard's with `shard`, else the whole range's encode). */
std::string renderCommand(const Farm& farm, const std::string& shard, bool encode) {
  std::string s = fmt::format("{} render {} --frames {} --out {}", shellQuote(farm.sylva.string()),
                              shellQuote(farm.scene.string()), farm.frames, shellQuote(farm.out.string()));
  if (!shard.empty()) {
    s += " --shard " + shard;
  }
  s += " --camera " + shellQuote(farm.camera);
  s += fmt::format(" --width {} --height {}", farm.width, farm.height);
  if (encode && !farm.gif.empty()) {
    s += " --gif " + shellQuote(farm.gif);
  }
  if (encode && !farm.mp4.empty()) {
    s += " --mp4 " + shellQuote(farm.mp4);
  }
  return s;
}

/** Replaces the placeholders of one argument for item `item` (index `index`); unknown ones are errors. */
std::string substitute(const std::string& arg, const std::string& item, int index) {
  const fs::path p(item);
  std::string out;
  for (std::size_t i = 0; i < arg.size();) {
    if (arg[i] != '{') {
      out += arg[i++];
      continue;
    }
    const std::size_t close = arg.find('}', i);
    if (close == std::string::npos) {
      fail(
          "command argument '{}': '{{' without '}}' (placeholders: {{}} {{stem}} {{name}} {{dir}} {{index}})",
          arg);
    }
    const std::string key = arg.substr(i + 1, close - i - 1);
    if (key.empty()) {
      out += item;
    } else if (key == "stem") {
      out += p.stem().string();
    } else if (key == "name") {
      out += p.filename().string();
    } else if (key == "dir") {
      out += p.parent_path().empty() ? std::string(".") : p.parent_path().string();
    } else if (key == "index") {
      out += std::to_string(index);
    } else {
      fail("command argument '{}': unknown placeholder {{{}}} (known: {{}} {{stem}} {{name}} {{dir}} "
           "{{index}})",
           arg, key);
    }
    i = close + 1;
  }
  return out;
}

int parseIndex(std::string_view text, std::string_view whole) {
  int v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < 0 || text.empty()) {
    fail("array list: '{}' is not an index list ('{}')", text, whole);
  }
  return v;
}

/** The value of `Key=` in one scontrol record line ("" when absent). */
std::string field(std::string_view line, std::string_view key) {
  const std::string needle = std::string(key) + "=";
  std::size_t at = 0;
  while ((at = line.find(needle, at)) != std::string_view::npos) {
    if (at == 0 || line[at - 1] == ' ') {
      const std::size_t start = at + needle.size();
      const std::size_t end = line.find(' ', start);
      return std::string(
          line.substr(start, end == std::string_view::npos ? line.size() - start : end - start));
    }
    at += needle.size();
  }
  return {};
}

} // namespace

int taskCount(long long units, const Split& split, std::string_view unitName) {
  if (units < 1) {
    fail("nothing to do: no {}", unitName);
  }
  if (split.retries < 0 || split.retries > 100) {
    fail("--retries {}: expected 0 to 100", split.retries);
  }
  if (split.maxArray < 1) {
    fail("--max-array {}: expected 1 or more", split.maxArray);
  }
  long long tasks = split.tasks;
  if (tasks < 0) {
    fail("--tasks {}: expected 1 or more", tasks);
  }
  if (tasks == 0) {
    if (split.chunk < 1) {
      fail("--chunk {}: expected 1 or more {} per task", split.chunk, unitName);
    }
    tasks = (units + split.chunk - 1) / split.chunk;
  } else if (tasks > units) {
    fail("--tasks {}: only {} {}, so a task would have none (give at most {} tasks)", tasks, units, unitName,
         units);
  }
  if (tasks > split.maxArray) {
    fail("{} {} in {} tasks: more than the array limit of {} (--max-array; sites cap arrays, often at 1001): "
         "give more {} per task with --chunk {}",
         units, unitName, tasks, split.maxArray, unitName, (units + split.maxArray - 1) / split.maxArray);
  }
  return static_cast<int>(tasks);
}

int Farm::unitCount() const {
  return kind == "render" ? static_cast<int>(scene::parseFrames(frames).count())
                          : static_cast<int>(items.size());
}

std::vector<int> Farm::unitsOf(int task) const {
  if (kind == "render") {
    return scene::framesOf(scene::parseFrames(frames), scene::Shard{task, tasks});
  }
  std::vector<int> out;
  for (int i = task; i < static_cast<int>(items.size()); i += tasks) {
    out.push_back(i);
  }
  return out;
}

bool Farm::unitDone(int unit) const {
  if (kind == "render") {
    // The header only: status and wait look at thousands of frames twice a second, and frames are written
    // whole (a temporary renamed). The renderer itself decodes each frame fully before it skips it.
    const fs::path frame = out / scene::frameName(unit);
    std::error_code ec;
    if (!fs::is_regular_file(frame, ec)) {
      return false;
    }
    try {
      const std::optional<ImageHeader> header = readImageHeader(frame);
      return header && header->format == "PNG" && header->width == width && header->height == height;
    } catch (const Error&) {
      return false; // unreadable: not done
    }
  }
  std::error_code ec;
  return fs::exists(dir() / "done" / std::to_string(unit), ec);
}

fs::path Farm::logOf(const std::string& job, int task) const {
  return dir() / "logs" / fmt::format("{}-{}_{}.out", name, job, task);
}

Farm planRender(const RenderRequest& r, const fs::path& sylva) {
  checkResources(r.resources);
  Farm farm;
  farm.kind = "render";
  const scene::SceneDesc desc = scene::loadScene(r.scene);
  farm.scene = absoluteOf(r.scene);
  farm.width = r.width > 0 ? r.width : desc.output.width;
  farm.height = r.height > 0 ? r.height : desc.output.height;
  farm.camera = r.camera.empty() ? desc.output.camera : r.camera;
  if (!desc.cameras.contains(farm.camera)) {
    fail("--camera {}: {} has no such camera", farm.camera, r.scene);
  }
  const scene::FrameRange range =
      r.frames.empty()
          ? scene::parseFrames(fmt::format("{}-{}", desc.output.firstFrame, desc.output.lastFrame))
          : scene::parseFrames(r.frames);
  std::string frames;
  for (const auto& [a, b] : range.spans) {
    frames += fmt::format("{}{}-{}", frames.empty() ? "" : ",", a, b);
  }
  farm.frames = frames;
  farm.tasks = taskCount(range.count(), r.split, "frames");
  farm.retries = r.split.retries;
  farm.resources = r.resources;
  farm.name = jobName(r.scene);
  farm.out = absoluteOf(r.out.empty() ? fs::path("out") / fs::path(r.scene).stem() : fs::path(r.out));
  checkSbatchPath(farm.out, "--out");
  std::error_code ec;
  if (fs::exists(farm.out, ec) && !fs::is_directory(farm.out, ec)) {
    fail("--out {}: the frames need a directory, and this is a file", r.out);
  }
  if (!r.gif.empty()) {
    requireExtension("--gif", r.gif, ".gif");
    checkOutputFile(r.gif, "--gif", "anim.gif");
    farm.gif = absoluteOf(r.gif).string();
  }
  if (!r.mp4.empty()) {
    requireExtension("--mp4", r.mp4, ".mp4");
    checkOutputFile(r.mp4, "--mp4", "anim.mp4");
    farm.mp4 = absoluteOf(r.mp4).string();
  }
  farm.workdir = fs::current_path();
  farm.sylva = sylva;
  return farm;
}

Farm planEach(const EachRequest& r, const fs::path& sylva) {
  checkResources(r.resources);
  if (r.command.empty()) {
    fail("no command: give it after `--` (sylva farm each LIST -o OUT -- sylva fold synth {{}} -o "
         "out/{{stem}})");
  }
  if (r.out.empty()) {
    fail("-o/--out: the farm's folder is needed (its state, logs and done markers)");
  }
  Farm farm;
  farm.kind = "each";
  std::istringstream lines(readTextFile(r.list));
  std::string line;
  while (std::getline(lines, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) {
      line.pop_back();
    }
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') {
      continue;
    }
    farm.items.push_back(line.substr(first));
  }
  if (farm.items.empty()) {
    fail("{}: no items (one per line; blank lines and lines starting with '#' are skipped)", r.list);
  }
  for (const std::string& arg : r.command) {
    if (arg.find('\n') != std::string::npos) {
      fail("command argument '{}': holds a line break", arg);
    }
  }
  for (std::size_t k = 0; k < farm.items.size(); ++k) {
    std::string command;
    for (const std::string& arg : r.command) {
      if (!command.empty()) {
        command += ' ';
      }
      command += shellQuote(substitute(arg, farm.items[k], static_cast<int>(k)));
    }
    farm.commands.push_back(command);
  }
  farm.tasks = taskCount(static_cast<long long>(farm.items.size()), r.split, "items");
  farm.retries = r.split.retries;
  farm.resources = r.resources;
  farm.name = jobName(r.list);
  farm.out = absoluteOf(r.out);
  checkSbatchPath(farm.out, "--out");
  std::error_code ec;
  if (fs::exists(farm.out, ec) && !fs::is_directory(farm.out, ec)) {
    fail("--out {}: the farm needs a directory, and this is a file", r.out);
  }
  farm.workdir = fs::current_path();
  farm.sylva = sylva;
  return farm;
}

std::string taskScriptText(const Farm& farm) {
  const int count = farm.unitCount();
  std::string s = "#!/bin/bash\n";
  if (farm.kind == "render") {
    s += fmt::format("# Sylva render farm {}: frames {} of {}\n# in {} array tasks, written by `sylva farm "
                     "submit` (docs/farm.md). Task k renders frames k, k+{}, k+{}, …\n# of the range "
                     "(`sylva render --shard k/{}`), skipping frames already complete, so a retry resumes.\n",
                     farm.name, farm.frames, farm.scene.string(), farm.tasks, farm.tasks, 2 * farm.tasks,
                     farm.tasks);
  } else {
    s += fmt::format("# Sylva batch farm {}: {} items in {} array tasks, written by `sylva farm each`\n# "
                     "(docs/farm.md). Task k runs items k, k+{}, k+{}, … (their commands are the lines of "
                     "commands.txt);\n# an item that succeeds leaves done/<index>, so a retry or a resubmit "
                     "skips it.\n",
                     farm.name, count, farm.tasks, farm.tasks, 2 * farm.tasks);
  }
  s += fmt::format("# `sylva farm resubmit {}` submits it again for the tasks with work missing.\n",
                   farm.out.string());
  s += commonDirectives(farm, farm.name, true);
  s += fmt::format("#SBATCH --array=0-{}{}\n", farm.tasks - 1,
                   farm.resources.concurrent > 0 ? fmt::format("%{}", farm.resources.concurrent) : "");
  s += fmt::format("#SBATCH --output={}/logs/%x-%A_%a.out\n", farm.dir().string());
  s += "set -u\n";
  s += "task=${SLURM_ARRAY_TASK_ID:?run this script as a Slurm array task (sbatch --array)}\n";
  s += fmt::format("cd {} || exit 1\n", shellQuote(farm.workdir.string()));
  s += fmt::format("attempts={}\n", farm.retries + 1);
  if (farm.kind == "render") {
    s += "for attempt in $(seq 1 \"$attempts\"); do\n";
    s += "  echo \"sylva farm: task $task, attempt $attempt of $attempts on $(hostname)\" >&2\n";
    s += "  " + renderCommand(farm, fmt::format("\"$task/{}\"", farm.tasks), false) + " && exit 0\n";
    s += "done\n";
    s += "echo \"sylva farm: task $task failed $attempts times\" >&2\nexit 1\n";
    return s;
  }
  const std::string done = shellQuote((farm.dir() / "done").string());
  s += fmt::format("mkdir -p {}\nfailed=0\n", done);
  s += fmt::format("for ((i = task; i < {}; i += {})); do\n", count, farm.tasks);
  s += fmt::format("  [ -e {}/\"$i\" ] && continue\n", done);
  s += fmt::format("  command=$(sed -n \"$((i + 1))p\" {})\n",
                   shellQuote((farm.dir() / "commands.txt").string()));
  s += "  ok=0\n";
  s += "  for attempt in $(seq 1 \"$attempts\"); do\n";
  s += "    echo \"sylva farm: item $i, attempt $attempt of $attempts on $(hostname): $command\" >&2\n";
  s += "    if bash -c \"$command\"; then\n      ok=1\n      break\n    fi\n  done\n";
  s += fmt::format("  if [ \"$ok\" = 1 ]; then\n    : >{}/\"$i\"\n  else\n", done);
  s += "    echo \"sylva farm: item $i failed $attempts times\" >&2\n    failed=1\n  fi\ndone\nexit "
       "\"$failed\"\n";
  return s;
}

std::string encodeScriptText(const Farm& farm) {
  std::string s = "#!/bin/bash\n";
  s += fmt::format(
      "# Sylva render farm {}: encodes frames {} once every array task has succeeded\n# (submitted "
      "with --dependency=afterok on the array and --kill-on-invalid-dep=yes, so a failed task\n# "
      "cancels it instead of leaving it pending). The frames are complete: this renders none.\n",
      farm.name, farm.frames);
  s += commonDirectives(farm, farm.name + "-encode", false);
  s += fmt::format("#SBATCH --output={}/logs/%x-%j.out\n", farm.dir().string());
  s += fmt::format("cd {} || exit 1\n", shellQuote(farm.workdir.string()));
  s += "exec " + renderCommand(farm, "", true) + "\n";
  return s;
}

std::string arrayList(std::vector<int> indices) {
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::string out;
  for (std::size_t i = 0; i < indices.size();) {
    std::size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) {
      ++j;
    }
    if (!out.empty()) {
      out += ',';
    }
    out += j > i ? fmt::format("{}-{}", indices[i], indices[j]) : std::to_string(indices[i]);
    i = j + 1;
  }
  return out;
}

std::vector<int> parseArrayList(std::string_view text) {
  std::string_view list = text.substr(0, text.find('%')); // "%K": the concurrency cap
  std::vector<int> out;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    std::string_view part = list.substr(0, comma);
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
    int step = 1;
    if (const std::size_t colon = part.find(':'); colon != std::string_view::npos) {
      step = parseIndex(part.substr(colon + 1), text);
      part = part.substr(0, colon);
      if (step < 1) {
        fail("array list: step {} in '{}'", step, text);
      }
    }
    const std::size_t dash = part.find('-');
    const int a = parseIndex(part.substr(0, dash), text);
    const int b = dash == std::string_view::npos ? a : parseIndex(part.substr(dash + 1), text);
    if (b < a || b - a > 1000000) {
      fail("array list: '{}' in '{}'", part, text);
    }
    for (int v = a; v <= b; v += step) {
      out.push_back(v);
    }
  }
  if (out.empty()) {
    fail("array list: '{}' holds no index", text);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string manifestText(const Farm& farm) {
  nlohmann::json j;
  j["version"] = 1;
  j["kind"] = farm.kind;
  j["name"] = farm.name;
  j["out"] = farm.out.string();
  j["workdir"] = farm.workdir.string();
  j["sylva"] = farm.sylva.string();
  j["tasks"] = farm.tasks;
  j["retries"] = farm.retries;
  j["resources"] = {{"partition", farm.resources.partition},
                    {"cpusPerTask", farm.resources.cpusPerTask},
                    {"gpusPerTask", farm.resources.gpusPerTask},
                    {"time", farm.resources.time},
                    {"concurrent", farm.resources.concurrent}};
  if (farm.kind == "render") {
    j["scene"] = farm.scene.string();
    j["frames"] = farm.frames;
    j["camera"] = farm.camera;
    j["width"] = farm.width;
    j["height"] = farm.height;
    j["gif"] = farm.gif;
    j["mp4"] = farm.mp4;
  } else {
    j["items"] = farm.items;
    j["commands"] = farm.commands;
  }
  j["submissions"] = nlohmann::json::array();
  for (const Submission& s : farm.submissions) {
    j["submissions"].push_back({{"arrayJob", s.arrayJob}, {"tasks", s.tasks}, {"encodeJob", s.encodeJob}});
  }
  return j.dump(2) + "\n";
}

void saveFarm(const Farm& farm) {
  writeTextFile(farm.dir() / "farm.json", manifestText(farm));
}

Farm loadFarm(const fs::path& out) {
  const fs::path file = out / "farm" / "farm.json";
  std::error_code ec;
  if (!fs::exists(file, ec)) {
    fail("{}: not a farm (no farm/farm.json: give the folder `sylva farm submit` or `each` wrote to)",
         out.string());
  }
  return parseFarm(readTextFile(file), file.string());
}

Farm parseFarm(std::string_view text, const std::string& where) {
  const nlohmann::json json = parseJsonStrict(text, where);
  requireJsonVersion(json, 1, where);
  const JsonNode root(json, where);
  Farm farm;
  farm.kind = root["kind"].choice({"render", "each"});
  root.object(
      farm.kind == "render"
          ? std::initializer_list<const char*>{"version", "kind", "name", "out", "workdir", "sylva", "tasks",
                                               "retries", "resources", "scene", "frames", "camera", "width",
                                               "height", "gif", "mp4", "submissions"}
          : std::initializer_list<const char*>{"version", "kind", "name", "out", "workdir", "sylva", "tasks",
                                               "retries", "resources", "items", "commands", "submissions"});
  farm.name = root["name"].string();
  farm.out = root["out"].string();
  farm.workdir = root["workdir"].string();
  farm.sylva = root["sylva"].string();
  farm.tasks = root["tasks"].integer(1, 1000000);
  farm.retries = root["retries"].integer(0, 100);
  const JsonNode res = root["resources"];
  res.object({"partition", "cpusPerTask", "gpusPerTask", "time", "concurrent"});
  farm.resources.partition = res["partition"].string(true);
  farm.resources.cpusPerTask = res["cpusPerTask"].integer(1, 1024);
  farm.resources.gpusPerTask = res["gpusPerTask"].integer(0, 64);
  farm.resources.time = res["time"].string(true);
  farm.resources.concurrent = res["concurrent"].integer(0, 1000000);
  if (farm.kind == "render") {
    farm.scene = root["scene"].string();
    farm.frames = root["frames"].string();
    try {
      scene::parseFrames(farm.frames);
    } catch (const Error& e) {
      root["frames"].error(e.what());
    }
    farm.camera = root["camera"].string();
    farm.width = root["width"].integer(1, 1 << 16);
    farm.height = root["height"].integer(1, 1 << 16);
    farm.gif = root["gif"].string(true);
    farm.mp4 = root["mp4"].string(true);
  } else {
    const JsonNode items = root["items"];
    const JsonNode commands = root["commands"];
    const std::size_t n = items.array(1, 1000000);
    commands.arrayOf(n, "commands, one per item");
    for (std::size_t k = 0; k < n; ++k) {
      farm.items.push_back(items[k].string());
      farm.commands.push_back(commands[k].string());
    }
  }
  if (farm.tasks > farm.unitCount()) {
    root["tasks"].error(fmt::format("{} tasks for {} units", farm.tasks, farm.unitCount()));
  }
  const JsonNode subs = root["submissions"];
  const std::size_t n = subs.array(0, 100000);
  for (std::size_t k = 0; k < n; ++k) {
    const JsonNode s = subs[k];
    s.object({"arrayJob", "tasks", "encodeJob"});
    Submission sub;
    sub.arrayJob = s["arrayJob"].string();
    sub.encodeJob = s["encodeJob"].string(true);
    const std::size_t t = s["tasks"].array(1, 1000000);
    for (std::size_t i = 0; i < t; ++i) {
      sub.tasks.push_back(s["tasks"][i].integer(0, farm.tasks - 1));
    }
    farm.submissions.push_back(std::move(sub));
  }
  return farm;
}

std::vector<TaskState> parseJobLines(std::string_view text) {
  std::vector<TaskState> out;
  std::istringstream lines{std::string(text)};
  std::string line;
  while (std::getline(lines, line)) {
    const std::string id = field(line, "JobId");
    const std::string state = field(line, "JobState");
    if (id.empty() || state.empty()) {
      continue;
    }
    TaskState t;
    t.state = state;
    t.reason = field(line, "Reason");
    t.exitCode = field(line, "ExitCode");
    const std::string arrayJob = field(line, "ArrayJobId");
    const std::string taskId = field(line, "ArrayTaskId");
    if (arrayJob.empty() || taskId.empty()) {
      t.job = id;
      out.push_back(t);
      continue;
    }
    t.job = arrayJob;
    try {
      for (int index : parseArrayList(taskId)) {
        t.task = index;
        out.push_back(t);
      }
    } catch (const Error&) {
      // A record we cannot read (a newer Slurm's syntax) says nothing about our tasks.
    }
  }
  return out;
}

bool stateActive(std::string_view s) {
  return s == "PENDING" || s == "RUNNING" || s == "CONFIGURING" || s == "COMPLETING" || s == "SUSPENDED" ||
         s == "REQUEUED" || s == "REQUEUE_HOLD" || s == "REQUEUE_FED" || s == "RESIZING" ||
         s == "SIGNALING" || s == "STAGE_OUT";
}

std::vector<int> FarmStatus::toResubmit() const {
  std::vector<int> out;
  for (const TaskStatus& t : tasks) {
    if (!t.missing.empty() && !stateActive(t.state)) {
      out.push_back(t.task);
    }
  }
  return out;
}

std::vector<int> FarmStatus::failed() const {
  std::vector<int> out;
  for (const TaskStatus& t : tasks) {
    if (!t.missing.empty() && !t.job.empty() && !stateActive(t.state)) {
      out.push_back(t.task);
    }
  }
  return out;
}

bool FarmStatus::settled() const {
  for (const TaskStatus& t : tasks) {
    if (stateActive(t.state)) {
      return false;
    }
  }
  return !stateActive(encodeState);
}

FarmStatus farmStatus(const Farm& farm, const std::vector<TaskState>& known) {
  FarmStatus st;
  std::map<std::pair<std::string, int>, const TaskState*> byTask;
  for (const TaskState& t : known) {
    byTask[{t.job, t.task}] = &t;
  }
  for (int task = 0; task < farm.tasks; ++task) {
    TaskStatus ts;
    ts.task = task;
    for (int unit : farm.unitsOf(task)) {
      ++ts.units;
      if (farm.unitDone(unit)) {
        ++ts.done;
      } else {
        ts.missing.push_back(unit);
      }
    }
    for (auto it = farm.submissions.rbegin(); it != farm.submissions.rend(); ++it) {
      if (std::find(it->tasks.begin(), it->tasks.end(), task) != it->tasks.end()) {
        ts.job = it->arrayJob;
        ts.log = farm.logOf(it->arrayJob, task);
        if (const auto found = byTask.find({it->arrayJob, task}); found != byTask.end()) {
          ts.state = found->second->state;
          ts.reason = found->second->reason;
          ts.exitCode = found->second->exitCode;
        }
        break;
      }
    }
    st.units += ts.units;
    st.done += ts.done;
    if (ts.state == "RUNNING" || ts.state == "COMPLETING") {
      st.inProgress += static_cast<int>(ts.missing.size());
    }
    st.tasks.push_back(std::move(ts));
  }
  if (!farm.submissions.empty() && !farm.submissions.back().encodeJob.empty()) {
    st.encodeJob = farm.submissions.back().encodeJob;
    if (const auto found = byTask.find({st.encodeJob, -1}); found != byTask.end()) {
      st.encodeState = found->second->state;
      st.encodeReason = found->second->reason;
    }
  }
  std::error_code ec;
  st.encodeWritten = farm.encodes() && (farm.gif.empty() || fs::exists(farm.gif, ec)) &&
                     (farm.mp4.empty() || fs::exists(farm.mp4, ec));
  return st;
}

std::string tailOf(const fs::path& file, int lines) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    return {};
  }
  std::vector<std::string> last;
  std::string line;
  while (std::getline(in, line)) {
    // Progress lines redraw with '\r': the last state of the line is what a person would have seen.
    if (const std::size_t cr = line.find_last_of('\r', line.size() >= 2 ? line.size() - 2 : 0);
        cr != std::string::npos && cr + 1 < line.size()) {
      line = line.substr(cr + 1);
    }
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
    }
    last.push_back(line);
    if (static_cast<int>(last.size()) > lines) {
      last.erase(last.begin());
    }
  }
  std::string out;
  for (const std::string& l : last) {
    out += l + "\n";
  }
  return out;
}

std::string statusText(const Farm& farm, const FarmStatus& st) {
  const std::string unit = farm.kind == "render" ? "frames" : "items";
  std::string s;
  if (farm.kind == "render") {
    s += fmt::format("{}: frames {} of {} in {} tasks → {}\n", farm.name, farm.frames, farm.scene.string(),
                     farm.tasks, farm.out.string());
  } else {
    s += fmt::format("{}: {} items in {} tasks → {}\n", farm.name, st.units, farm.tasks, farm.out.string());
  }
  const int missing = st.units - st.done;
  s += fmt::format("{}: {} of {} done, {} in progress, {} missing\n", unit, st.done, st.units, st.inProgress,
                   missing - st.inProgress);
  s +=
      fmt::format("{:>6}  {:>6}  {:>6}  {:<12} {:<14} {}\n", "task", unit, "done", "state", "job", "missing");
  for (const TaskStatus& t : st.tasks) {
    std::string list;
    for (std::size_t k = 0; k < t.missing.size() && k < 8; ++k) {
      list += fmt::format("{}{}", k ? ", " : "", t.missing[k]);
    }
    if (t.missing.size() > 8) {
      list += fmt::format(", … ({} in all)", t.missing.size());
    }
    std::string state = t.job.empty() ? "not submitted" : t.state.empty() ? "ended" : t.state;
    if (stateEndedBadly(t.state) && !t.exitCode.empty() && t.exitCode != "0:0") {
      state += " " + t.exitCode;
    }
    s += fmt::format("{:>6}  {:>6}  {:>6}  {:<12} {:<14} {}\n", t.task, t.units, t.done, state,
                     t.job.empty() ? "-" : fmt::format("{}_{}", t.job, t.task), list);
  }
  if (!st.encodeJob.empty()) {
    s += fmt::format("encode job {}: {}{}{}\n", st.encodeJob,
                     st.encodeState.empty() ? "ended" : st.encodeState,
                     st.encodeReason.empty() || st.encodeReason == "None" ? "" : " (" + st.encodeReason + ")",
                     st.encodeWritten ? ", written" : "");
  }
  for (const int task : st.failed()) {
    const TaskStatus& t = st.tasks[static_cast<std::size_t>(task)];
    const std::string tail = tailOf(t.log, 6);
    s += fmt::format("failed task {} ({} {} missing), log {}:\n", task, t.missing.size(), unit,
                     t.log.string());
    std::istringstream lines(tail.empty() ? std::string("(no log)\n") : tail);
    std::string line;
    while (std::getline(lines, line)) {
      s += "  | " + line + "\n";
    }
  }
  if (!st.toResubmit().empty()) {
    s += fmt::format("to render what is missing: sylva farm resubmit {}\n", shellQuote(farm.out.string()));
  } else if (missing == 0 && farm.encodes() && !st.encodeWritten && !stateActive(st.encodeState)) {
    s += fmt::format("every frame is done; to encode: sylva farm resubmit {}\n",
                     shellQuote(farm.out.string()));
  }
  return s;
}

std::string statusJson(const Farm& farm, const FarmStatus& st) {
  nlohmann::json j;
  j["name"] = farm.name;
  j["kind"] = farm.kind;
  j["out"] = farm.out.string();
  j["units"] = st.units;
  j["done"] = st.done;
  j["inProgress"] = st.inProgress;
  j["settled"] = st.settled();
  j["tasks"] = nlohmann::json::array();
  for (const TaskStatus& t : st.tasks) {
    j["tasks"].push_back({{"task", t.task},
                          {"units", t.units},
                          {"done", t.done},
                          {"missing", t.missing},
                          {"job", t.job},
                          {"state", t.state},
                          {"reason", t.reason},
                          {"exitCode", t.exitCode},
                          {"log", t.log.string()}});
  }
  j["failed"] = st.failed();
  j["toResubmit"] = st.toResubmit();
  j["encode"] = {{"job", st.encodeJob},
                 {"state", st.encodeState},
                 {"reason", st.encodeReason},
                 {"written", st.encodeWritten}};
  return j.dump(2) + "\n";
}

FilesystemKind filesystemOf(const fs::path& path) {
  fs::path p = fs::absolute(path);
  std::error_code ec;
  while (!p.empty() && !fs::exists(p, ec) && p != p.root_path()) {
    p = p.parent_path();
  }
  struct statfs info {};
  if (::statfs(p.c_str(), &info) != 0) {
    return {"unknown", true};
  }
  // Magic numbers from statfs(2) / linux/magic.h, and the cluster filesystems' own.
  static const std::map<unsigned long, std::pair<const char*, bool>> kTypes = {
      {0x6969, {"nfs", true}},           {0x0BD00BD0, {"lustre", true}},   {0x47504653, {"gpfs", true}},
      {0xFF534D42, {"cifs", true}},      {0xFE534D42, {"smb2", true}},     {0x517B, {"smb", true}},
      {0x00C36400, {"ceph", true}},      {0x19830326, {"beegfs", true}},   {0x5346414F, {"afs", true}},
      {0x6B414653, {"afs", true}},       {0xAAD7AAEA, {"panfs", true}},    {0x65735546, {"fuse", true}},
      {0xEF53, {"ext4", false}},         {0x58465342, {"xfs", false}},     {0x9123683E, {"btrfs", false}},
      {0x01021994, {"tmpfs", false}},    {0x794C7630, {"overlay", false}}, {0x2FC12FC1, {"zfs", false}},
      {0x73717368, {"squashfs", false}}, {0xF2F52010, {"f2fs", false}},    {0x4d44, {"vfat", false}}};
  const auto it = kTypes.find(static_cast<unsigned long>(info.f_type));
  if (it == kTypes.end()) {
    return {fmt::format("0x{:x}", static_cast<unsigned long>(info.f_type)), true};
  }
  return {it->second.first, it->second.second};
}

} // namespace sylva::farm
