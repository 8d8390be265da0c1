#!/usr/bin/env bash
# Runs check_recording.mjs, installing the pinned node packages on first use (as run.sh does).
#   check_recording.sh RECORDING.mcap EXPECTED_JSON
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
source "$here/../support/node_packages.sh"
require_tools check_recording node npm
install_node_packages "$here"
exec node "$here/check_recording.mjs" "$@"
