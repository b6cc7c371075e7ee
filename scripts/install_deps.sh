#!/usr/bin/env bash
# Installs the Debian packages the project needs. Idempotent: when all are present it only checks and returns.
# Nothing is downloaded from anywhere but Debian's package archive.
#   install_deps.sh          everything: the core build, the tests and the optional parts (README command (2), CI)
#   install_deps.sh --core   only what the core build needs: the program and library without the optional parts
#                            (README command (1)); a build configured without the others switches those parts off.
# ccache is in the core set: installing it later would change every compile command of an existing build/ and
# so rebuild it all.
set -euo pipefail
source "$(dirname "$0")/apt_install.sh"
core=(build-essential cmake ninja-build pkg-config ccache
  libeigen3-dev libopencv-dev libopencv-contrib-dev libceres-dev libpng-dev libjpeg-dev libdeflate-dev
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev)
optional=(
  python3 libgtest-dev libgmock-dev universal-ctags   # the tests (cmake/test_labels.py), scripts/code_metrics.py
  curl                                                # scripts/fetch_data.sh downloads with it (and its test)
  libbenchmark-dev                                    # -DAMOS_BUILD_BENCH=ON
  libopenni2-dev                                      # the live camera module
  libcpp-httplib-dev libjs-three chromium             # the web viewer and report.html; chromium for its tests
  pybind11-dev python3-dev python3-numpy python3-opencv  # the Python module and its tests
  libopen3d-dev)                                      # the dense static map
case "${1:-}" in
  --core) apt_install install_deps "${core[@]}" ;;
  "" | --all) apt_install install_deps "${core[@]}" "${optional[@]}" ;;
  *) echo "install_deps.sh: unknown argument '$1' (expected --core, --all or nothing)" >&2; exit 2 ;;
esac
