// libFuzzer entry point for one target, chosen at build time by SYLVA_FUZZ_TARGET (see fuzz/CMakeLists.txt).
#include "Harness.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sylva::fuzz::runTarget(SYLVA_FUZZ_TARGET, {data, size});
  return 0;
}
