#!/usr/bin/env bash
# The cost of `run --dense` on a sequence (issue 43): PAIRS interleaved pairs of `run --mode full` without and with
# --dense (folder source), then --realtime without and with, all under the build lock so builds do not disturb
# them. Prints per run: fps, wall s, the dense map's final fusion s; then delivered / processed / dropped.
#   bash bench/dense_speed.sh [SEQUENCE] [CONFIG] [PAIRS] [BIN] [OUT]
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
seq=${1:-$root/../shared/data/bonn_crowd_dev}; config=${2:-$root/configs/bonn.yaml}; pairs=${3:-2}
bin=${4:-$root/build/bin/amos-slam}; out=${5:-$root/out/dense_speed}
mkdir -p "$out"
exec 9> /tmp/amos-build.lock
flock 9
field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$1" "$2"; }
for ((i = 1; i <= pairs; i++)); do
  for v in plain dense; do
    extra=(); [[ $v == dense ]] && extra=(--dense)
    "$bin" run --sequence "$seq" --config "$config" --output "$out/${v}_$i" --mode full "${extra[@]}" --overwrite > "$out/${v}_$i.log" 2>&1
    echo "$v $i fps $(field "$out/${v}_$i/stats.json" "d['fps']") wall_s $(field "$out/${v}_$i/stats.json" "d['wall_time_s']") dense_final_s $(field "$out/${v}_$i/stats.json" "d.get('dense', {}).get('final_s', '-')")"
  done
done
for v in plain dense; do
  extra=(); [[ $v == dense ]] && extra=(--dense)
  "$bin" run --sequence "$seq" --config "$config" --output "$out/rt_$v" --mode full --realtime "${extra[@]}" --overwrite > "$out/rt_$v.log" 2>&1
  echo "realtime $v delivered/processed/dropped $(field "$out/rt_$v/stats.json" "'%d %d %d' % (d['source']['delivered'], d['source']['processed'], d['source']['dropped'])")"
done
