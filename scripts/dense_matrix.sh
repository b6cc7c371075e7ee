#!/usr/bin/env bash
# The dense static map on synthetic truth (issue 43): per preset and seed, `run --dense` in each mode on the dynamic
# sequence and in mode none on its static twin (same room and camera path, --no-movers), each mesh scored by
# `amos-slam eval-mesh` at each tolerance against the sequence's true static surface and the movers' swept volume:
# accuracy (median, 90 %), completeness, ghosts (vertices off the static surface inside the swept volume: remains
# of people and objects) and vertices off the static surface anywhere. The twin has no movers: it is scored against
# its moving sibling's swept volume (--swept), so both count the same place. People must leave ghosts in none,
# close to none in full, and the twin is the reference.
#   bash scripts/dense_matrix.sh [--seeds "1 2 3 4 5"] [--presets "walking_xyz walking_halfsphere walking_static
#                                objects_xyz"] [--modes "full none"] [--frames 150] [--tolerances "0.02 0.04"]
#                                [--reuse-runs] [--no-twins] [--bin build/bin/amos-slam] [--out out/dense]
#                                [--config configs/tum3.yaml]
# The tables (markdown, one per tolerance) go to stdout, progress to stderr. Sequences are cached in
# OUT/sequences/, runs go to OUT/runs/ with their logs and OUT/runs/MODE/NAME/mesh_eval_TOLERANCE.json.
# --reuse-runs keeps finished runs and scores of OUT (to score again, or to gather presets run one at a time).
# --no-twins leaves the static twins out (half the runs, when only the dynamic sequences' figures are wanted).
# Exit status 1 when any job failed.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seeds="1 2 3 4 5"
presets="walking_xyz walking_halfsphere walking_static objects_xyz"
modes="full none"
frames=150
tolerances="0.02 0.04"
reuse=0
twins=1
bin="$root/build/bin/amos-slam"
out="$root/out/dense"
config="$root/configs/tum3.yaml"

# shellcheck source=scripts/synth_lib.sh
source "$root/scripts/synth_lib.sh"
usage() { sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; }
while (($#)); do
  case "$1" in
    --tolerances) tolerances=${2:?--tolerances needs a value}; shift 2 ;;
    --reuse-runs) reuse=1; shift ;;
    --no-twins) twins=0; shift ;;
    -h | --help) usage; exit 0 ;;
    *) common_option "$1" "${2-}" || { echo "error: unknown argument '$1' (see --help)" >&2; exit 2; }; shift 2 ;;
  esac
done
check_common_options  # also fills preset_list and mode_list
read -r -a tolerance_list <<< "$tolerances"
for t in "${tolerance_list[@]}"; do
  [[ "$t" =~ ^0?\.[0-9]+$ ]] || { echo "error: tolerance '$t' is not a distance in metres below 1" >&2; exit 2; }
done
mkdir -p "$out/sequences" "$out/runs"
cd "$root"
failures=0

# dense_run SEQUENCE_DIR MODE NAME SWEPT -> runs (unless reused) and scores the mesh at every tolerance against
# SWEPT ("" = the sequence's own swept volume); prints per tolerance "tolerance accuracy_median p90 completeness
# ghost_share off_surface_share ghosts ate seen_through_share" (nothing on failure).
dense_run() {
  local seq=$1 mode=$2 dir="$out/runs/$2/$3" swept=$4 t0=$SECONDS tol json extra=()
  [[ -n "$swept" ]] && extra=(--swept "$swept")
  if ((reuse)) && [[ -f "$dir/.complete" ]]; then
    log "run $3 --mode $mode: reused"
  else
    rm -rf "$dir"; mkdir -p "$(dirname "$dir")"
    if ! "$bin" run --sequence "$seq" --config "$config" --output "$dir" --mode "$mode" --deterministic --dense \
        > "$dir.log" 2>&1; then
      log "run $3 --mode $mode FAILED (log: $dir.log)"; tail -3 "$dir.log" >&2; return 1
    fi
    touch "$dir/.complete"
    log "run $3 --mode $mode --dense done in $((SECONDS - t0)) s"
  fi
  for tol in "${tolerance_list[@]}"; do
    json="$dir/mesh_eval_$tol.json"
    if ! { ((reuse)) && [[ -f "$json" ]]; }; then
      if ! "$bin" eval-mesh --mesh "$dir/mesh.ply" --sequence "$seq" --tolerance "$tol" --output "$json" \
          "${extra[@]}" >> "$dir.log" 2>&1; then
        log "eval-mesh $3 --mode $mode --tolerance $tol FAILED (log: $dir.log)"; tail -3 "$dir.log" >&2; return 1
      fi
    fi
    python3 - "$json" "$tol" << 'PY'
import json, sys
e = json.load(open(sys.argv[1]))
print(sys.argv[2], e["accuracy_median_m"], e["accuracy_p90_m"], e["completeness"], e["ghost_share"],
      e["off_surface_share"], e["ghosts"], e["ate_rmse_m"], e.get("seen_through", {}).get("seen_through_share", "nan"))
PY
  done
}

