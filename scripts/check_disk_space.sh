#!/usr/bin/env bash
# Warns (never fails) when the disk that builds and tests is nearly full, before apt-get, the compiler or a test
# fails half-way with "No space left on device": a fresh machine needs about 4 GiB (the build folder 1.1 GiB with
# the tests, the compiler cache 0.4 GiB, the packages most of the rest); the tests' scratch folders stay under
# 0.2 GiB, since each test process removes its own (src/amos/testing/scratch_dir.h).
#   bash scripts/check_disk_space.sh [FOLDER...]   (default: the checkout and the temp folder)
# AMOS_MIN_FREE_GIB sets the bar (default 4).
set -euo pipefail
min_gib="${AMOS_MIN_FREE_GIB:-4}"
[[ "$min_gib" =~ ^[0-9]+$ ]] || { echo "check_disk_space.sh: AMOS_MIN_FREE_GIB must be a whole number of GiB, not '$min_gib'" >&2; exit 2; }
folders=("$@")
((${#folders[@]})) || folders=("$(cd "$(dirname "$0")/.." && pwd)" "${TMPDIR:-/tmp}")
for folder in "${folders[@]}"; do
  free_kib=$(df -Pk "$folder" | awk 'NR == 2 {print $4}')
  if ((free_kib < min_gib * 1024 * 1024)); then
    echo "warning: $folder has $((free_kib / 1024)) MiB free; this needs about $min_gib GiB" \
      "(free some space, or set TMPDIR to a folder on a larger disk)" >&2
  fi
done
