#!/usr/bin/env bash
# The real-video check: runs `uavmot process` on the real aerial sequences shipped in data/ (no
# ground truth: on these flights almost everything that shows is static structure or parked) and
# reports, per sequence, the confirmed tracks and confirmed boxes per frame, with an annotated frame
# (PNG, from the annotated H.264 video) for a person to look at.
#   bash tools/real_video_check.sh [--out DIR] [--images DIR] [--config FILE]
#     --out     results per sequence (default out/real_video)
#     --images  where the annotated frames go (default: under --out; docs/images/real_video for the docs)
#     --config  chain configuration YAML for every sequence (default: the built-in defaults)
#   UAVMOT_BIN=OTHER/bin/uavmot runs another build (an experiment's).
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/real_video images="" config=""
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift ;;
    --images) images=$2; shift ;;
    --config) config=$2; shift ;;
    -h|--help) sed -n 2,10p "$0"; exit 0 ;;
    *) echo "real_video_check: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done
images=${images:-$out/images}
bin=${UAVMOT_BIN:-build/bin/uavmot}
[ -x "$bin" ] || { echo "real_video_check: $bin is missing; build first (bash tools/build.sh)" >&2; exit 1; }
mkdir -p "$out" "$images"

# name|input|frame to show (1-based)
sequences=(
  "clif2007|data/clif2007/jpg|200"
  "aphill_short|data/aphill/aphill_short.ts|40"
  "aphill_1fps|data/aphill/aphill_240_1fps_crf32.mp4|200"
)
printf '%-14s %7s %10s %10s %12s %9s\n' sequence frames confirmed boxes boxes/frame seconds
for entry in "${sequences[@]}"; do
  IFS='|' read -r name input show <<<"$entry"
  run="$out/$name"
  rm -rf "$run"
  start=$SECONDS
  "$bin" process "$input" --out "$run" --video "$run/annotated.mp4" --quiet ${config:+--config "$config"} \
    >"$run.log" 2>&1 || { echo "real_video_check: uavmot process failed on $input (log: $run.log)" >&2; tail -5 "$run.log" >&2; exit 1; }
  frames=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['frames'])" "$run/summary.json")
  confirmed=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['confirmed_tracks'])" "$run/summary.json")
  boxes=$(wc -l <"$run/tracks.txt")
  printf '%-14s %7d %10d %10d %12.2f %9d\n' "$name" "$frames" "$confirmed" "$boxes" \
    "$(python3 -c "print($boxes / max(1, $frames))")" "$((SECONDS - start))"
  # The annotated frame: frame `show` of the annotated video (select counts from 0).
  ffmpeg -loglevel error -y -i "$run/annotated.mp4" -vf "select=eq(n\,$((show - 1)))" -frames:v 1 "$images/real_$name.png"
done
echo "annotated frames: $images/real_*.png; results and videos: $out/<sequence>/"
