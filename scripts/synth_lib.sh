# Shared by the synthetic evaluation scripts (*_matrix.sh, maps_check.sh); sourced, not run.
# The functions read and set the caller's seeds, seed_list, frames, bin, out and config.

abspath() { case "$1" in /*) printf '%s\n' "$1" ;; *) printf '%s\n' "$PWD/$1" ;; esac; }

# common_option NAME VALUE: sets the option every matrix takes (--seeds, --frames, --bin, --out, --config), and
# --presets / --modes for a script that set a default for them, and returns 0; returns 1 for any other NAME. Paths
# are made absolute against the current folder.
common_option() {
  case "$1" in
    --presets) [[ -n "${presets+set}" ]] || return 1; presets=${2:?--presets needs a value} ;;
    --modes) [[ -n "${modes+set}" ]] || return 1; modes=${2:?--modes needs a value} ;;
    --seeds) seeds=${2:?--seeds needs a value} ;;
    --frames) frames=${2:?--frames needs a value} ;;
    --bin) bin=$(abspath "${2:?--bin needs a value}") ;;
    --out) out=$(abspath "${2:?--out needs a value}") ;;
    --config) config=$(abspath "${2:?--config needs a value}") ;;
    *) return 1 ;;
  esac
}

# parse_common_options LINES ARGS...: for a script that takes only the common options: -h/--help prints lines
# LINES (a sed range such as 2,16) of the calling script without their comment marks and exits; any other
# argument is an error. Then check_common_options.
parse_common_options() {
  local lines=$1
  shift
  while (($#)); do
    case "$1" in
      -h | --help) sed -n "${lines}p" "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
      *) common_option "$1" "${2-}" || { echo "error: unknown argument '$1' (see --help)" >&2; exit 2; }; shift 2 ;;
    esac
  done
  check_common_options
}

# check_common_options: exits with a message naming the bad value; fills seed_list from seeds, and preset_list
# and mode_list from presets and modes when the script has them.
check_common_options() {
  [[ -x "$bin" ]] || { echo "error: amos-slam binary '$bin' not found or not executable; build first (scripts/build.sh) or pass --bin" >&2; exit 1; }
  [[ -f "$config" ]] || { echo "error: settings file '$config' not found" >&2; exit 1; }
  [[ "$frames" =~ ^[1-9][0-9]*$ ]] || { echo "error: --frames must be a positive integer, got '$frames'" >&2; exit 2; }
  read -r -a seed_list <<< "$seeds"
  ((${#seed_list[@]})) || { echo "error: --seeds is empty" >&2; exit 2; }
  local s
  for s in "${seed_list[@]}"; do
    [[ "$s" =~ ^[0-9]+$ ]] || { echo "error: seed '$s' is not a non-negative integer" >&2; exit 2; }
  done
  if [[ -n "${presets+set}" ]]; then
    read -r -a preset_list <<< "$presets"
    ((${#preset_list[@]})) || { echo "error: --presets is empty" >&2; exit 2; }
  fi
  if [[ -n "${modes+set}" ]]; then
    read -r -a mode_list <<< "$modes"
    ((${#mode_list[@]})) || { echo "error: --modes is empty" >&2; exit 2; }
    local m
    for m in "${mode_list[@]}"; do
      [[ "$m" =~ ^(none|prior|geometry|full)$ ]] || { echo "error: unknown mode '$m'" >&2; exit 2; }
    done
  fi
}

log() { printf '[%s] %s\n' "$(date +%H:%M:%S)" "$*" >&2; }

# json_get FILE .a.b.c -> the value or "null"; instance_get FILE NAME FIELD -> a field of the mover called NAME in
# stats.json's mask_accuracy.instances, or "null". jq, else python3.
if command -v jq > /dev/null; then
  json_get() { jq -r "$2 // \"null\"" "$1" 2> /dev/null || echo null; }
  instance_get() {
    jq -r --arg n "$2" --arg f "$3" \
      '[.mask_accuracy.instances[]? | select(.name == $n) | .[$f]] | first // "null"' "$1" 2> /dev/null || echo null
  }
elif command -v python3 > /dev/null; then
  json_get() {
    python3 - "$1" "$2" << 'EOF' 2> /dev/null || echo null
import json, sys
v = json.load(open(sys.argv[1]))
for k in sys.argv[2].lstrip(".").split("."):
    v = v.get(k) if isinstance(v, dict) else None
print("null" if v is None else v)
EOF
  }
  instance_get() {
    python3 - "$1" "$2" "$3" << 'EOF' 2> /dev/null || echo null
import json, sys
d = json.load(open(sys.argv[1]))
v = next((i.get(sys.argv[3]) for i in d.get("mask_accuracy", {}).get("instances", []) if i.get("name") == sys.argv[2]), None)
print("null" if v is None else json.dumps(v) if isinstance(v, (list, dict)) else v)
EOF
  }
else
  echo "error: reading stats.json needs jq or python3 (apt-get install jq)" >&2; exit 1
fi

# render PRESET SEED STATIC(0|1) -> prints the sequence folder; returns 1 on failure. Rendered sequences are cached
# in $out/sequences/ (reused when the render finished, i.e. its .complete marker exists).
render() {
  local preset=$1 seed=$2 static=$3 name extra=()
  name="${preset}_s${seed}_f${frames}"
  ((static)) && { name+="_nomovers"; extra=(--no-movers); }
  render_named "$name" "$preset" "$seed" "${extra[@]}"
}

# render_named NAME PRESET SEED [SYNTH FLAGS...] -> as render, into $out/sequences/NAME with the extra synth flags
# (the caller's NAME must tell the flags apart: it is the cache key).
render_named() {
  local name=$1 preset=$2 seed=$3 dir
  shift 3
  dir="$out/sequences/$name"
  if [[ -f "$dir/.complete" ]]; then
    log "render $name: cached"
  else
    rm -rf "$dir"
    local t0=$SECONDS
    log "render $name${*:+ ($*)} ..."
    if ! "$bin" synth --preset "$preset" --seed "$seed" --frames "$frames" --output "$dir" "$@" \
        > "$out/sequences/$name.log" 2>&1; then
      log "render $name FAILED (log: $out/sequences/$name.log):"; tail -3 "$out/sequences/$name.log" >&2
      return 1
    fi
    touch "$dir/.complete"
    log "render $name done in $((SECONDS - t0)) s"
  fi
  printf '%s\n' "$dir"
}

# Formatting: metres -> mm, fraction -> 3 decimals / percent; "fail" and "null" pass through as-is.
num() { [[ $1 =~ ^-?[0-9.]+([eE][-+]?[0-9]+)?$ ]]; }
mm() { if num "$1"; then awk -v v="$1" 'BEGIN { printf "%.2f", 1000 * v }'; else printf '%s' "${1/null/n/a}"; fi; }
cm() { if num "$1"; then awk -v v="$1" 'BEGIN { printf "%.2f", 100 * v }'; else printf '%s' "${1/null/n/a}"; fi; }
dec() { if num "$1"; then awk -v v="$1" 'BEGIN { printf "%.3f", v }'; else printf '%s' "${1/null/n/a}"; fi; }
pct() { if num "$1"; then awk -v v="$1" 'BEGIN { printf "%.3f", 100 * v }'; else printf '%s' "${1/null/n/a}"; fi; }
ratio() { if num "$1" && num "$2"; then awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.2f", a / b; else printf "n/a" }'; else printf 'n/a'; fi; }
mean() { printf '%s\n' "$@" | awk '/^-?[0-9.]+([eE][-+]?[0-9]+)?$/ { s += $1; n++ } END { if (n) printf "%.17g", s / n; else printf "null" }'; }
median() { printf '%s\n' "$@" | awk '/^-?[0-9.]+([eE][-+]?[0-9]+)?$/' | sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) printf "null"; else if (NR % 2) printf "%.17g", v[(NR + 1) / 2]; else printf "%.17g", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
