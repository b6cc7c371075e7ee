#!/usr/bin/env bash
# The README's headline table, measured: runs the measurements below and rewrites the table between the lines
# "<!-- headline:begin -->" and "<!-- headline:end -->" of README.md (nothing else), so that the table is
# regenerated, never edited by hand.
#   bash scripts/headline_results.sh [--runs 3] [--out out/headline] [--print]
#   --runs N   runs per Bonn variant and per fr2 speed run (the table gives medians; default 3)
#   --out DIR  where the runs, logs and rendered sequences go (default out/headline)
#   --print    print the table on stdout instead of writing it into README.md
# Rows (build first: bash scripts/build.sh):
#   TUM fr2/desk, first 50 frames, --mode none, configs/tum2.yaml: ATE of a --deterministic run, fps the median
#     of N normal runs
#   Bonn crowd dev slice, none / full / full --realtime, configs/bonn.yaml: bash bench/bonn_speed.sh N
#     "none full realtime" (N interleaved rounds; ATE, lost frames, fps, CPU of full against none round by round,
#     dropped frames, latency p95)
#   synthetic walking_xyz (--mode full) and box_push (--mode geometry), seed 1, 300 frames, each with its static
#     twin (--no-movers, same mode), and static_loop (--mode none), seed 1, 600 frames; configs/tum3.yaml,
#     --deterministic: ATE, mask recall / precision, loops closed (as scripts/quality_matrix.sh and
#     scripts/loop_matrix.sh measure them)
# Needs tum_fr2_desk_first50 and bonn_crowd_dev in $AMOS_DATA_DIR (default ../shared/data), python3 or jq, and an
# otherwise idle machine (~15 min on 2 cores). When a measurement fails, README.md is left as it was, the table
# is printed with "fail" in that cell, and the exit status is 1.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
runs=3
out="$root/out/headline"
print=0
# shellcheck source=scripts/synth_lib.sh
source "$root/scripts/synth_lib.sh"  # abspath, log, json_get, render, median, mm, cm, dec
while (($#)); do
  case "$1" in
    -h | --help) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    --runs) runs=${2:?--runs needs a value}; shift 2 ;;
    --out) out=$(abspath "${2:?--out needs a value}"); shift 2 ;;
    --print) print=1; shift ;;
    *) echo "error: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "error: --runs must be a positive integer, got '$runs'" >&2; exit 2; }
cd "$root"
bin="$root/build/bin/amos-slam"
data="${AMOS_DATA_DIR:-../shared/data}"
fr2="$data/tum_fr2_desk_first50"
[[ -x "$bin" ]] || { echo "error: $bin not found; run bash scripts/build.sh first" >&2; exit 1; }
[[ -d "$fr2" ]] || { echo "error: $fr2 not found (set AMOS_DATA_DIR to the folder that holds it)" >&2; exit 1; }
for marker in '<!-- headline:begin -->' '<!-- headline:end -->'; do
  [[ $(grep -cxF "$marker" README.md) == 1 ]] || { echo "error: README.md needs the line '$marker' once" >&2; exit 1; }
done
mkdir -p "$out/sequences"

# run NAME ARGS...: amos-slam run ARGS into $out/NAME (log $out/NAME.log); prints stats.json's path, or "" when it
# failed (called in $(...): a failure shows as a "fail", "n/a" or "null" cell of the table, checked at the end).
run() {
  local name=$1 dir="$out/$1"
  shift
  rm -rf "$dir"
  log "run $name ..."
  if "$bin" run --output "$dir" "$@" > "$dir.log" 2>&1 && [[ -f "$dir/stats.json" ]]; then
    printf '%s\n' "$dir/stats.json"
  else
    log "run $name FAILED (log: $dir.log)"; tail -3 "$dir.log" >&2
    printf '\n'
  fi
}
get() { if [[ -n "$1" ]]; then json_get "$1" "$2"; else echo fail; fi; }  # get STATS .key
fps() { if num "$1"; then awk -v v="$1" 'BEGIN { printf "%.1f", v }'; else printf '%s' "$1"; fi; }
today=$(date -u +%F)

# TUM fr2/desk: ATE deterministic, fps of normal runs.
s=$(run fr2_deterministic --sequence "$fr2" --config configs/tum2.yaml --mode none --deterministic)
fr2_ate=$(get "$s" .evaluation.ate_rmse_m)
fr2_fps=()
for i in $(seq 1 "$runs"); do
  s=$(run "fr2_$i" --sequence "$fr2" --config configs/tum2.yaml --mode none)
  fr2_fps+=("$(get "$s" .fps)")
done

