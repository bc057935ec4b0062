#include "Bench.hpp"

#include <unistd.h>

#include <cstdint>
#include <fstream>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

namespace sylva::app {

std::uint64_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t size = 0;
  std::uint64_t resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::vector<double> timeRuns(int warmup, int runs, const std::function<void()>& fn) {
  std::vector<double> seconds;
  for (int i = 0; i < warmup + runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (i >= warmup) {
      seconds.push_back(s);
    }
  }
  return seconds;
}

nlohmann::json printBenchRows(const std::vector<BenchRow>& rows) {
  std::printf("  %-62s %12s %-16s %8s %5s %7s  %s\n", "metric", "measured", "unit", "target", "", "threads",
              "note");
  nlohmann::json rowsJson = nlohmann::json::array();
  for (const BenchRow& r : rows) {
    const bool measured = !std::isnan(r.value);
    const bool hasTarget = !std::isnan(r.target);
    const bool pass = measured && hasTarget && (r.atMost ? r.value <= r.target : r.value >= r.target);
    const std::string target = hasTarget ? fmt::format("{:g}", r.target) : std::string();
    std::printf("  %-62s %12.4g %-16s %2s %5s %5s %7s  %s\n", r.metric.c_str(), r.value, r.unit.c_str(),
                !hasTarget ? ""
                : r.atMost ? "<="
                           : ">=",
                target.c_str(),
                !measured || !hasTarget ? "-"
                : pass                  ? "ok"
                                        : "MISS",
                r.threads == 0 ? "gpu" : std::to_string(r.threads).c_str(), r.note.c_str());
    rowsJson.push_back({{"metric", r.metric},
                        {"value", measured ? nlohmann::json(r.value) : nlohmann::json(nullptr)},
                        {"unit", r.unit},
                        {"target", hasTarget ? nlohmann::json(r.target) : nlohmann::json(nullptr)},
                        {"target_is", r.atMost ? "at most" : "at least"},
                        {"met", measured && hasTarget ? nlohmann::json(pass) : nlohmann::json(nullptr)},
                        {"threads", r.threads},
                        {"note", r.note}});
  }
  return rowsJson;
}

} // namespace sylva::app
