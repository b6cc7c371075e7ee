// libFuzzer target: amos::fuzz::readSettingsInput (fuzz/settings_input.h) on every input
// (fuzz/fuzz_target.h says what is a bug). scripts/fuzz.sh builds and runs it.
#include "fuzz/fuzz_target.h"
#include "fuzz/settings_input.h"

AMOS_FUZZ_TARGET(amos::fuzz::readSettingsInput)
