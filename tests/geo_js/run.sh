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
source "$here/../support/node_packages.sh"
require_tools geo_geojson_validator node npm
install_node_packages "$here"
rm -rf "$out"
"$make_geojson" "$ts" "$out"
node "$here/validate.mjs" "$out/tracks.geojson" "$out/footprints.json"
