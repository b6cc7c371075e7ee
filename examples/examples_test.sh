#!/usr/bin/env bash
# The examples' tests (examples/CMakeLists.txt sets the environment):
#   examples_test.sh install   cmake --install the build into $AMOS_PREFIX (emptied first)
#   examples_test.sh headers   compile each installed public header alone, with only the installed include path
#                              (and OpenCV's and Eigen's)
#   examples_test.sh build     build examples/cpp out of tree against $AMOS_PREFIX into
#                              $AMOS_BUILD_DIR/examples-cpp-build (emptied first), for the two tests below
#   examples_test.sh track     run the C++ example track_folder (examples_test.sh build) and
#                              examples/python/track_folder.py on tum_fr2_desk_first50 (configs/tum2.yaml, mode full,
#                              deterministic), and check both trajectories equal the installed
#                              `amos-slam run --deterministic`'s trajectory.txt byte for byte; also writes a mask
#                              overlay with examples/python/show_mask.py
#   examples_test.sh detector  render a synthetic sequence with movers no front-end stage sees in mode none
#                              (`amos-slam synth --preset objects_xyz`), run examples/python/with_my_detector.py on it
#                              (the caller's masks: the sequence's own mover masks) and check that its masks removed
#                              keypoints and that its trajectory is evaluated against the ground truth
#   examples_test.sh dense     run the C++ example dense_map (examples_test.sh build) and
#                              examples/python/dense_map.py on tum_fr2_desk_first50 (configs/tum2.yaml, mode none, deterministic) and check that
#                              their mesh.ply (vertices, normals, colours, triangles) and floor plan equal the
#                              installed `amos-slam run --dense --deterministic`'s byte for byte (skipped, 77,
#                              without Open3D)
# The data is looked for in $AMOS_DATA_DIR (else the build's AMOS_DATA_DIR); without it the test is skipped (77),
# or fails with AMOS_REQUIRE_SHARED_DATA=1. The runs are made in a scratch folder outside both trees, with
# AMOS_MODELS unset, so the programs find the models in the installed data folder.
set -euo pipefail
: "${AMOS_BUILD_DIR:?}" "${AMOS_PREFIX:?}" "${AMOS_SOURCE_DIR:?}"
prefix=$AMOS_PREFIX
unset AMOS_MODELS

install_package() {
  rm -rf "$prefix"
  cmake --install "$AMOS_BUILD_DIR" --prefix "$prefix" > "$AMOS_BUILD_DIR/examples-install.log"
  for f in bin/amos-slam include/amos/slam.h lib/cmake/AmosSlam/AmosSlamConfig.cmake \
           lib/pkgconfig/amos-slam.pc share/amos-slam/models/orb_vocabulary.voc; do
    [[ -f "$prefix/$f" ]] || { echo "not installed: $f" >&2; exit 1; }
  done
  echo "installed into $prefix: $(find "$prefix" -type f | wc -l) files"
}