# Bonn: bench/bonn_speed.sh's own table (| variant | fps | CPU | ATE cm | lost | dropped % | latency median / p95 |).
log "bench/bonn_speed.sh $runs \"none full realtime\" ..."
bonn_table="$out/bonn_speed.md"
if ! AMOS_BENCH_OUT="$out/bonn" bash bench/bonn_speed.sh "$runs" "none full realtime" > "$bonn_table" 2> "$out/bonn_speed.log"; then
  log "bench/bonn_speed.sh FAILED (log: $out/bonn_speed.log)"; tail -3 "$out/bonn_speed.log" >&2
  : > "$bonn_table"
fi
bonn() {  # bonn VARIANT COLUMN(1 fps, 2 CPU, 3 ATE cm, 4 lost, 5 dropped %, 6 latency) -> the cell, or "fail"
  local v
  v=$(awk -F'|' -v name="$1" -v col="$2" '{ gsub(/ /, "", $2) } $2 == name { c = $(col + 2); sub(/^ +/, "", c); sub(/ +$/, "", c); print c; exit }' "$bonn_table")
  printf '%s' "${v:-fail}"
}
ratio_full=$(sed -n 's/^CPU full \/ none, round by round: .*(median \([0-9.]*\)x.*/\1/p' "$bonn_table")
p95=$(bonn realtime 6); p95=${p95##*/ }

# Synthetic, as the quality and loop matrices run them.
frames=300  # render() reads $frames, $bin and $out
synth() {  # synth PRESET STATIC(0|1) MODE -> stats.json path or ""
  local seq name=$1
  ((${2})) && name+="_twin"
  if ! seq=$(render "$1" 1 "$2"); then printf '\n'; return 0; fi
  run "$name" --sequence "$seq" --config configs/tum3.yaml --mode "$3" --deterministic
}
walk=$(synth walking_xyz 0 full); walk_twin=$(synth walking_xyz 1 full)
box=$(synth box_push 0 geometry); box_twin=$(synth box_push 1 geometry)
frames=600
loop=$(synth static_loop 0 none)
loops=$(get "$loop" .mapping.loops_closed)
loop_text="loop not closed"; [[ "$loops" =~ ^[1-9] ]] && loop_text="loop closed"; [[ "$loops" == fail ]] && loop_text=fail

by="\`scripts/headline_results.sh --runs $runs\`"
table=$(cat << EOF
| sequence | mode | ATE RMSE | frames per second | measured |
|---|---|---|---|---|
| TUM fr2/desk, first 50 frames | none | $(mm "$fr2_ate") mm (\`--deterministic\`) | $(fps "$(median "${fr2_fps[@]}")") | $today, $by, fps median of $runs |
| Bonn crowd, 270-frame slice | none | $(bonn none 3) cm | $(bonn none 1) | $today, $by (\`bench/bonn_speed.sh\`), medians of $runs |
| Bonn crowd, 270-frame slice | full | $(bonn full 3) cm, $(bonn full 4) lost (CPU ${ratio_full:-fail}x \`none\`) | $(bonn full 1) | same runs |
| Bonn crowd, 270-frame slice | full \`--realtime\` (30 Hz replay) | $(bonn realtime 3) cm; $(bonn realtime 5) % dropped, latency p95 $p95 ms | $(bonn realtime 1) processed | same runs |
| synthetic walking_xyz, 300 frames, seed 1 | full | $(mm "$(get "$walk" .evaluation.ate_rmse_m)") mm (static twin $(mm "$(get "$walk_twin" .evaluation.ate_rmse_m)") mm) | - | $today, $by (\`--deterministic\`, \`configs/tum3.yaml\`) |
| synthetic box_push, 300 frames, seed 1 | geometry | $(mm "$(get "$box" .evaluation.ate_rmse_m)") mm (static twin $(mm "$(get "$box_twin" .evaluation.ate_rmse_m)") mm); mover recall $(dec "$(get "$box" .mask_accuracy.recall)"), precision $(dec "$(get "$box" .mask_accuracy.precision)") | - | same |
| synthetic static_loop, 600 frames, seed 1 | none | $(mm "$(get "$loop" .evaluation.ate_rmse_m)") mm, $loop_text | - | same |
EOF
)

if grep -qwE 'fail|n/a|null' <<< "$table"; then
  printf '%s\n' "$table"
  log "a measurement failed (the cells that say fail, n/a or null; logs in $out): README.md not changed"
  exit 1
fi
if ((print)); then printf '%s\n' "$table"; exit 0; fi
printf '%s\n' "$table" > "$out/table.md"
awk -v table="$out/table.md" '
  $0 == "<!-- headline:begin -->" { print; while ((getline line < table) > 0) print line; skip = 1; next }
  $0 == "<!-- headline:end -->" { skip = 0 }
  !skip { print }' README.md > README.md.tmp
mv README.md.tmp README.md
log "README.md: headline table rewritten ($out/table.md)"
