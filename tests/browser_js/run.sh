#!/usr/bin/env bash
# ctest browser_video_playback: the annotated video `uavmot process --video` writes (H.264, a short
# simulated paper sequence) plays in headless Chromium: a decoded frame of the video's size that is
# not blank (play.mjs). Uses Debian's /usr/bin/chromium through playwright-core (no browser
# download). Installs the pinned node packages on first use.
#   run.sh BIN_DIR OUT_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin=$1
out=$2
source "$here/../support/node_packages.sh"
require_tools browser_video_playback node npm /usr/bin/chromium
install_node_packages "$here"
rm -rf "$out"
mkdir -p "$out"
"$bin/uavmot-sim" --preset paper --seed 1 --frames 30 --out "$out/paper" > "$out/sim.log"
"$bin/uavmot-process" "$out/paper" --out "$out/result" --video "$out/annotated.mp4" --quiet
node "$here/play.mjs" "$out/annotated.mp4" --size 1024x768 --png "$out/frame.png"
