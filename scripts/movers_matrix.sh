#!/usr/bin/env bash
# Movers that no detector knows, on seeds nobody tuned on (issue 16). Per preset, seed and mode (--deterministic):
#   1. per mover: recall and precision of its pixels over the frames where it moves, the share of it still marked
#      over the frames where it rests, and after each stop the frames until it is released (marked share < 5 %);
#   2. ATE of the sequence against the same preset rendered --no-movers (same camera path, run in the same mode),
#      the pooled mask precision and recall, and the share of the twin's pixels marked dynamic.
#   bash scripts/movers_matrix.sh [--seeds "2 3 4"] [--presets "objects_xyz box_starts box_stops chair_push"]
#                                 [--modes "geometry full"] [--frames 300] [--bin build/bin/amos-slam]
#                                 [--out out/movers] [--config configs/tum3.yaml]
# Tables (markdown) go to stdout, progress to stderr; the last table gives the median over the seeds per mover.
# Sequences are cached in OUT/sequences/, runs go to OUT/runs/ with their logs. Exit status 1 when any job failed.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seeds="2 3 4"
presets="objects_xyz box_starts box_stops chair_push"
modes="geometry full"
frames=300
bin="$root/build/bin/amos-slam"
out="$root/out/movers"
config="$root/configs/tum3.yaml"

