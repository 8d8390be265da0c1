#!/usr/bin/env bash
# The README's main command: install, build, and run the chain end to end.
# Today: the video source streams the CLIF 2007 aerial frames through Fast DDS to a subscriber
# that records what it received; the full chain replaces this as its layers land.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_deps.sh
bash tools/build.sh
out=${1:-out/demo}
data=${UAVMOT_SHARED_DATA:-$(cd .. && pwd)/shared/data}
rm -rf "$out"; mkdir -p "$out"
bin=build/bin
"$bin/uavmot" framesink --out "$out/received" --domain 7 &
sink=$!
"$bin/uavmot" source "$data/clif2007/jpg" --domain 7 --mode lossless
wait "$sink"
echo "demo: $(($(wc -l <"$out/received/frames.csv") - 1)) frames received over DDS -> $out/received/frames.csv"
