#!/usr/bin/env bash
# Maps that last (issue 15): a map saved by one run, localised in by another.
#   bash scripts/maps_check.sh [--seeds "1 2 3"] [--frames 300] [--bin build/bin/amos-slam] [--out out/maps]
#                              [--config configs/tum3.yaml]
#   1. Bonn crowd dev slice (configs/bonn.yaml, --mode full): the first half mapped and saved, the second half
#      localised in it (--load-map --localize) from a cold start: frames localised, ATE over them;
#   2. per seed: static_loop (600 frames, --mode none) mapped and saved, walking_loop (people walking, first --frames
#      frames, --mode full) localised in it: frames localised, ATE; the map's keyframes, file size, save and
#      load times;
#   3. per seed: covered_halfsphere (lens covered, black and no depth, from 5 to 7 s = frames 150-209, while the
#      camera moves on; --mode full): frames lost beyond the covered ones (= frames until relocalised) and ATE.
# Every run is --deterministic. Tables (markdown) go to stdout, progress to stderr. Sequences are cached in
# OUT/sequences/, runs go to OUT/runs/ with their logs. Exit status 1 when any job failed.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seeds="1 2 3"
frames=300
bin="$root/build/bin/amos-slam"
out="$root/out/maps"
config="$root/configs/tum3.yaml"

# shellcheck source=scripts/synth_lib.sh
source "$root/scripts/synth_lib.sh"  # options, log, json_get, render, formatting (mm, cm)
parse_common_options 2,13 "$@"
walk_frames=$frames  # --frames: the walking_loop frames localised
mkdir -p "$out/sequences" "$out/runs"
cd "$root"
failures=0
covered_frames=60  # covered_halfsphere: frames 150-209 (synth/presets.cc)

# slam KEY ARGS...: one deterministic run into OUT/runs/KEY; returns 1 (and counts a failure) when it failed.
slam() {
  local key=$1
  shift
  local dir="$out/runs/$key"
  rm -rf "$dir"
  log "run $key ..."
  if ! "$bin" run --output "$dir" --deterministic "$@" > "$dir.log" 2>&1 || [[ ! -f "$dir/stats.json" ]]; then
    log "run $key FAILED (log: $dir.log)"; tail -3 "$dir.log" >&2
    failures=$((failures + 1)); return 1
  fi
}
field() { json_get "$out/runs/$1/stats.json" "$2"; }
# save_ms / load_ms KEY: the map save / load time that run KEY logged ("... in N ms" / "loaded in N ms").
save_ms() { grep -o 'map saved to .* in [0-9]* ms' "$out/runs/$1.log" | grep -o '[0-9]* ms$' | tr -d ' ms' || echo "-"; }
load_ms() { grep -o 'map points, loaded in [0-9]* ms' "$out/runs/$1.log" | grep -o '[0-9]*' | head -1 || echo "-"; }
# tracked_ate_mm KEY SEQ: ATE RMSE (mm) over the frames run KEY tracked. A lost frame repeats the last tracked pose
# in trajectory.txt (ORB-SLAM2's convention), so a line whose pose equals the line before it is left out.
tracked_ate_mm() {
  local dir="$out/runs/$1"
  awk '/^#/ { print; next } { k = $2 " " $3 " " $4 " " $5 " " $6 " " $7 " " $8; if (k != p) print; p = k }' \
    "$dir/trajectory.txt" > "$dir/tracked.txt"
  "$bin" eval --gt "$2/groundtruth.txt" --est "$dir/tracked.txt" 2> /dev/null |
    awk '/^ATE/ { printf "%.2f (%d frames)", $3 * 1000, $NF }'
}

echo "## Maps that last: --deterministic, binary $(basename "$bin")"
echo
echo "### Bonn crowd dev slice (--mode full, configs/bonn.yaml): frames 0-134 mapped, 135-269 localised"
echo
echo "| map keyframes | map points | frames localised | relocalised | ATE over them (cm) |"
echo "|---|---|---|---|---|"
bonn="$root/../shared/data/bonn_crowd_dev"
bonn_cfg="$root/configs/bonn.yaml"
if slam bonn_map --sequence "$bonn" --config "$bonn_cfg" --mode full --max-frames 135 \
      --save-map "$out/runs/bonn_map.amap" &&
   slam bonn_localize --sequence "$bonn" --config "$bonn_cfg" --mode full --first-frame 135 \
      --load-map "$out/runs/bonn_map.amap" --localize; then
  echo "| $(field bonn_map .keyframes) | $(field bonn_map .map_points) |" \
       "$(field bonn_localize .evaluation.est_poses) of $(field bonn_localize .frames) |" \
       "$(field bonn_localize .relocalised) | $(cm "$(field bonn_localize .evaluation.ate_rmse_m)") |"
else
  echo "| fail | fail | fail | fail | fail |"
fi

echo
echo "### walking_loop (first $walk_frames frames, --mode full) localised in the map of static_loop (600 frames, --mode none)"
echo
echo "| seed | map keyframes | map file (MB) | saved in (ms) | loaded in (ms) | frames localised | ATE (mm) |"
echo "|---|---|---|---|---|---|---|"
for seed in "${seed_list[@]}"; do
  frames=600
  lap=$(render static_loop "$seed" 0) || { failures=$((failures + 1)); echo "| $seed | fail | | | | | |"; continue; }
  frames=$walk_frames
  walk=$(render walking_loop "$seed" 0) || { failures=$((failures + 1)); echo "| $seed | fail | | | | | |"; continue; }
  map="$out/runs/static_loop_s$seed.amap"
  if slam "static_loop_s$seed" --sequence "$lap" --config "$config" --mode none --save-map "$map" &&
     slam "walking_loop_s$seed" --sequence "$walk" --config "$config" --mode full --load-map "$map" --localize; then
    size=$(awk -v b="$(wc -c < "$map")" 'BEGIN { printf "%.1f", b / 1e6 }')
    echo "| $seed | $(field "static_loop_s$seed" .keyframes) | $size | $(save_ms "static_loop_s$seed") |" \
         "$(load_ms "walking_loop_s$seed") |" \
         "$(field "walking_loop_s$seed" .evaluation.est_poses) of $(field "walking_loop_s$seed" .frames) |" \
         "$(mm "$(field "walking_loop_s$seed" .evaluation.ate_rmse_m)") |"
  else
    echo "| $seed | fail | | | | | |"
  fi
done

echo
echo "### covered_halfsphere (--mode full): the lens covered for $covered_frames frames while the camera moves on"
echo
echo "| seed | frames lost | lost beyond the covered ones | relocalised | ATE over the tracked frames (mm) |"
echo "|---|---|---|---|---|"
frames=360
for seed in "${seed_list[@]}"; do
  seq=$(render covered_halfsphere "$seed" 0) || { failures=$((failures + 1)); echo "| $seed | fail | | | |"; continue; }
  if slam "covered_halfsphere_s$seed" --sequence "$seq" --config "$config" --mode full; then
    lost=$(field "covered_halfsphere_s$seed" .lost)
    echo "| $seed | $lost | $((lost - covered_frames)) | $(field "covered_halfsphere_s$seed" .relocalised) |" \
         "$(tracked_ate_mm "covered_halfsphere_s$seed" "$seq") |"
  else
    echo "| $seed | fail | | | |"
  fi
done
((failures == 0)) || { log "$failures job(s) failed"; exit 1; }
