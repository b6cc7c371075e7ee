# Shared set-up of the bench/*.sh scripts (sourced, not run): the checkout as working folder, the amos-slam binary,
# the Bonn dev slice and an output folder, each checked with a message naming what is missing.
#   NAME=my_bench; source "$(dirname "$0")/common.sh"   -> BIN, SEQ, OUT (default out/$NAME, or $AMOS_BENCH_OUT)
cd "$(dirname "${BASH_SOURCE[0]}")/.."
BIN=build/bin/amos-slam
SEQ="${AMOS_DATA_DIR:-../shared/data}/bonn_crowd_dev"
OUT="${AMOS_BENCH_OUT:-out/$NAME}"
[ -x "$BIN" ] || { echo "$NAME: $BIN is missing: run bash scripts/build.sh first" >&2; exit 2; }
[ -d "$SEQ" ] || { echo "$NAME: $SEQ is missing (set AMOS_DATA_DIR to the folder that holds bonn_crowd_dev)" >&2; exit 2; }
command -v python3 > /dev/null || { echo "$NAME: python3 is needed for the tables" >&2; exit 2; }
mkdir -p "$OUT"
