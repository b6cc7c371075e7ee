#!/usr/bin/env bash
# What the live viewer costs a run: frames per second of `run --mode full` on the Bonn dev slice without and with
# --viewer (a client reading the event stream and fetching the frame image twice a second, as the page does),
# interleaved run by run so that a drifting machine affects both alike; medians of RUNS runs each; and the time
# `run` took to write report.html (its log line).
#   bash bench/viewer_overhead.sh [RUNS=3]
# Needs build/bin/amos-slam (built with the viewer), ../shared/data/bonn_crowd_dev, curl and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS="${1:-3}"
BIN=build/bin/amos-slam
SEQ="${AMOS_DATA_DIR:-../shared/data}/bonn_crowd_dev"
OUT="${AMOS_BENCH_OUT:-out/viewer_overhead}"
[ -x "$BIN" ] || { echo "viewer_overhead: $BIN is missing: run bash scripts/build.sh first" >&2; exit 2; }
[ -d "$SEQ" ] || { echo "viewer_overhead: $SEQ is missing" >&2; exit 2; }
mkdir -p "$OUT"
PORT="${AMOS_VIEWER_PORT:-8097}"

# A browser's load while the run goes: the event stream, and the frame image after each update (at most 5 a second).
client() {
  until curl -s -o /dev/null "http://127.0.0.1:$PORT/api/state"; do sleep 0.2; done
  curl -s -N "http://127.0.0.1:$PORT/api/events" > "$1/events.txt" &
  local stream=$!
  while kill -0 "$2" 2>/dev/null; do
    curl -s -o /dev/null "http://127.0.0.1:$PORT/api/frame.jpg" || true
    sleep 0.2
  done
  kill "$stream" 2>/dev/null || true
}

for run in $(seq 1 "$RUNS"); do
  for v in plain viewer; do
    dir="$OUT/$v.$run"
    rm -rf "$dir"
    args=(run --sequence "$SEQ" --config configs/bonn.yaml --mode full --output "$dir")
    if [ "$v" = viewer ]; then
      mkdir -p "$dir.client"
      "$BIN" "${args[@]}" --viewer --viewer-port "$PORT" > "$dir.stdout" 2> "$dir.stderr" &
      pid=$!
      client "$dir.client" "$pid"
      wait "$pid"
    else
      "$BIN" "${args[@]}" > "$dir.stdout" 2> "$dir.stderr"
    fi
    echo "$v run $run: $(grep -o '[0-9.]* fps$' "$dir.stdout" | head -1 || true) $(grep -o 'report.html written in [0-9]* ms' "$dir.stderr")" >&2
  done
done

python3 - "$OUT" "$RUNS" <<'PY'
import json, re, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
def fps(v):
    return [json.load(open(f"{out}/{v}.{r}/stats.json"))["fps"] for r in range(1, runs + 1)]
def report_ms(v):
    ms = []
    for r in range(1, runs + 1):
        m = re.search(r"report.html written in (\d+) ms", open(f"{out}/{v}.{r}.stderr").read())
        if m: ms.append(int(m.group(1)))
    return ms
plain, viewer = fps("plain"), fps("viewer")
print(f"fps without --viewer: {' '.join(f'{x:.1f}' for x in plain)}  median {statistics.median(plain):.1f}")
print(f"fps with --viewer:    {' '.join(f'{x:.1f}' for x in viewer)}  median {statistics.median(viewer):.1f}")
ratios = [v / p for v, p in zip(viewer, plain)]
print(f"with / without, run by run: {' '.join(f'{x:.3f}' for x in ratios)}  median {statistics.median(ratios):.3f}")
ms = report_ms("plain") + report_ms("viewer")
if ms: print(f"report.html written in (ms): {' '.join(map(str, ms))}  median {statistics.median(ms)}")
PY
