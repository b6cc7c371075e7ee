#!/usr/bin/env bash
# Command (2) of the README: installs the dependencies, builds everything and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/install_ros_deps.sh  # the optional ROS 1 part (AMOS_WITH_ROS), tested too: docs/ros.md
bash scripts/build.sh -DAMOS_BUILD_TESTS=ON
ctest --test-dir build --output-on-failure -j "${AMOS_JOBS:-$(nproc)}"
