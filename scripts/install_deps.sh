#!/usr/bin/env bash
# Installs every Debian package the project needs. Idempotent: when all are present it only checks and returns.
# Nothing is downloaded from anywhere but Debian's package archive.
set -euo pipefail
source "$(dirname "$0")/apt_install.sh"
apt_install install_deps \
  build-essential cmake ninja-build pkg-config python3 universal-ctags \
  libeigen3-dev libopencv-dev libopencv-contrib-dev libceres-dev libpng-dev libjpeg-dev libdeflate-dev \
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev \
  libgtest-dev libgmock-dev libbenchmark-dev ccache \
  libopenni2-dev \
  libcpp-httplib-dev libjs-three chromium \
  pybind11-dev python3-dev python3-numpy python3-opencv \
  libopen3d-dev