# shellcheck source=scripts/synth_lib.sh
source "$root/scripts/synth_lib.sh"  # options, log, json_get, instance_get, render, formatting
usage() { sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; }
while (($#)); do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    *) common_option "$1" "${2-}" || { echo "error: unknown argument '$1' (see --help)" >&2; exit 2; }; shift 2 ;;
  esac
done
check_common_options  # also fills preset_list and mode_list

mkdir -p "$out/sequences" "$out/runs"
cd "$root"
failures=0
start_all=$SECONDS

# run SEQUENCE_DIR MODE RUN_NAME -> prints the run folder (nothing on failure; runs in a subshell, so the caller
# counts the failures)
run() {
  local seq=$1 mode=$2 dir="$out/runs/$2/$3" t0=$SECONDS
  rm -rf "$dir"; mkdir -p "$(dirname "$dir")"
  if "$bin" run --sequence "$seq" --config "$config" --output "$dir" --mode "$mode" --deterministic > "$dir.log" 2>&1 &&
      [[ -f "$dir/stats.json" ]]; then
    log "run $3 --mode $mode done in $((SECONDS - t0)) s: ATE $(json_get "$dir/stats.json" .evaluation.ate_rmse_m) m"
    printf '%s\n' "$dir"
  else
    log "run $3 --mode $mode FAILED (log: $dir.log)"; tail -3 "$dir.log" >&2
  fi
}

movers_of() {  # STATS -> the names of the movers that move at some frame, one per line
  local names
  if command -v jq > /dev/null; then
    names=$(jq -r '.mask_accuracy.instances[]? | select(.moving_frames > 0) | .name' "$1" 2> /dev/null) || names=""
  else
    names=$(python3 - "$1" 2> /dev/null << 'EOF'
import json, sys
for i in json.load(open(sys.argv[1])).get("mask_accuracy", {}).get("instances", []):
    if i.get("moving_frames", 0) > 0:
        print(i["name"])
EOF
) || names=""
  fi
  printf '%s\n' "$names"
}

releases_of() {  # STATS NAME -> "first rest frame:frames to release" per stop, space-separated (-1: never released)
  if command -v jq > /dev/null; then
    jq -r --arg n "$2" '[.mask_accuracy.instances[]? | select(.name == $n) | .releases[]? |
      "\(.first_rest_frame):\(.frames_to_release)"] | join(" ")' "$1" 2> /dev/null || true
  else
    python3 - "$1" "$2" << 'EOF' 2> /dev/null || true
import json, sys
d = json.load(open(sys.argv[1]))
print(" ".join("%s:%s" % (r["first_rest_frame"], r["frames_to_release"])
               for i in d.get("mask_accuracy", {}).get("instances", []) if i.get("name") == sys.argv[2]
               for r in i.get("releases", [])))
EOF
  fi
}

declare -A runs  # runs[preset|seed|mode|dynamic|static] = run folder
log "movers matrix: presets ${preset_list[*]}, seeds ${seed_list[*]}, modes ${mode_list[*]}, $frames frames, config $config"
for seed in "${seed_list[@]}"; do
  for preset in "${preset_list[@]}"; do
    for static in 0 1; do
      kind=dynamic; ((static)) && kind=static
      if ! seq=$(render "$preset" "$seed" "$static"); then failures=$((failures + 1)); continue; fi
      for mode in "${mode_list[@]}"; do
        dir=$(run "$seq" "$mode" "$(basename "$seq")")
        [[ -n "$dir" ]] || failures=$((failures + 1))
        runs[$preset|$seed|$mode|$kind]=$dir
      done
    done
  done
done

echo "## Movers matrix: seeds ${seed_list[*]}, $frames frames, $(basename "$config"), --deterministic"
echo
echo "### Per mover: recall / precision over its moving frames, share marked at rest, frames to release after each stop"
echo "(first frame at rest:frames until less than 5 % of it is marked; -1 = never)"
echo
echo "| preset | mode | seed | mover | recall | precision | marked at rest (%) | frames to release |"
echo "|---|---|---|---|---|---|---|---|"
declare -A recalls precisions
for preset in "${preset_list[@]}"; do
  for mode in "${mode_list[@]}"; do
    for seed in "${seed_list[@]}"; do
      dir=${runs[$preset|$seed|$mode|dynamic]:-}
      [[ -n "$dir" ]] || { echo "| $preset | $mode | $seed | fail | | | | |"; continue; }
      while IFS= read -r mover; do
        [[ -n "$mover" ]] || continue
        r=$(instance_get "$dir/stats.json" "$mover" recall); p=$(instance_get "$dir/stats.json" "$mover" precision)
        rest=$(instance_get "$dir/stats.json" "$mover" rest_marked_fraction)
        rel=$(releases_of "$dir/stats.json" "$mover")
        recalls[$preset|$mode|$mover]+="$r "; precisions[$preset|$mode|$mover]+="$p "
        echo "| $preset | $mode | $seed | $mover | $(dec "$r") | $(dec "$p") | $(pct "$rest") | ${rel:-none} |"
      done < <(movers_of "$dir/stats.json")
    done
  done
done
echo
echo "### Per run: ATE against the same path without movers (same mode), pooled mask accuracy, static twin marked"
echo
echo "| preset | mode | seed | ATE (mm) | ATE no movers (mm) | ratio | precision | recall | twin marked (%) |"
echo "|---|---|---|---|---|---|---|---|---|"
for preset in "${preset_list[@]}"; do
  for mode in "${mode_list[@]}"; do
    for seed in "${seed_list[@]}"; do
      d=${runs[$preset|$seed|$mode|dynamic]:-}; s=${runs[$preset|$seed|$mode|static]:-}
      ad=null; as=null; p=null; r=null; f=null
      [[ -n "$d" ]] && { ad=$(json_get "$d/stats.json" .evaluation.ate_rmse_m); p=$(json_get "$d/stats.json" .mask_accuracy.precision); r=$(json_get "$d/stats.json" .mask_accuracy.recall); }
      [[ -n "$s" ]] && { as=$(json_get "$s/stats.json" .evaluation.ate_rmse_m); f=$(json_get "$s/stats.json" .mask_accuracy.dynamic_fraction); }
      echo "| $preset | $mode | $seed | $(mm "$ad") | $(mm "$as") | $(ratio "$ad" "$as") | $(dec "$p") | $(dec "$r") | $(pct "$f") |"
    done
  done
done
echo
echo "### Median over seeds ${seed_list[*]} per mover"
echo
echo "| preset | mode | mover | recall | precision |"
echo "|---|---|---|---|---|"
for key in $(printf '%s\n' "${!recalls[@]}" | sort); do
  IFS='|' read -r preset mode mover <<< "$key"
  read -r -a rs <<< "${recalls[$key]}"; read -r -a ps <<< "${precisions[$key]}"
  echo "| $preset | $mode | $mover | $(dec "$(median "${rs[@]}")") | $(dec "$(median "${ps[@]}")") |"
done
elapsed=$((SECONDS - start_all))
log "done: $failures failed, $((elapsed / 60)) min $((elapsed % 60)) s; outputs in $out"
((failures == 0))
