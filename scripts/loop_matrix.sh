#!/usr/bin/env bash
# Loop closing on synthetic sequences (issue 15): does every room lap close its loop, how accurate is it then, and is
# a loop ever closed where there is none?
#   bash scripts/loop_matrix.sh [--seeds "1 2 3 4 5 6 7 8 9 10"] [--frames 600] [--bin build/bin/amos-slam]
#                               [--out out/loops] [--config configs/tum3.yaml]
# Tables (markdown) go to stdout, progress to stderr:
#   1. static_loop (a 20 s room lap at 600 frames), --mode none: loops closed, ATE RMSE, keyframes;
#   2. sequences without a loop, 300 frames: static_xyz (--mode none) and walking_xyz (--mode full): loops closed.
# Every run is --deterministic. Rendered sequences are cached in OUT/sequences/; runs go to OUT/runs/ with their
# logs beside them. Exit status 1 when any job failed (the tables are still printed, failed cells say "fail").
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seeds="1 2 3 4 5 6 7 8 9 10"
frames=600
bin="$root/build/bin/amos-slam"
out="$root/out/loops"
config="$root/configs/tum3.yaml"

# shellcheck source=scripts/synth_lib.sh
source "$root/scripts/synth_lib.sh"  # options, log, json_get, render, formatting
parse_common_options 2,10 "$@"
loop_frames=$frames
mkdir -p "$out/sequences" "$out/runs"
cd "$root"

failures=0
declare -A result  # result[key|field]: loops, ate, keyframes ("fail" when the job failed)

fail_job() {  # KEY: its cells say "fail"
  for f in loops ate keyframes; do result[$1|$f]=fail; done
  failures=$((failures + 1))
}

# run KEY PRESET SEED FRAMES MODE
run() {
  local key=$1 preset=$2 seed=$3 mode=$5 seq dir
  frames=$4  # render() reads it
  dir="$out/runs/$key"
  if ! seq=$(render "$preset" "$seed" 0); then fail_job "$key"; return 0; fi
  rm -rf "$dir"
  log "run $key --mode $mode ..."
  if ! "$bin" run --sequence "$seq" --config "$config" --output "$dir" --mode "$mode" --deterministic \
      > "$dir.log" 2>&1 || [[ ! -f "$dir/stats.json" ]]; then
    log "run $key FAILED (log: $dir.log)"; tail -3 "$dir.log" >&2
    fail_job "$key"; return 0
  fi
  result[$key|loops]=$(json_get "$dir/stats.json" .mapping.loops_closed)
  result[$key|ate]=$(json_get "$dir/stats.json" .evaluation.ate_rmse_m)
  result[$key|keyframes]=$(json_get "$dir/stats.json" .keyframes)
  log "run $key: ${result[$key|loops]} loops, ATE ${result[$key|ate]} m"
}

log "loop matrix: seeds ${seed_list[*]}, laps of $loop_frames frames, binary $bin, config $config, out $out"
for seed in "${seed_list[@]}"; do
  run "static_loop_s$seed" static_loop "$seed" "$loop_frames" none
  run "static_xyz_s$seed" static_xyz "$seed" 300 none
  run "walking_xyz_s$seed" walking_xyz "$seed" 300 full
done

echo "## Loop matrix: seeds ${seed_list[*]}, $(basename "$config"), --deterministic"
echo
echo "### static_loop ($loop_frames frames), --mode none"
echo
echo "| seed | loops closed | ATE (mm) | keyframes |"
echo "|---|---|---|---|"
closed=0; under=0; ates=()
for seed in "${seed_list[@]}"; do
  k="static_loop_s$seed"
  echo "| $seed | ${result[$k|loops]} | $(mm "${result[$k|ate]}") | ${result[$k|keyframes]} |"
  num "${result[$k|loops]}" && ((result[$k|loops] > 0)) && closed=$((closed + 1))
  num "${result[$k|ate]}" && awk -v a="${result[$k|ate]}" 'BEGIN { exit !(a < 0.01) }' && under=$((under + 1))
  ates+=("${result[$k|ate]}")
done
echo
echo "Closed: $closed of ${#seed_list[@]}; ATE under 1 cm: $under of ${#seed_list[@]}; median ATE $(mm "$(median "${ates[@]}")") mm."
echo
echo "### Sequences without a loop (300 frames): loops closed"
echo
echo "| seed | static_xyz (none) | walking_xyz (full) |"
echo "|---|---|---|"
false_loops=0
for seed in "${seed_list[@]}"; do
  a=${result[static_xyz_s$seed|loops]}; b=${result[walking_xyz_s$seed|loops]}
  echo "| $seed | $a | $b |"
  for v in "$a" "$b"; do num "$v" && ((v > 0)) && false_loops=$((false_loops + v)); done
done
echo
echo "Loops closed where there is none: $false_loops."
((failures == 0)) || { log "$failures job(s) failed"; exit 1; }
