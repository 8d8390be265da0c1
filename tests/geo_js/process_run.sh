#!/usr/bin/env bash
# ctest geo_process_geojson_validator: validates the tracks.geojson that `uavmot process` writes,
# with @mapbox/geojsonhint and geojson-validation, and checks that every position lies inside the
# union of the footprints (KLV frame corners) of the frames its track spans:
#   1. aphill_short.ts itself (720x480, 29.97 frames/s decoded);
#   2. a simulated sequence with traffic (uavmot sim --preset paper, 60 frames, 1024x768, 25 fps)
#      encoded to H.264 and muxed by ffmpeg with the clip's KLV stream, so the chain confirms tracks
#      and the map has features (at least 5 required). --gsd 0.35 is the simulation's own GSD (the
#      KLV's footprint would say about 0.03 m/px at 1024 px, which is not the scene's).
# Installs the pinned node packages on first use.
#   process_run.sh BIN_DIR GEO_FOOTPRINTS_BINARY TS OUT_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin=$1
footprints=$2
ts=$3
out=$4
source "$here/../support/node_packages.sh"
require_tools geo_process_geojson_validator node npm ffmpeg
install_node_packages "$here"
rm -rf "$out"
mkdir -p "$out"

echo "== aphill_short.ts"
"$bin/uavmot-process" "$ts" --out "$out/aphill" --quiet
"$footprints" "$ts" 720 480 29.97002997002997 "$out/aphill_footprints.json"
node "$here/validate.mjs" "$out/aphill/tracks.geojson" "$out/aphill_footprints.json"

echo "== simulated traffic under aphill_short.ts's KLV"
"$bin/uavmot-sim" --preset paper --seed 7 --frames 60 --out "$out/sim" > "$out/sim.log"
ffmpeg -nostdin -v error -y -framerate 25 -i "$out/sim/img1/%06d.jpg" -i "$ts" -map 0:v -map 1:d \
  -c:v libx264 -preset veryfast -crf 18 -pix_fmt yuv420p -c:d copy -f mpegts "$out/sim_klv.ts"
"$bin/uavmot-process" "$out/sim_klv.ts" --out "$out/sim_klv" --gsd 0.35 --quiet
"$footprints" "$out/sim_klv.ts" 1024 768 25 "$out/sim_klv_footprints.json"
node "$here/validate.mjs" "$out/sim_klv/tracks.geojson" "$out/sim_klv_footprints.json" --min-features 5
