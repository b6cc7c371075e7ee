#!/usr/bin/env bash
# Where the per-frame pose scatter comes from (issue 42): synthetic sequences rendered with one sensor effect at a
# time against exact truth, run with --deterministic --mode full; per preset and effect set the median over the
# seeds of the ATE RMSE and of the RPE over one frame (stats.json evaluation.jitter.rpe1_trans_rmse_m), and the
# share of the 'all' set's excess over 'exact' that each effect alone accounts for.
#   bash scripts/sensor_effects_matrix.sh [--seeds "1 2 3 4 5"] [--frames 300] [--bin build/bin/amos-slam]
#                                         [--out out/sensor_effects] [--config configs/tum3.yaml]
#                                         [--presets "static_xyz static_rpy walking_xyz walking_halfsphere"]
#                                         [--effects "exact depth_noise time_offset rolling_shutter all"]
#                                         [--offset-ms 10] [--readout-ms 25]
# Effect sets (amos-slam synth flags):
#   exact            --exact: no depth noise, no colour noise, global shutter, depth at the colour time
#   depth_noise      --no-color-noise: depth noise sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2 and holes only
#   time_offset      --exact --depth-time-offset-ms OFFSET: depth taken OFFSET ms after the colour
#   rolling_shutter  --exact --rolling-shutter-ms READOUT: colour rows read out over READOUT ms
#   all              depth noise, colour noise, the time offset and the rolling shutter together
#   also available: color_noise (--no-depth-noise), disparity (--exact --disparity-quantisation),
#   motion_blur (--exact --motion-blur)
# share = (median of the set - median of exact) / (median of all - median of exact), per figure; the shares need
# not add up to 100 % (colour noise and the effects' interplay make the rest).
# Tables (markdown) go to stdout, progress to stderr. Sequences are cached in OUT/sequences/ (reused when their
# render finished, i.e. their .complete marker exists); runs go to OUT/runs/ with their logs. One job at a time.
# Exit status 1 when any job failed (the tables are still printed, the failed cells say "fail").
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seeds="1 2 3 4 5"
frames=300
bin="$root/build/bin/amos-slam"
out="$root/out/sensor_effects"
config="$root/configs/tum3.yaml"
presets="static_xyz static_rpy walking_xyz walking_halfsphere"
effects="exact depth_noise time_offset rolling_shutter all"
offset_ms=10
readout_ms=25

# shellcheck source=scripts/synth_lib.sh
source "$root/scripts/synth_lib.sh"  # options, log, json_get, formatting, median
usage() { sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; }
while (($#)); do
  case "$1" in
    --effects) effects=${2:?--effects needs a value}; shift 2 ;;
    --offset-ms) offset_ms=${2:?--offset-ms needs a value}; shift 2 ;;
    --readout-ms) readout_ms=${2:?--readout-ms needs a value}; shift 2 ;;
    -h | --help) usage; exit 0 ;;
    *) common_option "$1" "${2-}" || { echo "error: unknown argument '$1' (see --help)" >&2; exit 2; }; shift 2 ;;
  esac
done
check_common_options  # also fills preset_list
read -r -a effect_list <<< "$effects"
((${#effect_list[@]})) || { echo "error: empty --effects" >&2; exit 2; }
num "$offset_ms" || { echo "error: --offset-ms must be a number, got '$offset_ms'" >&2; exit 2; }
num "$readout_ms" || { echo "error: --readout-ms must be a number, got '$readout_ms'" >&2; exit 2; }

# effect_flags SET -> the synth flags of an effect set (one per line); effect_tag SET -> its cache-name part
effect_flags() {
  case "$1" in
    exact) printf '%s\n' --exact ;;
    depth_noise) printf '%s\n' --no-color-noise ;;
    color_noise) printf '%s\n' --no-depth-noise ;;
    time_offset) printf '%s\n' --exact --depth-time-offset-ms "$offset_ms" ;;
    rolling_shutter) printf '%s\n' --exact --rolling-shutter-ms "$readout_ms" ;;
    disparity) printf '%s\n' --exact --disparity-quantisation ;;
    motion_blur) printf '%s\n' --exact --motion-blur ;;
    all) printf '%s\n' --depth-time-offset-ms "$offset_ms" --rolling-shutter-ms "$readout_ms" ;;
    *) return 1 ;;
  esac
}
effect_tag() {
  case "$1" in
    time_offset) printf 'offset%sms' "$offset_ms" ;;
    rolling_shutter) printf 'rs%sms' "$readout_ms" ;;
    all) printf 'all_offset%sms_rs%sms' "$offset_ms" "$readout_ms" ;;
    *) printf '%s' "$1" ;;
  esac
}
for e in "${effect_list[@]}"; do effect_flags "$e" > /dev/null || { echo "error: unknown effect set '$e'" >&2; exit 2; }; done

mkdir -p "$out/sequences" "$out/runs"
cd "$root"

# render_effect PRESET SEED SET -> prints the sequence folder; returns 1 on failure (cached as synth_lib's render)
render_effect() {
  local preset=$1 seed=$2 set=$3 flags
  mapfile -t flags < <(effect_flags "$set")
  render_named "${preset}_s${seed}_f${frames}_$(effect_tag "$set")" "$preset" "$seed" "${flags[@]}"
}

