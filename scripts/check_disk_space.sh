#!/usr/bin/env bash
# Warns (never fails) when the disk that builds and tests is nearly full, before apt-get, the compiler or a test
# fails half-way with "No space left on device". On a fresh Debian 12 machine (apt-get -s in a debootstrap root,
# sizes from apt-cache), the test command installs 2.9 GiB of packages from 0.63 GiB of downloads, its build folder
# is 1.1 GiB and the compiler cache 0.4 GiB: about 5 GiB; the demo installs 1.75 GiB from 0.39 GiB and builds
# little: about 3 GiB. The tests' scratch folders stay under 0.2 GiB, since each test process removes its own
# (src/amos/testing/scratch_dir.h). With the packages already there, far less is needed: it only warns.
#   bash scripts/check_disk_space.sh [FOLDER...]   (default: the checkout and the temp folder)
# AMOS_MIN_FREE_GIB sets the bar (default 5, the test command's).
set -euo pipefail
min_gib="${AMOS_MIN_FREE_GIB:-5}"
[[ "$min_gib" =~ ^[0-9]+$ ]] || { echo "check_disk_space.sh: AMOS_MIN_FREE_GIB must be a whole number of GiB, not '$min_gib'" >&2; exit 2; }
folders=("$@")
((${#folders[@]})) || folders=("$(cd "$(dirname "$0")/.." && pwd)" "${TMPDIR:-/tmp}")
for folder in "${folders[@]}"; do
  free_kib=$(df -Pk "$folder" | awk 'NR == 2 {print $4}')
  if ((free_kib < min_gib * 1024 * 1024)); then
    echo "warning: $folder has $((free_kib / 1024)) MiB free; a fresh set-up needs about $min_gib GiB" \
      "(free some space, or set TMPDIR to a folder on a larger disk)" >&2
  fi
done
