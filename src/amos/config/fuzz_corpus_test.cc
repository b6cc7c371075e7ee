// The corpus of the settings fuzz target (fuzz/corpus/settings/), replayed through the target's entry function: no
// input may crash or throw anything but core::Error.
#include <gtest/gtest.h>

#include "amos/testing/fuzz_corpus.h"
#include "fuzz/settings_input.h"

namespace amos::config {
namespace {

TEST(FuzzCorpus, SettingsInputsGiveSettingsOrCoreErrors) {
  EXPECT_GE(testing::replayFuzzCorpus("settings", fuzz::readSettingsInput), 8u);
}

}  // namespace
}  // namespace amos::config
