#!/usr/bin/env bash
# The README's test command: installs dependencies, builds, runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_deps.sh
bash tools/build.sh
build_dir=${UAVMOT_BUILD_DIR:-build}
# Integration tests start real Fast DDS processes; run them one at a time so they
# do not compete for the two cores and shared-memory segments.
ctest --test-dir "$build_dir" --output-on-failure -j 2 -LE serial
ctest --test-dir "$build_dir" --output-on-failure -L serial
