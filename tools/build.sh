#!/usr/bin/env bash
# Configures and builds uavmot into build/ (Release, warnings as errors).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${UAVMOT_BUILD_DIR:-build}
# ccache keys on paths relative to here, so another clone of the repo reuses the cache.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(cd .. && pwd)}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DUAVMOT_WERROR=ON ${UAVMOT_CMAKE_ARGS:-} >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
