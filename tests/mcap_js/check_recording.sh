#!/usr/bin/env bash
# Runs check_recording.mjs, installing the pinned node packages on first use (as run.sh does).
#   check_recording.sh RECORDING.mcap EXPECTED_JSON
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "check_recording: node and npm are required (bash tools/install_deps.sh)" >&2
  exit 1
fi
if [[ ! -f "$here/node_modules/.package-lock.json" || "$here/package-lock.json" -nt "$here/node_modules/.package-lock.json" ]]; then
  (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
fi
exec node "$here/check_recording.mjs" "$@"