declare -A acc p90 comp ghost off ate through rows
for preset in "${preset_list[@]}"; do
  for seed in "${seed_list[@]}"; do
    cases=() seq=""
    if seq=$(render "$preset" "$seed" 0); then
      for mode in "${mode_list[@]}"; do cases+=("$mode|$seq|$mode|"); done
    else failures=$((failures + 1)); fi
    # The twin is scored against its moving sibling's swept volume (its own is empty).
    if ((!twins)); then :
    elif [[ -n "$seq" ]] && twin=$(render "$preset" "$seed" 1); then
      cases+=("twin none|$twin|none|$seq/swept_volume.ply")
    else failures=$((failures + 1)); fi
    for c in "${cases[@]}"; do
      IFS='|' read -r label dir mode swept <<< "$c"
      if ! r=$(dense_run "$dir" "$mode" "$(basename "$dir")" "$swept") || [[ -z "$r" ]]; then
        failures=$((failures + 1))
        for tol in "${tolerance_list[@]}"; do rows[$tol]+="| $preset | $label | $seed | fail | | | | | | |"$'\n'; done
        continue
      fi
      while read -r tol a p c9 g o n e st; do
        k="$tol|$preset|$label"
        acc[$k]+="$a "; p90[$k]+="$p "; comp[$k]+="$c9 "; ghost[$k]+="$g "; off[$k]+="$o "; ate[$k]+="$e "
        through[$k]+="$st "
        rows[$tol]+="| $preset | $label | $seed | $(mm "$a") | $(mm "$p") | $(dec "$c9") | $(pct "$g") | $n | $(pct "$o") | $(pct "$st") | $(mm "$e") |"$'\n'
      done <<< "$r"
    done
  done
done

for tol in "${tolerance_list[@]}"; do
  echo "## Dense static map on synthetic truth at $(cm "$tol") cm: seeds ${seed_list[*]}, $frames frames, $(basename "$config"), --deterministic"
  echo
  echo "| preset | run | seed | accuracy median (mm) | accuracy p90 (mm) | completeness | ghosts in swept volume (%) | ghost vertices | off the static surface (%) | seen through (%) | ATE (mm) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s' "${rows[$tol]:-}"
  echo
  echo "### Mean over the seeds, tolerance $(cm "$tol") cm"
  echo
  echo "| preset | run | accuracy median (mm) | accuracy p90 (mm) | completeness | ghosts in swept volume (%) | off the static surface (%) | seen through (%) | ATE (mm) |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for preset in "${preset_list[@]}"; do
    for label in "${mode_list[@]}" "twin none"; do
      k="$tol|$preset|$label"
      # shellcheck disable=SC2086
      echo "| $preset | $label | $(mm "$(mean ${acc[$k]:-})") | $(mm "$(mean ${p90[$k]:-})") | $(dec "$(mean ${comp[$k]:-})") | $(pct "$(mean ${ghost[$k]:-})") | $(pct "$(mean ${off[$k]:-})") | $(pct "$(mean ${through[$k]:-})") | $(mm "$(mean ${ate[$k]:-})") |"
    done
  done
  echo
done
((failures == 0)) || { log "$failures job(s) failed"; exit 1; }
