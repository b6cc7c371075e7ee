#!/usr/bin/env bash
# Fingerprints of deterministic runs, to show that a change of structure changes no behaviour:
#   bash scripts/golden_outputs.sh [--bin build/bin/amos-slam] [--out out/golden] [--frames 120]
# Runs, each with --deterministic and --save-masks:
#   fr2_desk_none  TUM fr2/desk first 50 frames, mode none   (configs/tum2.yaml)
#   fr2_desk_full  TUM fr2/desk first 50 frames, mode full   (configs/tum2.yaml)
#   bonn_full      the Bonn crowd dev slice, mode full       (configs/bonn.yaml)
#   walking_xyz    synthetic walking_xyz seed 1, mode full   (configs/tum3.yaml)
#   box_push       synthetic box_push seed 1, mode geometry  (configs/tum3.yaml; a mover no detector knows)
#   objects_xyz    synthetic objects_xyz seed 5, mode full   (configs/tum3.yaml; the rigid movers' preset)
# and prints one line per run: its name, the sha256 of its trajectory and of all its masks (in file order).
# Compare two binaries by running this twice and diffing the outputs. Real data is read from $AMOS_DATA_DIR
# (default ../shared/data); a run whose input is missing is reported as "missing". One job at a time.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin="$root/build/bin/amos-slam"
out="$root/out/golden"
frames=120
while (($#)); do
  case "$1" in
    --bin) bin=$(realpath "$2"); shift 2 ;;
    --out) out=$(realpath -m "$2"); shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    -h | --help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "error: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
data="${AMOS_DATA_DIR:-$root/../shared/data}"
mkdir -p "$out/sequences" "$out/runs"
cd "$root"

render() {  # PRESET SEED -> prints the sequence folder (rendered once, then cached)
  local dir="$out/sequences/$1_s$2_f$frames"
  if [[ ! -f "$dir/.complete" ]]; then
    rm -rf "$dir"
    "$bin" synth --preset "$1" --seed "$2" --frames "$frames" --output "$dir" > "$dir.log" 2>&1
    touch "$dir/.complete"
  fi
  printf '%s\n' "$dir"
}

fingerprint() {  # NAME SEQUENCE CONFIG MODE
  local name=$1 seq=$2 config=$3 mode=$4 dir="$out/runs/$1"
  if [[ ! -d "$seq" ]]; then printf '%-15s missing (%s)\n' "$name" "$seq"; return; fi
  rm -rf "$dir"
  "$bin" run --sequence "$seq" --config "$config" --mode "$mode" --deterministic --output "$dir" \
    --save-masks > "$dir.log" 2>&1 || { printf '%-15s FAILED (log %s)\n' "$name" "$dir.log"; return; }
  local traj masks
  traj=$(sha256sum "$dir/trajectory.txt" | cut -c1-16)
  if [[ -d "$dir/masks" ]]; then
    masks=$(find "$dir/masks" -type f | sort | xargs cat | sha256sum | cut -c1-16)
  else
    masks=none
  fi
  printf '%-15s trajectory %s masks %s\n' "$name" "$traj" "$masks"
}

fingerprint fr2_desk_none "$data/tum_fr2_desk_first50" configs/tum2.yaml none
fingerprint fr2_desk_full "$data/tum_fr2_desk_first50" configs/tum2.yaml full
fingerprint bonn_full "$data/bonn_crowd_dev" configs/bonn.yaml full
fingerprint walking_xyz "$(render walking_xyz 1)" configs/tum3.yaml full
fingerprint box_push "$(render box_push 1)" configs/tum3.yaml geometry
fingerprint objects_xyz "$(render objects_xyz 5)" configs/tum3.yaml full
