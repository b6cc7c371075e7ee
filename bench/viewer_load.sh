#!/usr/bin/env bash
# A live run under viewer load: `run --mode full --realtime --viewer` on the Bonn dev slice with no client, and with
# CLIENTS concurrent loopback clients (bench/viewer_load.py: event streams, /api/state, /api/frame.jpg, each with a
# pause of 0.1 s between requests) for as long as the run goes; interleaved pair by pair so that a drifting machine
# affects both alike. Reported per run: the share of frames the realtime source dropped and the p95 latency from a
# frame's arrival to its pose (stats.json `source`), and what the clients got (requests, statuses, latency).
#   bash bench/viewer_load.sh [PAIRS=3] [CLIENTS=50]
# Needs build/bin/amos-slam (built with the viewer), ../shared/data/bonn_crowd_dev and python3.
set -euo pipefail
PAIRS="${1:-3}"
CLIENTS="${2:-50}"
NAME=viewer_load
source "$(dirname "$0")/common.sh"
PORT="${AMOS_VIEWER_PORT:-8098}"

for pair in $(seq 1 "$PAIRS"); do
  for v in quiet loaded; do
    dir="$OUT/$v.$pair"
    rm -rf "$dir"
    "$BIN" run --sequence "$SEQ" --config configs/bonn.yaml --mode full --realtime --viewer --viewer-port "$PORT" \
      --output "$dir" > "$dir.stdout" 2> "$dir.stderr" &
    pid=$!
    if [ "$v" = loaded ]; then python3 bench/viewer_load.py "$PORT" "$pid" "$dir.load.json" "$CLIENTS" 60; fi
    wait "$pid"
    echo "$v pair $pair: done (load average $(cut -d' ' -f1-3 /proc/loadavg))" >&2
  done
done

python3 - "$OUT" "$PAIRS" <<'PY'
import json, statistics, sys
out, pairs = sys.argv[1], int(sys.argv[2])
def source(v, p): return json.load(open(f"{out}/{v}.{p}/stats.json"))["source"]
for v in ("quiet", "loaded"):
    dropped = [100 * source(v, p)["dropped"] / max(1, source(v, p)["delivered"]) for p in range(1, pairs + 1)]
    p95 = [source(v, p)["latency_ms"]["p95"] for p in range(1, pairs + 1)]
    print(f"{v:6s} dropped % {' '.join(f'{x:.1f}' for x in dropped)} (median {statistics.median(dropped):.1f}); "
          f"latency p95 ms {' '.join(f'{x:.1f}' for x in p95)} (median {statistics.median(p95):.1f})")
for p in range(1, pairs + 1):
    load = json.load(open(f"{out}/loaded.{p}.load.json"))
    print(f"clients, pair {p}: " + "; ".join(
        f"{path} {e['requests']} requests {e['status']} errors {e['errors']} median {e['median_ms'] or 0:.0f} ms "
        f"p95 {e['p95_ms'] or 0:.0f} ms max {e['max_ms'] or 0:.0f} ms" for path, e in sorted(load["endpoints"].items())))
PY
