#!/usr/bin/env bash
# Downloads a TUM RGB-D or Bonn RGB-D Dynamic sequence from its official site and unpacks it into the layout the
# sequence reader reads (rgb/, depth/, rgb.txt, depth.txt, groundtruth.txt) as DEST/NAME.
#   scripts/fetch_data.sh [--from ARCHIVE] NAME [DEST]     e.g. scripts/fetch_data.sh freiburg3_walking_xyz
#   scripts/fetch_data.sh --list | --help
# DEST defaults to $AMOS_DATA_DIR, else ../shared/data beside the checkout (where the tests look, see README).
# --from takes the archive from a local file or another URL (a mirror, file://) instead of the official site.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
tum_url=https://cvg.cit.tum.de/rgbd/dataset
bonn_url=https://www.ipb.uni-bonn.de/html/projects/rgbd_dynamic2019

tum_names=(
  freiburg1_360 freiburg1_desk freiburg1_desk2 freiburg1_floor freiburg1_plant freiburg1_room freiburg1_rpy
  freiburg1_teddy freiburg1_xyz
  freiburg2_360_hemisphere freiburg2_360_kidnap freiburg2_coke freiburg2_desk freiburg2_desk_with_person
  freiburg2_dishes freiburg2_flowerbouquet freiburg2_flowerbouquet_brownbackground freiburg2_large_no_loop
  freiburg2_large_with_loop freiburg2_metallic_sphere freiburg2_metallic_sphere2 freiburg2_pioneer_360
  freiburg2_pioneer_slam freiburg2_pioneer_slam2 freiburg2_pioneer_slam3 freiburg2_rpy freiburg2_xyz
  freiburg3_cabinet freiburg3_large_cabinet freiburg3_long_office_household freiburg3_nostructure_notexture_far
  freiburg3_nostructure_notexture_near_withloop freiburg3_nostructure_texture_far
  freiburg3_nostructure_texture_near_withloop freiburg3_sitting_halfsphere freiburg3_sitting_rpy
  freiburg3_sitting_static freiburg3_sitting_xyz freiburg3_structure_notexture_far
  freiburg3_structure_notexture_near freiburg3_structure_texture_far freiburg3_structure_texture_near
  freiburg3_teddy freiburg3_walking_halfsphere freiburg3_walking_rpy freiburg3_walking_static freiburg3_walking_xyz
)
bonn_names=(
  bonn_balloon bonn_balloon2 bonn_balloon_tracking bonn_balloon_tracking2 bonn_crowd bonn_crowd2 bonn_crowd3
  bonn_kidnapping_box bonn_kidnapping_box2 bonn_moving_nonobstructing_box bonn_moving_nonobstructing_box2
  bonn_moving_obstructing_box bonn_moving_obstructing_box2 bonn_person_tracking bonn_person_tracking2
  bonn_placing_nonobstructing_box bonn_placing_nonobstructing_box2 bonn_placing_nonobstructing_box3
  bonn_placing_obstructing_box bonn_removing_nonobstructing_box bonn_removing_nonobstructing_box2
  bonn_removing_obstructing_box bonn_static bonn_static_close_far bonn_synchronous bonn_synchronous2
)

usage() {
  sed -n '2,7s/^# \{0,1\}//p' "$0"
}
fail() { echo "fetch_data.sh: error: $*" >&2; exit 1; }
known() { local n; for n in "${@:2}"; do [[ "$n" == "$1" ]] && return 0; done; return 1; }

from=""
args=()
while (($#)); do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --list)
      echo "TUM RGB-D ($tum_url):"; printf '  %s\n' "${tum_names[@]}"
      echo "Bonn RGB-D Dynamic ($bonn_url):"; printf '  %s\n' "${bonn_names[@]}"
      exit 0 ;;
    --from) (($# >= 2)) || fail "--from needs an archive path or URL"; from=$2; shift ;;
    -*) fail "unknown option $1 (see --help)" ;;
    *) args+=("$1") ;;
  esac
  shift
done
((${#args[@]} >= 1 && ${#args[@]} <= 2)) || { usage >&2; exit 2; }
name=${args[0]}
dest=${args[1]:-${AMOS_DATA_DIR:-$root/../shared/data}}

if known "$name" "${tum_names[@]}"; then
  freiburg=${name%%_*}  # freiburg<N>
  url="$tum_url/$freiburg/rgbd_dataset_$name.tgz"
  format=tgz
elif known "$name" "${bonn_names[@]}"; then
  url="$bonn_url/rgbd_bonn_${name#bonn_}.zip"
  format=zip
else
  fail "unknown sequence '$name'; known names: scripts/fetch_data.sh --list"
fi
[[ -n "$from" ]] && url=$from

mkdir -p "$dest"
target="$dest/$name"
[[ ! -e "$target" ]] || fail "$target already exists; remove it first to fetch $name again"

# Everything happens in a temporary folder inside DEST (the final move is a rename); removed on any exit.
work=$(mktemp -d "$dest/.fetch_$name.XXXXXX")
trap 'rm -rf "$work"' EXIT

archive="$work/archive.$format"
echo "fetch_data.sh: $name from $url" >&2
case "$url" in
  *://*)
    if command -v curl > /dev/null; then
      curl --fail --location --show-error --output "$archive.part" "$url" || fail "could not download $url"
    elif command -v wget > /dev/null && [[ "$url" != file://* ]]; then
      wget --output-document="$archive.part" "$url" || fail "could not download $url"
    else
      fail "neither curl nor wget is installed (apt-get install curl)"
    fi ;;
  *)
    [[ -f "$url" ]] || fail "archive $url not found"
    cp -- "$url" "$archive.part" ;;
esac
mv -- "$archive.part" "$archive"

mkdir "$work/unpacked"
case "$format" in
  tgz) tar -xzf "$archive" -C "$work/unpacked" || fail "$url is not a readable .tgz archive" ;;
  zip)
    if command -v unzip > /dev/null; then
      unzip -q "$archive" -d "$work/unpacked" || fail "$url is not a readable .zip archive"
    else
      python3 -m zipfile -e "$archive" "$work/unpacked" || fail "$url is not a readable .zip archive"
    fi ;;
esac

# The archives hold one folder (rgbd_dataset_<name>, rgbd_bonn_<name>); take the one with rgb.txt.
sequence=$(find "$work/unpacked" -maxdepth 2 -name rgb.txt -printf '%h\n' | head -n 1)
[[ -n "$sequence" ]] || fail "the archive from $url holds no rgb.txt: not a TUM/Bonn sequence"
for needed in rgb.txt depth.txt rgb depth; do
  [[ -e "$sequence/$needed" ]] || fail "the archive from $url lacks $needed beside rgb.txt"
done
[[ -f "$sequence/groundtruth.txt" ]] || echo "fetch_data.sh: warning: $name has no groundtruth.txt" >&2

mv -- "$sequence" "$target"
frames=$(grep -c -v '^#' "$target/rgb.txt" || true)
echo "fetch_data.sh: $name: $frames RGB frames in $(cd "$target" && pwd)"
