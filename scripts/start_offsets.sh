#!/usr/bin/env bash
# ATE of deterministic runs that start at frames 0..N-1 of a sequence, and their mean: a short sequence's ATE
# depends on where the map starts (which frames become keyframes), so one run says less than several.
#   scripts/start_offsets.sh SEQUENCE CONFIG [N=8] [MODE=none]
# e.g. scripts/start_offsets.sh ../shared/data/tum_fr2_desk_first50 configs/tum2.yaml
# Each slice is a temporary folder with the sequence's images linked and its lists shortened; build first
# (scripts/build.sh).
set -euo pipefail
sequence=$(realpath "${1:?sequence folder}")
config=$(realpath "${2:?settings file}")
count=${3:-8}
mode=${4:-none}
root=$(cd "$(dirname "$0")/.." && pwd)
slam="$root/build/bin/amos-slam"
[[ -x "$slam" ]] || { echo "error: $slam not found; run scripts/build.sh first" >&2; exit 1; }
[[ -f "$sequence/groundtruth.txt" ]] || { echo "error: $sequence/groundtruth.txt not found" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

results=()
for ((offset = 0; offset < count; offset++)); do
  slice="$work/slice_$offset"
  mkdir -p "$slice"
  for entry in "$sequence"/*; do
    name=$(basename "$entry")
    case "$name" in
      rgb.txt | depth.txt | associate.txt | associations.txt)
        # Comment lines stay, the first `offset` data lines go.
        awk -v skip="$offset" '/^#/ { print; next } NF { if (n++ >= skip) print }' "$entry" > "$slice/$name" ;;
      *) ln -s "$entry" "$slice/$name" ;;
    esac
  done
  out="$work/out_$offset"
  "$slam" run --sequence "$slice" --config "$config" --output "$out" --mode "$mode" --deterministic > "$out.log" 2>&1 ||
    { echo "error: run from frame $offset failed:" >&2; tail -3 "$out.log" >&2; exit 1; }
  ate=$("$slam" eval --gt "$sequence/groundtruth.txt" --est "$out/trajectory.txt" --json |
        sed -n 's/.*"ate_rmse_m": *\([0-9.eE+-]*\).*/\1/p')
  results+=("$ate")
  printf 'start at frame %d: ATE RMSE %.2f mm\n' "$offset" "$(awk -v a="$ate" 'BEGIN { print 1000 * a }')"
done
printf '%s\n' "${results[@]}" | awk '{ s += $1; n++ } END { printf "mean over %d starts: %.2f mm\n", n, 1000 * s / n }'
