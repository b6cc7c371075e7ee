#!/usr/bin/env bash
# Command (1) of the README: installs the core dependencies, builds the program without its optional parts (those
# whose packages are absent are switched off), renders a synthetic dynamic sequence (the default input, made from
# nothing outside the repository) and runs SLAM on it with the full anti-dynamics front end, printing its accuracy
# against the exact ground truth.
set -euo pipefail
cd "$(dirname "$0")/.."
AMOS_MIN_FREE_GIB="${AMOS_MIN_FREE_GIB:-3}" bash scripts/check_disk_space.sh  # the core alone
bash scripts/install_deps.sh --core
bash scripts/build.sh -DAMOS_BUILD_TESTS=OFF -DAMOS_BUILD_BENCH=OFF
PRESET="${1:-walking_xyz}"
OUT="${AMOS_DEMO_DIR:-out/demo}"
mkdir -p "$OUT"
# Real person photographs make the synthetic walkers look like people to the detector; used when available.
CUTOUTS=()
if [ -d ../shared/data/person_masks ]; then CUTOUTS=(--person-cutouts ../shared/data/person_masks); fi
./build/bin/amos-slam synth --preset "$PRESET" --seed 1 --frames 300 --output "$OUT/$PRESET" "${CUTOUTS[@]}"
./build/bin/amos-slam run --sequence "$OUT/$PRESET" --config configs/tum3.yaml --output "$OUT/run_$PRESET" --overwrite
