// libFuzzer target: amos::fuzz::readTrajectoryInput (fuzz/io_inputs.h) on every input. core::Error is an accepted
// outcome; a crash, a sanitizer report or any other exception (which reaches std::terminate) is a bug.
// scripts/fuzz.sh builds and runs it.
#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "amos/core/error.h"
#include "fuzz/io_inputs.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  spdlog::set_level(spdlog::level::off);  // warnings about bad lines are expected by the thousand
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    amos::fuzz::readTrajectoryInput(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const amos::core::Error&) {
  }
  return 0;
}
