#!/bin/bash
# Installs the Debian packages (when missing), builds in ./build and runs every test with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
PKGS="g++ cmake make libcgal-dev libgmp-dev libmpfr-dev libboost-dev libboost-test-dev libboost-program-options-dev libeigen3-dev"
missing=""
for p in $PKGS; do dpkg -s "$p" > /dev/null 2>&1 || missing="$missing $p"; done
if [ -n "$missing" ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON
cmake --build build -j"$(nproc)"
cd build && ctest -j"$(nproc)" --output-on-failure
