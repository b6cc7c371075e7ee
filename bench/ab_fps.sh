#!/usr/bin/env bash
# Side-by-side speed of two builds: runs A and B in turn (A B A B ...) on the same sequence, so that a drifting
# machine affects both alike, and prints each run's fps (stats.json), the medians and the median of the per-pair
# ratios B/A; then a table of both builds' medians (bench/ab_table.py): fps, ATE, whole-process CPU per frame, peak
# memory and each pipeline thread's CPU per frame.
#   bash bench/ab_fps.sh BIN_A BIN_B [RUNS=5] [SEQUENCE=../shared/data/bonn_crowd_dev] [CONFIG=configs/bonn.yaml]
#                        [MODE=full] [-- EXTRA RUN FLAGS...]
# With CONFIG_B=FILE in the environment B's runs use that settings file instead of CONFIG, so the same binary given
# twice compares two settings (e.g. a key's cost: CONFIG_B=/tmp/fewer_features.yaml bash bench/ab_fps.sh BIN BIN 5).
# Run on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
a=${1:?BIN_A}; b=${2:?BIN_B}; runs=${3:-5}
seq=${4:-../shared/data/bonn_crowd_dev}; config=${5:-configs/bonn.yaml}; mode=${6:-full}
shift $(($# < 6 ? $# : 6))
[[ "${1-}" == "--" ]] && shift
[ -x /usr/bin/time ] || { echo "ab_fps: /usr/bin/time is needed (apt-get install time)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fps() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['fps'])" "$1/stats.json"; }
fa=(); fb=(); ratios=()
for i in $(seq 1 "$runs"); do
  for side in a b; do
    bin=$a; cfg=$config
    [[ $side == b ]] && { bin=$b; cfg=${CONFIG_B:-$config}; }
    /usr/bin/time -f "%U %S %M" -o "$out/$side$i.time" \
      "$bin" run --sequence "$seq" --config "$cfg" --mode "$mode" --output "$out/$side$i" "$@" > "$out/$side$i.log" 2>&1
    mv "$out/$side$i.time" "$out/$side$i/time.txt"
  done
  x=$(fps "$out/a$i"); y=$(fps "$out/b$i")
  fa+=("$x"); fb+=("$y"); ratios+=("$(awk -v x="$x" -v y="$y" 'BEGIN { printf "%.4f", y / x }')")
  printf 'run %d: A %.1f fps, B %.1f fps, B/A %s\n' "$i" "$x" "$y" "${ratios[-1]}"
done
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
printf 'median: A %.1f fps, B %.1f fps, B/A %.3f (%d interleaved pairs)\n' "$(median "${fa[@]}")" "$(median "${fb[@]}")" \
  "$(median "${ratios[@]}")" "$runs"
python3 bench/ab_table.py "$out" "$runs"
