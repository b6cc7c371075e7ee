#!/usr/bin/env bash
# Installs the Debian packages of the optional fuzz build (scripts/fuzz.sh) on top of scripts/install_deps.sh's:
# clang and compiler-rt, which holds libFuzzer and the sanitizer runtimes. Idempotent.
set -euo pipefail
source "$(dirname "$0")/apt_install.sh"
apt_install install_fuzz_deps clang libclang-rt-dev