total_jobs=$((${#seed_list[@]} * ${#preset_list[@]} * ${#effect_list[@]}))
job=0
failures=0
start_all=$SECONDS
declare -A result  # result[preset|set|seed|field] = value, "fail" when the job failed

run_one() {  # PRESET SET SEED SEQUENCE_DIR
  local key="$1|$2|$3" seq=$4 dir t0=$SECONDS
  job=$((job + 1))
  dir="$out/runs/$1_s$3_$(effect_tag "$2")"
  rm -rf "$dir"
  log "run $job/$total_jobs: $1 seed $3 $2 ..."
  if ! "$bin" run --sequence "$seq" --config "$config" --output "$dir" --mode full --deterministic \
      > "$dir.log" 2>&1 || [[ ! -f "$dir/stats.json" ]]; then
    log "run $1 seed $3 $2 FAILED (log: $dir.log):"; tail -3 "$dir.log" >&2
    for f in ate rpe1 step; do result[$key|$f]=fail; done
    failures=$((failures + 1))
    return 0
  fi
  result[$key|ate]=$(json_get "$dir/stats.json" .evaluation.ate_rmse_m)
  result[$key|rpe1]=$(json_get "$dir/stats.json" .evaluation.jitter.rpe1_trans_rmse_m)
  result[$key|step]=$(json_get "$dir/stats.json" .evaluation.jitter.gt_step_median_m)
  [[ ${result[$key|ate]} == null ]] && failures=$((failures + 1))
  log "run $1 seed $3 $2 done in $((SECONDS - t0)) s: ATE ${result[$key|ate]} m, RPE1 ${result[$key|rpe1]} m"
}

log "sensor effects matrix: presets ${preset_list[*]}, effects ${effect_list[*]}, seeds ${seed_list[*]}," \
    "$frames frames, offset $offset_ms ms, readout $readout_ms ms, binary $bin, config $config, out $out"
for seed in "${seed_list[@]}"; do
  for preset in "${preset_list[@]}"; do
    for set in "${effect_list[@]}"; do
      if seq=$(render_effect "$preset" "$seed" "$set"); then
        run_one "$preset" "$set" "$seed" "$seq"
      else
        job=$((job + 1))
        for f in ate rpe1 step; do result[$preset|$set|$seed|$f]=fail; done
        failures=$((failures + 1))
      fi
    done
  done
done

# med PRESET SET FIELD -> median over the seeds; share VALUE EXACT ALL -> percent of all's excess over exact
med() {
  local vs=() s
  for s in "${seed_list[@]}"; do vs+=("${result[$1|$2|$s|$3]}"); done
  median "${vs[@]}"
}
share() {
  if num "$1" && num "$2" && num "$3"; then
    awk -v v="$1" -v e="$2" -v a="$3" 'BEGIN { if (a - e > 0) printf "%.0f %%", 100 * (v - e) / (a - e); else printf "n/a" }'
  else printf 'n/a'; fi
}
has_set() { local e; for e in "${effect_list[@]}"; do [[ $e == "$1" ]] && return 0; done; return 1; }

echo "## Sensor effects matrix: seeds ${seed_list[*]}, $frames frames, $(basename "$config"), --mode full --deterministic"
echo
echo "Time offset $offset_ms ms (depth after colour), rolling-shutter readout $readout_ms ms. Medians over the seeds;"
echo "share = (set - exact) / (all - exact)."
echo
echo "| preset | effects | ATE (mm) | share of all's ATE | RPE 1 frame rmse (mm) | share of all's RPE 1 frame | true step (mm) |"
echo "|---|---|---|---|---|---|---|"
for preset in "${preset_list[@]}"; do
  ate_exact=null; ate_all=null; rpe_exact=null; rpe_all=null
  if has_set exact; then ate_exact=$(med "$preset" exact ate); rpe_exact=$(med "$preset" exact rpe1); fi
  if has_set all; then ate_all=$(med "$preset" all ate); rpe_all=$(med "$preset" all rpe1); fi
  for set in "${effect_list[@]}"; do
    a=$(med "$preset" "$set" ate); r=$(med "$preset" "$set" rpe1)
    echo "| $preset | $set | $(mm "$a") | $(share "$a" "$ate_exact" "$ate_all") | $(mm "$r") |" \
         "$(share "$r" "$rpe_exact" "$rpe_all") | $(mm "$(med "$preset" "$set" step)") |"
  done
done
echo
echo "### Per seed: ATE / RPE 1 frame rmse (mm)"
echo
printf '| preset | seed |'; for set in "${effect_list[@]}"; do printf ' %s |' "$set"; done; echo
printf '|---|---|'; for set in "${effect_list[@]}"; do printf -- '---|'; done; echo
for preset in "${preset_list[@]}"; do
  for seed in "${seed_list[@]}"; do
    printf '| %s | %s |' "$preset" "$seed"
    for set in "${effect_list[@]}"; do
      printf ' %s / %s |' "$(mm "${result[$preset|$set|$seed|ate]}")" "$(mm "${result[$preset|$set|$seed|rpe1]}")"
    done
    echo
  done
done
echo
elapsed=$((SECONDS - start_all))
log "done: $job runs, $failures failed, $((elapsed / 60)) min $((elapsed % 60)) s; outputs in $out"
((failures == 0))
