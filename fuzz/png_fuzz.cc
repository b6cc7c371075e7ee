// libFuzzer target: amos::fuzz::decodePngInput (fuzz/io_inputs.h) on every input
// (fuzz/fuzz_target.h says what is a bug). scripts/fuzz.sh builds and runs it.
#include "fuzz/fuzz_target.h"
#include "fuzz/io_inputs.h"

AMOS_FUZZ_TARGET(amos::fuzz::decodePngInput)
