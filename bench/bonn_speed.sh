#!/usr/bin/env bash
# End-to-end speed of the front-end modes on the Bonn dev slice: frames per second of the whole run (PNG decoding
# included), whole-process CPU per frame (all threads, from /usr/bin/time), the CPU of each pipeline thread per
# frame (the "cpu.*" stages of stats.json), ATE and lost frames; medians of RUNS runs, the variants interleaved so
# that a drifting machine affects them alike; with "none" among the variants also each variant's CPU against
# none's, round by round. Optional variant "paper": --mode full with the schedule and settings
# of before issue 12 (every-frame segmentation with the detector, LK window 15 run to 30 iterations / 0.01 px,
# local BA over every covisible keyframe); "detect6": full with the detector on every other segmentation
# (Dynamic.Prior.detectEvery 2: every 6th frame), the mask network alone on the others.
#   bash bench/bonn_speed.sh [RUNS=3] [VARIANTS="none full paper realtime"]
# Needs build/bin/amos-slam, ../shared/data/bonn_crowd_dev and python3. Run on an otherwise idle machine.
set -euo pipefail
RUNS="${1:-3}"
VARIANTS="${2:-none full paper realtime}"
NAME=bonn_speed
source "$(dirname "$0")/common.sh"
PAPER_CONFIG="$OUT/bonn_paper.yaml"
# configs/bonn.yaml with these keys set (replaced where the file sets them: a key set twice is an error).
paper_keys=("Dynamic.Prior.interval: 1" "Dynamic.Prior.lag: 0" "Dynamic.Prior.detectEvery: 1"
            "Dynamic.LK.window: 15" "Dynamic.LK.maxIterations: 30"
            "Dynamic.LK.epsilon: 0.01" "LocalBA.maxKeyFrames: 0")
cp configs/bonn.yaml "$PAPER_CONFIG"
for kv in "${paper_keys[@]}"; do
  key="${kv%%:*}"
  grep -v "^${key}:" "$PAPER_CONFIG" > "$PAPER_CONFIG.tmp"
  echo "$kv" >> "$PAPER_CONFIG.tmp"
  mv "$PAPER_CONFIG.tmp" "$PAPER_CONFIG"
done

DETECT6_CONFIG="$OUT/bonn_detect6.yaml"
cp configs/bonn.yaml "$DETECT6_CONFIG"
echo "Dynamic.Prior.detectEvery: 2" >> "$DETECT6_CONFIG"

for run in $(seq 1 "$RUNS"); do
  for v in $VARIANTS; do
    case "$v" in
      none) args=(--mode none --config configs/bonn.yaml) ;;
      full) args=(--mode full --config configs/bonn.yaml) ;;
      paper) args=(--mode full --config "$PAPER_CONFIG") ;;
      realtime) args=(--mode full --config configs/bonn.yaml --realtime) ;;
      detect6) args=(--mode full --config "$DETECT6_CONFIG") ;;
      *) echo "bonn_speed: unknown variant $v" >&2; exit 2 ;;
    esac
    dir="$OUT/$v.$run"
    rm -rf "$dir"
    echo "bonn_speed: run $run/$RUNS $v" >&2
    /usr/bin/time -f "%U %S %e" -o "$dir.time" "$BIN" run --sequence "$SEQ" --output "$dir" "${args[@]}" \
      > "$dir.log" 2>&1
  done
done

python3 - "$OUT" "$RUNS" $VARIANTS <<'PY'
import json, statistics, sys
out, runs, variants = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
threads = {  # which pipeline thread each cpu.* stage runs in
    "prepare": "look-ahead", "segmentation": "segmentation", "mapping": "mapping",
    "corner_tracking": "look-ahead", "initial_pose": "tracking", "front_end": "tracking", "track": "tracking"}
rows = {}
for v in variants:
    r = {"fps": [], "cpu": [], "ate": [], "lost": [], "dropped": [], "lat50": [], "lat95": [], "stages": {}}
    for i in range(1, runs + 1):
        s = json.load(open(f"{out}/{v}.{i}/stats.json"))
        user, sys_, wall = map(float, open(f"{out}/{v}.{i}.time").read().split()[:3])
        n = s["frames"]
        r["fps"].append(s["fps"])
        r["cpu"].append(1000 * (user + sys_) / n)
        r["ate"].append(100 * s.get("evaluation", {}).get("ate_rmse_m", float("nan")))
        r["lost"].append(s["lost"])
        src = s.get("source", {})
        r["dropped"].append(100 * src.get("dropped", 0) / max(1, src.get("delivered", n)))
        lat = src.get("latency_ms", {})
        r["lat50"].append(lat.get("median", float("nan")))
        r["lat95"].append(lat.get("p95", float("nan")))
        for k, st in s["stages"].items():
            if k.startswith("cpu."):
                r["stages"].setdefault(k[4:], []).append(st["mean_ms"] * st["count"] / n)
    rows[v] = r
med = statistics.median
print("| variant | fps | CPU ms/frame (process) | ATE cm | lost | dropped % | latency median / p95 ms |")
print("|---|---|---|---|---|---|---|")
for v, r in rows.items():
    print(f"| {v} | {med(r['fps']):.1f} | {med(r['cpu']):.0f} | {med(r['ate']):.2f} | {med(r['lost']):.0f} | "
          f"{med(r['dropped']):.0f} | {med(r['lat50']):.0f} / {med(r['lat95']):.0f} |")
stages = sorted({k for r in rows.values() for k in r["stages"]}, key=lambda k: (threads.get(k, "?"), k))
print()
print("| thread | stage | " + " | ".join(variants) + " |")
print("|---|---|" + "---|" * len(variants))
for k in stages:
    cells = [f"{med(rows[v]['stages'][k]):.1f}" if k in rows[v]["stages"] else "-" for v in variants]
    print(f"| {threads.get(k, '?')} | {k} | " + " | ".join(cells) + " |")
print("(CPU ms per processed frame, medians of runs; the process figure also holds PNG decoding and start-up)")
# The runs of one round are neighbours in time, so their ratio is less affected by the machine's drift than the
# ratio of the medians (issue 12's "CPU of full at most 2x that of none").
if "none" in rows:
    for v in variants:
        if v == "none":
            continue
        ratios = [c / b for c, b in zip(rows[v]["cpu"], rows["none"]["cpu"])]
        print(f"CPU {v} / none, round by round: " + ", ".join(f"{x:.2f}" for x in ratios) +
              f" (median {med(ratios):.2f}x; ratio of the medians {med(rows[v]['cpu']) / med(rows['none']['cpu']):.2f}x)")
PY
