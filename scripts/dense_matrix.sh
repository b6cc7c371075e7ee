#!/usr/bin/env bash
# The dense static map on synthetic truth (issue 43): per preset and seed, `run --dense` in each mode on the dynamic
# sequence and in mode none on its static twin (same room and camera path, --no-movers), each mesh scored by
# `amos-slam eval-mesh` against the sequence's true static surface: accuracy (median, 90 %), completeness and
# ghosts (vertices farther than 2 voxels from the static truth). People must leave ghosts in none, close to none
# in full, and the twin is the reference.
#   bash scripts/dense_matrix.sh [--seeds "1 2 3 4 5"] [--presets "walking_xyz walking_halfsphere walking_static
#                                objects_xyz"] [--modes "full none"] [--frames 150] [--bin build/bin/amos-slam]
#                                [--out out/dense] [--config configs/tum3.yaml]
# The table (markdown) goes to stdout, progress to stderr. Sequences are cached in OUT/sequences/, runs go to
# OUT/runs/ with their logs. Exit status 1 when any job failed.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seeds="1 2 3 4 5"
presets="walking_xyz walking_halfsphere walking_static objects_xyz"
modes="full none"
frames=150
bin="$root/build/bin/amos-slam"
out="$root/out/dense"
config="$root/configs/tum3.yaml"

# shellcheck source=scripts/synth_lib.sh
source "$root/scripts/synth_lib.sh"
usage() { sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; }
while (($#)); do
  case "$1" in
    --presets) presets=${2:?--presets needs a value}; shift 2 ;;
    --modes) modes=${2:?--modes needs a value}; shift 2 ;;
    -h | --help) usage; exit 0 ;;
    *) common_option "$1" "${2-}" || { echo "error: unknown argument '$1' (see --help)" >&2; exit 2; }; shift 2 ;;
  esac
done
check_common_options
read -r -a preset_list <<< "$presets"
read -r -a mode_list <<< "$modes"
mkdir -p "$out/sequences" "$out/runs"
cd "$root"
failures=0

# dense_run SEQUENCE_DIR MODE NAME -> prints "accuracy_median p90 completeness ghost_share ghosts" (nothing on failure)
dense_run() {
  local seq=$1 mode=$2 dir="$out/runs/$2/$3" t0=$SECONDS
  rm -rf "$dir"; mkdir -p "$(dirname "$dir")"
  if "$bin" run --sequence "$seq" --config "$config" --output "$dir" --mode "$mode" --deterministic --dense \
      > "$dir.log" 2>&1 && "$bin" eval-mesh --mesh "$dir/mesh.ply" --sequence "$seq" >> "$dir.log" 2>&1; then
    log "run $3 --mode $mode --dense and eval-mesh done in $((SECONDS - t0)) s"
    python3 - "$dir/mesh_eval.json" << 'PY'
import json, sys
e = json.load(open(sys.argv[1]))
print(e["accuracy_median_m"], e["accuracy_p90_m"], e["completeness"], e["ghost_share"], e["ghosts"])
PY
  else
    log "run $3 --mode $mode FAILED (log: $dir.log)"; tail -3 "$dir.log" >&2
  fi
}

echo "## Dense static map on synthetic truth: seeds ${seed_list[*]}, $frames frames, $(basename "$config"), --deterministic"
echo
echo "| preset | run | seed | accuracy median (mm) | accuracy p90 (mm) | completeness | ghosts (%) | ghost vertices |"
echo "|---|---|---|---|---|---|---|---|"
declare -A acc p90 comp ghost
for preset in "${preset_list[@]}"; do
  for seed in "${seed_list[@]}"; do
    cases=()
    if seq=$(render "$preset" "$seed" 0); then
      for mode in "${mode_list[@]}"; do cases+=("$mode|$seq|$mode"); done
    else failures=$((failures + 1)); fi
    if twin=$(render "$preset" "$seed" 1); then cases+=("twin none|$twin|none"); else failures=$((failures + 1)); fi
    for c in "${cases[@]}"; do
      IFS='|' read -r label dir mode <<< "$c"
      if ! r=$(dense_run "$dir" "$mode" "$(basename "$dir")") || [[ -z "$r" ]]; then
        failures=$((failures + 1)); echo "| $preset | $label | $seed | fail | | | | |"; continue
      fi
      read -r a p c9 g n <<< "$r"
      acc[$preset|$label]+="$a "; p90[$preset|$label]+="$p "; comp[$preset|$label]+="$c9 "; ghost[$preset|$label]+="$g "
      echo "| $preset | $label | $seed | $(mm "$a") | $(mm "$p") | $(dec "$c9") | $(pct "$g") | $n |"
    done
  done
done
echo
echo "### Mean over the seeds"
echo
echo "| preset | run | accuracy median (mm) | accuracy p90 (mm) | completeness | ghosts (%) |"
echo "|---|---|---|---|---|---|"
for preset in "${preset_list[@]}"; do
  for label in "${mode_list[@]}" "twin none"; do
    # shellcheck disable=SC2086
    echo "| $preset | $label | $(mm "$(mean ${acc[$preset|$label]:-})") | $(mm "$(mean ${p90[$preset|$label]:-})") | $(dec "$(mean ${comp[$preset|$label]:-})") | $(pct "$(mean ${ghost[$preset|$label]:-})") |"
  done
done
((failures == 0)) || { log "$failures job(s) failed"; exit 1; }
