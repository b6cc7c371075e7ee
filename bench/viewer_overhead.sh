#!/usr/bin/env bash
# What the live viewer costs a run: `run --mode full` on the Bonn dev slice without and with --viewer, interleaved
# run by run so that a drifting machine affects both alike; medians of RUNS runs each. With the viewer a client does
# what the page does: it follows the event stream and fetches the frame image after each update (at most 5 a
# second), over one kept-alive connection (bench/viewer_client.py; a browser on the same 2 cores would add its
# drawing on top). Reported: fps, the amos-slam process's CPU ms per frame (all its threads: what publishing costs
# the run, whatever the client does), the client's own CPU, and the time `run` took to write report.html.
#   bash bench/viewer_overhead.sh [RUNS=3]
# Needs build/bin/amos-slam (built with the viewer), ../shared/data/bonn_crowd_dev and python3.
set -euo pipefail
RUNS="${1:-3}"
NAME=viewer_overhead
source "$(dirname "$0")/common.sh"
PORT="${AMOS_VIEWER_PORT:-8097}"

for run in $(seq 1 "$RUNS"); do
  for v in plain viewer; do
    dir="$OUT/$v.$run"
    rm -rf "$dir"
    args=(run --sequence "$SEQ" --config configs/bonn.yaml --mode full --output "$dir")
    if [ "$v" = viewer ]; then
      /usr/bin/time -f "%U %S %e" -o "$dir.time" "$BIN" "${args[@]}" --viewer --viewer-port "$PORT" \
        > "$dir.stdout" 2> "$dir.stderr" &
      pid=$!
      /usr/bin/time -f "%U %S %e" -o "$dir.client.time" python3 bench/viewer_client.py "$PORT" "$pid" "$dir.client.json"
      wait "$pid"
    else
      /usr/bin/time -f "%U %S %e" -o "$dir.time" "$BIN" "${args[@]}" > "$dir.stdout" 2> "$dir.stderr"
    fi
    echo "$v run $run: $(grep -o '[0-9.]* fps$' "$dir.stdout" | head -1 || true) $(grep -o 'report.html written in [0-9]* ms' "$dir.stderr")" >&2
  done
done

python3 - "$OUT" "$RUNS" <<'PY'
import json, re, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
def stats(v, r): return json.load(open(f"{out}/{v}.{r}/stats.json"))
def cpu_ms(path, frames):
    user, sys_ = map(float, open(path).read().split()[:2])
    return 1000 * (user + sys_) / frames
rows = {}
for v in ("plain", "viewer"):
    fps = [stats(v, r)["fps"] for r in range(1, runs + 1)]
    cpu = [cpu_ms(f"{out}/{v}.{r}.time", stats(v, r)["frames"]) for r in range(1, runs + 1)]
    rows[v] = (fps, cpu)
    print(f"{v:7s} fps {' '.join(f'{x:.1f}' for x in fps)} (median {statistics.median(fps):.1f}); "
          f"CPU ms/frame {' '.join(f'{x:.1f}' for x in cpu)} (median {statistics.median(cpu):.1f})")
ratios = [w / p for w, p in zip(rows["viewer"][0], rows["plain"][0])]
print(f"fps with / without, run by run: {' '.join(f'{x:.3f}' for x in ratios)}  median {statistics.median(ratios):.3f}")
cpu_ratios = [w / p for w, p in zip(rows["viewer"][1], rows["plain"][1])]
print(f"run's CPU with / without: {' '.join(f'{x:.3f}' for x in cpu_ratios)}  median {statistics.median(cpu_ratios):.3f}")
client = []
for r in range(1, runs + 1):
    c = json.load(open(f"{out}/viewer.{r}.client.json"))
    user, sys_ = map(float, open(f"{out}/viewer.{r}.client.time").read().split()[:2])
    client.append((c["updates"], c["images"], 1000 * (user + sys_) / stats("viewer", r)["frames"]))
print("client, run by run (updates, images, CPU ms per frame of the run): " +
      "; ".join(f"{u}, {i}, {ms:.2f}" for u, i, ms in client))
ms = []
for v in ("plain", "viewer"):
    for r in range(1, runs + 1):
        m = re.search(r"report.html written in (\d+) ms", open(f"{out}/{v}.{r}.stderr").read())
        if m: ms.append(int(m.group(1)))
if ms: print(f"report.html written in (ms): {' '.join(map(str, ms))}  median {statistics.median(ms)}")
PY
