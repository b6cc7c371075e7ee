// libFuzzer target: amos::fuzz::readPlyInput (fuzz/ply_input.h) on every input
// (fuzz/fuzz_target.h says what is a bug). scripts/fuzz.sh builds and runs it.
#include "fuzz/fuzz_target.h"
#include "fuzz/ply_input.h"

AMOS_FUZZ_TARGET(amos::fuzz::readPlyInput)
