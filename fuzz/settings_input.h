#pragma once
// What the settings fuzz target does with one input, shared with its corpus replay test
// (src/amos/config/fuzz_corpus_test.cc): the bytes are a settings file, parsed and checked as `run --config` does.
// core::Error (InvalidOption included) is the documented outcome of a bad file; anything else escapes.
#include <string>

#include "amos/config/settings.h"

namespace amos::fuzz {

inline void readSettingsInput(const std::string& bytes) {
  const config::Settings settings = config::parseSettings(bytes, "fuzz.yaml");
  (void)settings.readerOptions();
  (void)settings.closeDepthThreshold();
}

}  // namespace amos::fuzz
