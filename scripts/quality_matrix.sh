#!/usr/bin/env bash
# Quality matrix on synthetic sequences: how much the movers cost, how well the geometric stage finds a mover no
# detector knows, and how much of a static scene is wrongly marked dynamic.
#   bash scripts/quality_matrix.sh [--seeds "1 2 3 4 5"] [--frames 300] [--bin build/bin/amos-slam]
#                                  [--out out/quality] [--config configs/tum3.yaml]
# Tables (markdown) go to stdout, progress to stderr:
#   1. walking_xyz / walking_static / walking_rpy / walking_halfsphere, --mode full: ATE of the dynamic sequence,
#      ATE of its static twin (same preset and seed, --no-movers), their ratio; per preset whether every seed is
#      within 1.5x.
#   2. box_push, --mode geometry: mover-pixel recall and precision (mask_accuracy in stats.json), ATE.
#   3. the static twins of table 1 (--mode full): percentage of pixels marked dynamic.
# Rendered sequences are cached in OUT/sequences/ (a sequence is reused when its render finished, i.e. its
# .complete marker exists); every run is redone, into OUT/runs/, with its log beside it. One job at a time.
# Paths given on the command line are relative to the current folder; the defaults to the checkout. Runs are
# started from the checkout, so the bundled ./models are found. Exit status 1 when any job failed (the tables are
# still printed, the failed cells say "fail").
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seeds="1 2 3 4 5"
frames=300
bin="$root/build/bin/amos-slam"
out="$root/out/quality"
config="$root/configs/tum3.yaml"

# shellcheck source=scripts/synth_lib.sh
source "$root/scripts/synth_lib.sh"  # options, log, json_get, render, formatting
parse_common_options 2,16 "$@"

walking=(walking_xyz walking_static walking_rpy walking_halfsphere)
mkdir -p "$out/sequences" "$out/runs"
cd "$root"

