#!/usr/bin/env bash
# ctest geo_geojson_validator: writes tracks.geojson for aphill_short.ts, then validates it with
# @mapbox/geojsonhint and checks each position against its frame's footprint polygon. Installs
# the pinned node packages on first use.
#   run.sh MAKE_GEOJSON_BINARY TS OUT_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
make_geojson=$1
ts=$2
out=$3
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "geo_geojson_validator: node and npm are required (bash tools/install_deps.sh)" >&2
  exit 1
fi
# (Re)install when node_modules is missing or older than the lock file.
if [[ ! -f "$here/node_modules/.package-lock.json" || "$here/package-lock.json" -nt "$here/node_modules/.package-lock.json" ]]; then
  (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
fi
rm -rf "$out"
"$make_geojson" "$ts" "$out"
node "$here/validate.mjs" "$out/tracks.geojson" "$out/footprints.json"
