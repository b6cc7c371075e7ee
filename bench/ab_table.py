#!/usr/bin/env python3
"""Side-by-side table of two builds' interleaved runs (written by bench/ab_fps.sh): per run folder A<i>/B<i> its
stats.json and time.txt (/usr/bin/time: user s, system s, peak RSS KB). Prints, for A and B, the medians over the
runs of: fps, ATE, whole-process CPU per frame, peak memory, a paced run's latency (p95, median) and dropped frames,
and each pipeline thread's CPU per frame (the cpu.*
stages of stats.json, mean x count / frames) and the rest of the process's CPU; then B/A of the medians, and the median of the per-pair fps ratios.

    python3 bench/ab_table.py OUT_FOLDER RUNS
"""
import json
import statistics
import sys
from pathlib import Path


def run_figures(folder: Path) -> dict:
    stats = json.loads((folder / "stats.json").read_text())
    user, system, rss_kb = (float(v) for v in (folder / "time.txt").read_text().split()[-3:])
    frames = stats["frames"]
    figures = {
        "fps": stats["fps"],
        "ATE cm": 100 * stats.get("evaluation", {}).get("ate_rmse_m", float("nan")),
        "process CPU ms/frame": 1000 * (user + system) / frames,
        "peak memory MiB": rss_kb / 1024,
    }
    # A paced source (--realtime, a camera): its latency from a frame's arrival to its pose, and the frames dropped.
    # (A folder run's "arrival" is when the frame was read, so its latency is only the look-ahead's queueing.)
    source = stats.get("source", {})
    if "latency_ms" in source and source.get("kind") != "folder":
        figures["latency p95 ms"] = source["latency_ms"]["p95"]
        figures["latency median ms"] = source["latency_ms"]["median"]
        figures["dropped frames"] = source.get("dropped", 0)
    for name, stage in sorted(stats["stages"].items()):
        if name.startswith("cpu."):
            figures[name + " ms/frame"] = stage["mean_ms"] * stage["count"] / frames
    threads = sum(v for k, v in figures.items() if k.startswith("cpu."))
    # Reading and decoding the frames, start-up, the outputs: the process's CPU outside the timed stages.
    figures["rest of the process ms/frame"] = figures["process CPU ms/frame"] - threads
    return figures


def main() -> None:
    out, runs = Path(sys.argv[1]), int(sys.argv[2])
    a = [run_figures(out / f"a{i}") for i in range(1, runs + 1)]
    b = [run_figures(out / f"b{i}") for i in range(1, runs + 1)]
    keys = list(dict.fromkeys([k for r in a + b for k in r]))
    print(f"| figure (median of {runs}) | A | B | B/A |")
    print("|---|---|---|---|")
    for key in keys:
        va = statistics.median(r.get(key, 0.0) for r in a)
        vb = statistics.median(r.get(key, 0.0) for r in b)
        ratio = f"{vb / va:.3f}" if va else "-"
        print(f"| {key} | {va:.2f} | {vb:.2f} | {ratio} |")
    pairs = [y["fps"] / x["fps"] for x, y in zip(a, b)]
    print(f"\nfps B/A per pair: {', '.join(f'{p:.3f}' for p in pairs)}; median {statistics.median(pairs):.3f}")
    if all("latency p95 ms" in r for r in a + b):
        lower = sum(y["latency p95 ms"] < x["latency p95 ms"] for x, y in zip(a, b))
        print(f"latency p95 lower in B in {lower} of {runs} pairs")


if __name__ == "__main__":
    main()