n_seeds=${#seed_list[@]}
total_jobs=$((n_seeds * (2 * ${#walking[@]} + 1)))  # runs; renders are counted separately
job=0
failures=0
start_all=$SECONDS
declare -A result  # result[name|field] = value, "fail" when the job failed

# run KEY SEQUENCE_DIR MODE -> fills result[KEY|ate], [KEY|precision], [KEY|recall], [KEY|dynamic_fraction]
run() {
  local key=$1 seq=$2 mode=$3 dir t0=$SECONDS
  job=$((job + 1))
  dir="$out/runs/$mode/$key"
  rm -rf "$dir"; mkdir -p "$(dirname "$dir")"
  log "run $job/$total_jobs: $key --mode $mode ..."
  if ! "$bin" run --sequence "$seq" --config "$config" --output "$dir" --mode "$mode" --deterministic \
      > "$dir.log" 2>&1 || [[ ! -f "$dir/stats.json" ]]; then
    log "run $key --mode $mode FAILED (log: $dir.log):"; tail -3 "$dir.log" >&2
    for f in ate precision recall dynamic_fraction; do result[$key|$f]=fail; done
    failures=$((failures + 1))
    return 0
  fi
  result[$key|ate]=$(json_get "$dir/stats.json" .evaluation.ate_rmse_m)
  result[$key|precision]=$(json_get "$dir/stats.json" .mask_accuracy.precision)
  result[$key|recall]=$(json_get "$dir/stats.json" .mask_accuracy.recall)
  result[$key|dynamic_fraction]=$(json_get "$dir/stats.json" .mask_accuracy.dynamic_fraction)
  [[ ${result[$key|ate]} == null ]] && failures=$((failures + 1))
  log "run $key --mode $mode done in $((SECONDS - t0)) s: ATE ${result[$key|ate]} m," \
      "mask precision ${result[$key|precision]} recall ${result[$key|recall]} marked ${result[$key|dynamic_fraction]}"
}

fail_run() {  # KEY: a run that could not start because its render failed
  job=$((job + 1))
  for f in ate precision recall dynamic_fraction; do result[$1|$f]=fail; done
  failures=$((failures + 1))
}

log "quality matrix: seeds ${seed_list[*]}, $frames frames, binary $bin, config $config, out $out"
for seed in "${seed_list[@]}"; do
  for preset in "${walking[@]}"; do
    for static in 0 1; do
      key="${preset}_s${seed}"; ((static)) && key+="_nomovers"
      if seq=$(render "$preset" "$seed" "$static"); then run "$key" "$seq" full; else fail_run "$key"; fi
    done
  done
  key="box_push_s${seed}"
  if seq=$(render box_push "$seed" 0); then run "$key" "$seq" geometry; else fail_run "$key"; fi
done

echo "## Quality matrix: seeds ${seed_list[*]}, $frames frames, $(basename "$config"), --deterministic"
echo
echo "### Walking presets, --mode full: ATE RMSE of the dynamic sequence vs its static twin (--no-movers)"
echo
echo "| preset | seed | ATE dynamic (mm) | ATE static twin (mm) | ratio |"
echo "|---|---|---|---|---|"
declare -A within
for preset in "${walking[@]}"; do
  ok=0
  for seed in "${seed_list[@]}"; do
    d=${result[${preset}_s${seed}|ate]}; s=${result[${preset}_s${seed}_nomovers|ate]}; r=$(ratio "$d" "$s")
    echo "| $preset | $seed | $(mm "$d") | $(mm "$s") | $r |"
    [[ $r != n/a ]] && awk -v r="$r" 'BEGIN { exit !(r <= 1.5) }' && ok=$((ok + 1))
  done
  within[$preset]=$ok
done
echo
echo "| preset | seeds within 1.5x | all within 1.5x | mean ATE dynamic (mm) | mean ATE static twin (mm) |"
echo "|---|---|---|---|---|"
for preset in "${walking[@]}"; do
  ds=(); ss=()
  for seed in "${seed_list[@]}"; do ds+=("${result[${preset}_s${seed}|ate]}"); ss+=("${result[${preset}_s${seed}_nomovers|ate]}"); done
  all=no; ((within[$preset] == n_seeds)) && all=yes
  echo "| $preset | ${within[$preset]}/$n_seeds | $all | $(mm "$(mean "${ds[@]}")") | $(mm "$(mean "${ss[@]}")") |"
done
echo
echo "### box_push, --mode geometry: mover pixels found by the geometric stage"
echo
echo "| seed | recall | precision | ATE (mm) |"
echo "|---|---|---|---|"
rs=(); ps=(); as=()
for seed in "${seed_list[@]}"; do
  k="box_push_s${seed}"
  echo "| $seed | $(dec "${result[$k|recall]}") | $(dec "${result[$k|precision]}") | $(mm "${result[$k|ate]}") |"
  rs+=("${result[$k|recall]}"); ps+=("${result[$k|precision]}"); as+=("${result[$k|ate]}")
done
echo "| mean | $(dec "$(mean "${rs[@]}")") | $(dec "$(mean "${ps[@]}")") | $(mm "$(mean "${as[@]}")") |"
echo
echo "### Static twins (--no-movers), --mode full: pixels marked dynamic (%)"
echo
printf '| seed |'; for preset in "${walking[@]}"; do printf ' %s --no-movers |' "$preset"; done; echo
printf '|---|'; for preset in "${walking[@]}"; do printf -- '---|'; done; echo
for seed in "${seed_list[@]}"; do
  printf '| %s |' "$seed"
  for preset in "${walking[@]}"; do printf ' %s |' "$(pct "${result[${preset}_s${seed}_nomovers|dynamic_fraction]}")"; done
  echo
done
printf '| mean |'
for preset in "${walking[@]}"; do
  fs=(); for seed in "${seed_list[@]}"; do fs+=("${result[${preset}_s${seed}_nomovers|dynamic_fraction]}"); done
  printf ' %s |' "$(pct "$(mean "${fs[@]}")")"
done
echo
echo
elapsed=$((SECONDS - start_all))
log "done: $job runs, $failures failed, $((elapsed / 60)) min $((elapsed % 60)) s; outputs in $out"
((failures == 0))
