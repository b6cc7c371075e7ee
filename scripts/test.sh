#!/usr/bin/env bash
# Command (2) of the README: installs every dependency, builds everything with the tests and runs the whole suite.
# The optional parts are asked for explicitly: a build/ first configured by the demo (without their packages) has
# them off in its cache, and a part that cannot be built must fail here rather than leave its tests out.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/check_disk_space.sh
bash scripts/install_deps.sh --all
bash scripts/install_ros_deps.sh  # the optional ROS 1 part (AMOS_WITH_ROS), tested too: docs/ros.md
bash scripts/build.sh -DAMOS_BUILD_TESTS=ON -DAMOS_BUILD_VIEWER=ON -DAMOS_WITH_OPEN3D=ON -DAMOS_BUILD_PYTHON=ON \
  -DAMOS_WITH_OPENNI2=ON -DAMOS_WITH_ROS=ON
ctest --test-dir build --output-on-failure -j "${AMOS_JOBS:-$(nproc)}"
