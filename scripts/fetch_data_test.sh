#!/usr/bin/env bash
# Offline test of scripts/fetch_data.sh (CTest "scripts/fetch_data"): --help and --list, the unknown-name and
# bad-archive errors, and the unpack/verify/move step on small archives built here (--from a file or file:// URL).
set -euo pipefail
script="$(cd "$(dirname "$0")" && pwd)/fetch_data.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() {  # check DESCRIPTION COMMAND...: the command must succeed
  if "${@:2}"; then echo "ok   $1"; else echo "FAIL $1"; failures=$((failures + 1)); fi
}
run() {  # run COMMAND...: its status, stdout+stderr in $work/out
  local status=0
  "$@" > "$work/out" 2>&1 || status=$?
  return "$status"
}
says() { grep -q -- "$1" "$work/out" || { echo "  output lacks '$1':"; sed 's/^/  | /' "$work/out"; return 1; }; }

check "--help prints the usage" bash -c "'$script' --help | grep -q 'fetch_data.sh \[--from ARCHIVE\] NAME'"
check "--list names TUM and Bonn sequences" bash -c \
  "'$script' --list | grep -qx '  freiburg2_desk' && '$script' --list | grep -qx '  bonn_crowd' \
   && '$script' --list | grep -qx '  freiburg3_walking_xyz' && '$script' --list | grep -qx '  bonn_person_tracking'"
check "no name is a usage error" bash -c "! '$script' > /dev/null 2>&1"
check "an unknown name is an error pointing at --list" \
  bash -c "! '$script' freiburg9_nothing '$work/dest' > '$work/out' 2>&1 && grep -q \"unknown sequence 'freiburg9_nothing'\" '$work/out' && grep -q -- '--list' '$work/out'"
check "an unknown name creates nothing" test ! -e "$work/dest"

# A tiny TUM-style archive: rgbd_dataset_freiburg2_desk/{rgb,depth}/, rgb.txt, depth.txt, groundtruth.txt.
make_sequence() {  # make_sequence DIR
  mkdir -p "$1/rgb" "$1/depth"
  printf '# color images\n1.0 rgb/1.0.png\n2.0 rgb/2.0.png\n' > "$1/rgb.txt"
  printf '# depth maps\n1.0 depth/1.0.png\n2.0 depth/2.0.png\n' > "$1/depth.txt"
  printf '1.0 0 0 0 0 0 0 1\n' > "$1/groundtruth.txt"
  touch "$1/rgb/1.0.png" "$1/rgb/2.0.png" "$1/depth/1.0.png" "$1/depth/2.0.png"
}
mkdir -p "$work/src"
make_sequence "$work/src/rgbd_dataset_freiburg2_desk"
tar -czf "$work/fr2.tgz" -C "$work/src" rgbd_dataset_freiburg2_desk

check "a local .tgz is unpacked into DEST/NAME" run "$script" --from "$work/fr2.tgz" freiburg2_desk "$work/dest"
check "  in the reader's layout" test -f "$work/dest/freiburg2_desk/rgb.txt" -a -f "$work/dest/freiburg2_desk/depth.txt" \
  -a -f "$work/dest/freiburg2_desk/groundtruth.txt" -a -f "$work/dest/freiburg2_desk/rgb/2.0.png" \
  -a -f "$work/dest/freiburg2_desk/depth/1.0.png"
check "  saying where it went and how many frames" says "freiburg2_desk: 2 RGB frames in $work/dest/freiburg2_desk"
check "  leaving no temporary folder" bash -c "[[ -z \$(find '$work/dest' -maxdepth 1 -name '.fetch_*') ]]"
check "an existing DEST/NAME is refused" bash -c "! '$script' --from '$work/fr2.tgz' freiburg2_desk '$work/dest' > '$work/out' 2>&1"
check "  naming it" says "already exists"

check "a file:// URL is fetched with curl" run "$script" --from "file://$work/fr2.tgz" freiburg2_desk "$work/dest2"
check "  into DEST/NAME" test -f "$work/dest2/freiburg2_desk/rgb.txt"
check "DEST defaults to \$AMOS_DATA_DIR" env AMOS_DATA_DIR="$work/dest3" "$script" --from "$work/fr2.tgz" freiburg2_desk
check "  into \$AMOS_DATA_DIR/NAME" test -f "$work/dest3/freiburg2_desk/depth.txt"

# A Bonn-style .zip: rgbd_bonn_crowd/...
make_sequence "$work/src/rgbd_bonn_crowd"
(cd "$work/src" && python3 -m zipfile -c "$work/crowd.zip" rgbd_bonn_crowd)
check "a local .zip is unpacked for a Bonn name" run "$script" --from "$work/crowd.zip" bonn_crowd "$work/dest"
check "  in the reader's layout" test -f "$work/dest/bonn_crowd/rgb.txt" -a -f "$work/dest/bonn_crowd/depth/2.0.png"

# Archives that are not a sequence.
rm "$work/src/rgbd_bonn_crowd/depth.txt"
tar -czf "$work/no_depth.tgz" -C "$work/src" rgbd_bonn_crowd
check "an archive without depth.txt is an error" bash -c \
  "! '$script' --from '$work/no_depth.tgz' freiburg1_xyz '$work/dest' > '$work/out' 2>&1"
check "  naming depth.txt" says "lacks depth.txt"
check "  and moves nothing into DEST" test ! -e "$work/dest/freiburg1_xyz"
echo "not an archive" > "$work/junk.tgz"
check "a damaged archive is an error" bash -c "! '$script' --from '$work/junk.tgz' freiburg1_xyz '$work/dest' > '$work/out' 2>&1"
check "  naming it" says "not a readable .tgz archive"
check "a missing local archive is an error" bash -c "! '$script' --from '$work/none.tgz' freiburg1_xyz '$work/dest' > '$work/out' 2>&1"
check "  naming it" says "not found"
check "a failed download is an error" bash -c "! '$script' --from 'file://$work/none.tgz' freiburg1_xyz '$work/dest' > '$work/out' 2>&1"
check "  naming the URL" says "could not download file://$work/none.tgz"
check "no temporary folder is left behind" bash -c "[[ -z \$(find '$work/dest' -maxdepth 1 -name '.fetch_*') ]]"

if ((failures)); then echo "$failures check(s) failed"; exit 1; fi
echo "all checks passed"
