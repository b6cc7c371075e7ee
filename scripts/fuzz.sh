#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang (ASan + UBSan) into ./build-fuzz and runs each in turn for
# SECONDS (default 60) seconds, at the lowest priority. Each starts from its seeds in fuzz/corpus/<name>/ (read only);
# what it finds goes to build-fuzz/corpus/<name>/, and a crashing input to build-fuzz/artifacts/<name>/ (after the fix,
# put it into fuzz/corpus/<name>/ so that the replay tests keep it). A single allocation above AMOS_FUZZ_MALLOC_MB
# (default 512) MB is reported as a crash: inputs are a few kB, so that is a header claiming more than its input
# holds. AMOS_JOBS (default 1) sets the build's jobs.
# Usage: bash scripts/fuzz.sh [SECONDS] [NAME...]   (names: settings sequence_index trajectory png ply)
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH="${1:-60}"
shift || true
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then TARGETS=(settings sequence_index trajectory png ply); fi
bash scripts/install_fuzz_deps.sh
nice -n 19 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DAMOS_BUILD_FUZZ=ON -DAMOS_BUILD_TESTS=OFF -DAMOS_BUILD_BENCH=OFF >/dev/null
nice -n 19 cmake --build build-fuzz -j "${AMOS_JOBS:-1}" --target "${TARGETS[@]/%/_fuzz}"
status=0
for name in "${TARGETS[@]}"; do
  mkdir -p "build-fuzz/corpus/$name" "build-fuzz/artifacts/$name"
  echo "fuzz.sh: $name for ${SECONDS_EACH} s"
  nice -n 19 "build-fuzz/bin/${name}_fuzz" -max_total_time="$SECONDS_EACH" -print_final_stats=1 \
    -malloc_limit_mb="${AMOS_FUZZ_MALLOC_MB:-512}" \
    -artifact_prefix="build-fuzz/artifacts/$name/" "build-fuzz/corpus/$name" "fuzz/corpus/$name" \
    2>"build-fuzz/${name}_fuzz.log" || { status=1; echo "fuzz.sh: $name FAILED, see build-fuzz/${name}_fuzz.log"; }
  grep -E "^stat::(number_of_executed_units|average_exec_per_sec|new_units_added)|^SUMMARY" \
    "build-fuzz/${name}_fuzz.log" || true
done
exit $status