compile_headers() {
  local flags
  flags=$(pkg-config --cflags opencv4 eigen3)
  for h in "$prefix"/include/amos/*.h; do
    # shellcheck disable=SC2086
    echo "#include <amos/$(basename "$h")>" | "${AMOS_CXX:-c++}" -std=c++17 -fsyntax-only -Wall -Wextra -Werror \
      -I"$prefix/include" $flags -x c++ - || { echo "FAILED: $h does not compile alone" >&2; exit 1; }
    echo "compiles alone: include/amos/$(basename "$h")"
  done
  # The pkg-config file: a program built and linked with its flags alone.
  work=$(mktemp -d "${TMPDIR:-/tmp}/amos-pkgconfig.XXXXXX")
  trap 'rm -rf "$work"' EXIT
  printf '%s\n' '#include <amos/slam.h>' '#include <cstdio>' \
    'int main() { std::printf("%s %s\n", amos::kVersion, amos::toString(amos::TrackingState::kOk)); }' \
    > "$work/main.cc"
  # eval: pkg-config escapes the quotes of the data folder's string for a shell (as make passes it to one).
  eval "\"\${AMOS_CXX:-c++}\" -std=c++17 \"\$work/main.cc\" -o \"\$work/main\" \
    $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs amos-slam)"
  [[ "$("$work/main")" == "$(sed -n 's/^Version: //p' "$prefix/lib/pkgconfig/amos-slam.pc") ok" ]]
  echo "pkg-config: a program links with amos-slam.pc's flags"
}

# The real sequence both examples' tests use (sets $sequence; exits 77, or 1 with AMOS_REQUIRE_SHARED_DATA=1,
# when it is missing).
find_sequence() {
  sequence=${AMOS_DATA_DIR:-$AMOS_DEFAULT_DATA_DIR}/tum_fr2_desk_first50
  if [[ ! -d "$sequence" ]]; then
    echo "real data missing: $sequence (set AMOS_DATA_DIR; scripts/fetch_data.sh)" >&2
    [[ "${AMOS_REQUIRE_SHARED_DATA:-0}" == 1 ]] && exit 1
    exit 77
  fi
}

# examples/cpp built out of tree against the installed package, once for the tests that run it.
cpp_examples=$AMOS_BUILD_DIR/examples-cpp-build
build_cpp_examples() {
  rm -rf "$cpp_examples"
  cmake -S "$AMOS_SOURCE_DIR/examples/cpp" -B "$cpp_examples" -DCMAKE_PREFIX_PATH="$prefix" \
    > "$AMOS_BUILD_DIR/examples-cpp-build.log" || { cat "$AMOS_BUILD_DIR/examples-cpp-build.log"; exit 1; }
  cmake --build "$cpp_examples" >> "$AMOS_BUILD_DIR/examples-cpp-build.log" ||
    { cat "$AMOS_BUILD_DIR/examples-cpp-build.log"; exit 1; }
  for program in track_folder dense_map; do
    [[ -x "$cpp_examples/$program" ]] || { echo "not built: $cpp_examples/$program" >&2; exit 1; }
  done
  echo "built examples/cpp against $prefix into $cpp_examples"
}

# A scratch folder for a test's runs (the current folder after; removed at exit).
enter_scratch_folder() {
  work=$(mktemp -d "${TMPDIR:-/tmp}/amos-examples.XXXXXX")
  trap 'rm -rf "$work"' EXIT
  cd "$work"
}

track() {
  local sequence config
  find_sequence
  config=$AMOS_SOURCE_DIR/configs/tum2.yaml
  enter_scratch_folder
  "$prefix/bin/amos-slam" run --sequence "$sequence" --config "$config" --mode full --deterministic \
    --output run > run.log 2>&1 || { tail -20 run.log; exit 1; }
  "$cpp_examples/track_folder" "$sequence" "$config" cpp_trajectory.txt full
  cmp run/trajectory.txt cpp_trajectory.txt
  echo "C++ example: trajectory identical to amos-slam run's ($(grep -vc '^#' cpp_trajectory.txt) poses)"
  if [[ "${AMOS_WITH_PYTHON:-0}" == 1 ]]; then
    local site=$prefix/lib/python3/dist-packages
    PYTHONPATH=$site "$AMOS_PYTHON" "$AMOS_SOURCE_DIR/examples/python/track_folder.py" "$sequence" "$config" \
      py_trajectory.txt --mode full
    cmp run/trajectory.txt py_trajectory.txt
    echo "Python example: trajectory identical to amos-slam run's"
    PYTHONPATH=$site "$AMOS_PYTHON" "$AMOS_SOURCE_DIR/examples/python/show_mask.py" "$sequence" "$config" 30 \
      overlay.png full
    [[ -s overlay.png ]]
  fi
}

# The same files, byte for byte, as the run's (named in the message).
same_dense_files() {
  local from=$1 name
  for name in mesh.ply occupancy.pgm occupancy.yaml; do
    if [[ -f "run/$name" || -f "$from/$name" ]]; then
      cmp "run/$name" "$from/$name"
    fi
  done
  echo "$from: mesh.ply identical to amos-slam run --dense's ($(sed -n 's/^element vertex //p' "$from/mesh.ply" |
    head -1) vertices, sha256 $(sha256sum "$from/mesh.ply" | cut -c1-16)), floor plan" \
    "$([[ -f "$from/occupancy.pgm" ]] && echo identical || echo "absent in both")"
}

dense() {
  local sequence config
  [[ "${AMOS_WITH_DENSE:-0}" == 1 ]] || { echo "the library is built without the dense map (Open3D)" >&2; exit 77; }
  find_sequence
  config=$AMOS_SOURCE_DIR/configs/tum2.yaml
  enter_scratch_folder
  "$prefix/bin/amos-slam" run --sequence "$sequence" --config "$config" --mode none --deterministic --dense \
    --output run > run.log 2>&1 || { tail -20 run.log; exit 1; }
  "$cpp_examples/dense_map" "$sequence" "$config" cpp none
  same_dense_files cpp
  if [[ "${AMOS_WITH_PYTHON:-0}" == 1 ]]; then
    PYTHONPATH=$prefix/lib/python3/dist-packages "$AMOS_PYTHON" "$AMOS_SOURCE_DIR/examples/python/dense_map.py" \
      "$sequence" "$config" py --mode none
    same_dense_files py
  fi
}

detector() {
  [[ "${AMOS_WITH_PYTHON:-0}" == 1 ]] || { echo "the Python module is not built" >&2; exit 77; }
  work=$(mktemp -d "${TMPDIR:-/tmp}/amos-detector.XXXXXX")
  trap 'rm -rf "$work"' EXIT
  cd "$work"
  "$prefix/bin/amos-slam" synth --preset objects_xyz --seed 1 --frames 60 --output seq > synth.log 2>&1 ||
    { tail -20 synth.log; exit 1; }
  PYTHONPATH=$prefix/lib/python3/dist-packages "$AMOS_PYTHON" \
    "$AMOS_SOURCE_DIR/examples/python/with_my_detector.py" seq "$AMOS_SOURCE_DIR/configs/tum3.yaml" traj.txt | tee out.txt
  removed=$(sed -n 's/.*the masks removed \([0-9]*\) keypoints.*/\1/p' out.txt)
  [[ "${removed:-0}" -gt 100 ]] || { echo "the caller's masks removed ${removed:-no} keypoints" >&2; exit 1; }
  "$prefix/bin/amos-slam" eval --gt seq/groundtruth.txt --est traj.txt
}

case "${1:-}" in
  install) install_package ;;
  headers) compile_headers ;;
  build) build_cpp_examples ;;
  track) track ;;
  detector) detector ;;
  dense) dense ;;
  *) echo "usage: $0 install|headers|build|track|detector|dense" >&2; exit 2 ;;
esac
