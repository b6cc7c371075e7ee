#!/usr/bin/env bash
# Installs the Debian packages of the optional fuzz build (scripts/fuzz.sh) on top of scripts/install_deps.sh's:
# clang and compiler-rt, which holds libFuzzer and the sanitizer runtimes. Idempotent.
set -euo pipefail
PACKAGES=(clang libclang-rt-dev)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_fuzz_deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "install_fuzz_deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
