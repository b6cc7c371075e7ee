#pragma once
// The two functions of a libFuzzer target that feeds every input, as a std::string, to `entry`: logging is off
// (malformed inputs are warned about by the thousand); core::Error is an accepted outcome; a crash, a sanitizer
// report or any other exception (which reaches std::terminate) is a bug. A macro because libFuzzer finds the two
// functions by their C names, which each target defines once.
#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "amos/core/error.h"

#define AMOS_FUZZ_TARGET(entry)                                                       \
  extern "C" int LLVMFuzzerInitialize(int*, char***) {                                \
    spdlog::set_level(spdlog::level::off);                                            \
    return 0;                                                                         \
  }                                                                                   \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    try {                                                                             \
      entry(std::string(reinterpret_cast<const char*>(data), size));                  \
    } catch (const amos::core::Error&) {                                              \
    }                                                                                 \
    return 0;                                                                         \
  }
