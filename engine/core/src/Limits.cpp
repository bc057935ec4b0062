#include <sylva/core/Limits.hpp>

#include <fstream>
#include <string>

namespace sylva {

std::optional<std::size_t> availableMemoryBytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::size_t kb = 0;
  std::string unit;
  while (meminfo >> key >> kb >> unit) {
    if (key == "MemAvailable:") {
      return kb * 1024;
    }
  }
  return std::nullopt;
}

} // namespace sylva
