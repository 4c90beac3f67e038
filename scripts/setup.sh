#!/usr/bin/env bash
# Installs imcol's build dependencies (Debian 12, as root) and builds into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ $(id -u) -eq 0 ]] && command -v apt-get >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends \
    cmake ninja-build g++ libsundials-dev libeigen3-dev libfftw3-dev libcli11-dev libtomlplusplus-dev \
    nlohmann-json3-dev libgtest-dev libbenchmark-dev libcerf-dev python3-matplotlib >/dev/null
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
