#!/usr/bin/env bash
# ctest mcap_official_reader: writes the sample recordings, then checks them with the official
# MCAP reader from npm. Installs the pinned node packages on first use.
#   run.sh MAKE_SAMPLE_BINARY MCAP_INFO_BINARY OUT_DIR IDL_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
make_sample=$1
mcap_info=$2
out=$3
idl=$4
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "mcap_official_reader: node and npm are required (bash tools/install_deps.sh)" >&2
  exit 1
fi
# (Re)install when node_modules is missing or older than the lock file.
if [[ ! -f "$here/node_modules/.package-lock.json" || "$here/package-lock.json" -nt "$here/node_modules/.package-lock.json" ]]; then
  (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
fi
rm -rf "$out"
"$make_sample" "$out" "$idl"
node "$here/validate.mjs" "$out" "$mcap_info"
