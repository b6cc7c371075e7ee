#!/usr/bin/env bash
# The Python module's overhead: frames per second of examples/python/track_folder.py (the amos_slam module, one
# frame at a time through amos::Slam) against `amos-slam run` on the Bonn dev slice, mode full, configs/bonn.yaml;
# RUNS interleaved pairs (run, python, run, python, ...) so that a drifting machine affects both alike; medians and
# the ratio python / run pair by pair. Each side's own fps: run's stats.json "fps" (frames / wall time of the run,
# reading included, start-up excluded) and the example's printed fps (frames / time of its loop, reading included).
# Both deterministic by default; DETERMINISTIC=0 runs both without.
# With CPP_EXAMPLE=<the built examples/cpp track_folder> the C++ example runs too (triples run, python, C++).
#   bash bench/python_overhead.sh [RUNS=5]
# Needs build/bin/amos-slam and the module built in build/python (AMOS_BUILD_PYTHON), /usr/bin/python3 with numpy.
set -euo pipefail
RUNS="${1:-5}"
NAME=python_overhead
source "$(dirname "$0")/common.sh"
PY_MODULE_DIR=build/python
ls "$PY_MODULE_DIR"/amos_slam*.so > /dev/null 2>&1 ||
  { echo "$NAME: $PY_MODULE_DIR/amos_slam*.so is missing: build with -DAMOS_BUILD_PYTHON=ON" >&2; exit 2; }
run_flags=(--deterministic)
py_flags=()
if [[ "${DETERMINISTIC:-1}" == 0 ]]; then run_flags=(); py_flags=(--not-deterministic); fi

for i in $(seq 1 "$RUNS"); do
  echo "$NAME: pair $i/$RUNS" >&2
  rm -rf "$OUT/run.$i"
  "$BIN" run --sequence "$SEQ" --config configs/bonn.yaml --mode full "${run_flags[@]}" --output "$OUT/run.$i" \
    > "$OUT/run.$i.log" 2>&1
  PYTHONPATH=$PY_MODULE_DIR /usr/bin/python3 examples/python/track_folder.py "$SEQ" configs/bonn.yaml \
    "$OUT/py.$i.txt" --mode full "${py_flags[@]}" > "$OUT/py.$i.log" 2>&1
  if [[ -n "${CPP_EXAMPLE:-}" ]]; then
    "$CPP_EXAMPLE" "$SEQ" configs/bonn.yaml "$OUT/cpp.$i.txt" full > "$OUT/cpp.$i.log" 2>&1
  fi
done

python3 - "$OUT" "$RUNS" <<'PY'
import json, re, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
run = [json.load(open(f"{out}/run.{i}/stats.json"))["fps"] for i in range(1, runs + 1)]
py = [float(re.search(r"([0-9.]+) fps", open(f"{out}/py.{i}.log").read()).group(1)) for i in range(1, runs + 1)]
ratio = [p / r for p, r in zip(py, run)]
med = statistics.median
print("run fps   ", " ".join(f"{x:.1f}" for x in run), f"  median {med(run):.1f}")
print("python fps", " ".join(f"{x:.1f}" for x in py), f"  median {med(py):.1f}")
print("python/run", " ".join(f"{x:.3f}" for x in ratio), f"  median {med(ratio):.3f}")
import os
if os.path.exists(f"{out}/cpp.1.log"):
    cpp = [float(re.search(r"([0-9.]+) fps", open(f"{out}/cpp.{i}.log").read()).group(1)) for i in range(1, runs + 1)]
    cpp_ratio = [c / r for c, r in zip(cpp, run)]
    print("C++ fps   ", " ".join(f"{x:.1f}" for x in cpp), f"  median {med(cpp):.1f}")
    print("C++/run   ", " ".join(f"{x:.3f}" for x in cpp_ratio), f"  median {med(cpp_ratio):.3f}")
PY
