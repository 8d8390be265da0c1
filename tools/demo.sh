#!/usr/bin/env bash
# The README's main command: install, build, and show the whole system on a simulated UAV flight.
#   1. install the Debian packages (tools/install_deps.sh) and build (tools/build.sh);
#   2. `uavmot sim --preset paper` renders a sequence with exact ground truth;
#   3. `uavmot launch bringup/local.yaml` runs it through the distributed chain
#      (source -> motion -> segmentation -> tracking -> sink, separate processes over Fast DDS);
#   4. `uavmot eval` scores the tracks, homographies and features against the ground truth;
#   5. the annotated video (uavmot view, else uavmot process --video) is written.
# A step whose program is not built says so and is skipped.
#
#   bash tools/demo.sh [--no-build] [--frames N] [--mode lossless|live] [OUT]   (OUT default out/demo)
set -euo pipefail
cd "$(dirname "$0")/.."

build=1 frames="" mode=lossless out=out/demo
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) build=0 ;;
    --frames) frames=$2; shift ;;
    --mode) mode=$2; shift ;;
    -h|--help) sed -n 2,12p "$0"; exit 0 ;;
    *) out=$1 ;;
  esac
  shift
done

step() { printf '\n== %s\n' "$*"; }
skip() { printf '   skipped: %s\n' "$*"; }
if [ "$build" = 1 ]; then
  step "installing dependencies and building (build/)"
  bash tools/install_deps.sh
  bash tools/build.sh
fi
bin=build/bin
for p in uavmot uavmot-sim uavmot-launch; do
  [ -x "$bin/$p" ] || { echo "demo: $bin/$p is missing; build first (bash tools/build.sh)" >&2; exit 1; }
done

seq="$out/paper" tracks="$out/tracks"
rm -rf "$out"; mkdir -p "$out"
start=$SECONDS

step "simulating a UAV flight: uavmot sim --preset paper --seed 1 -> $seq"
"$bin/uavmot" sim --preset paper --seed 1 ${frames:+--frames "$frames"} --out "$seq" --quiet
echo "   $(ls "$seq/img1" | wc -l) frames, ground truth in $seq/gt"

# The annotated video: `uavmot process --video` replays the sequence offline; otherwise `uavmot view`
# subscribes to the chain while it runs and writes the mp4 itself.
video="$out/demo.mp4" view_pid=""
if [ -x "$bin/uavmot-process" ] && "$bin/uavmot-process" --help 2>&1 | grep -q -- '--video'; then
  video_by=process
elif [ -x "$bin/uavmot-view" ] && "$bin/uavmot-view" --help 2>&1 | grep -q -- '--out'; then
  video_by=view
  "$bin/uavmot" view --domain 45 --out "$video" 2>"$out/view.log" &
  view_pid=$!
else
  video_by=none
fi

step "running the distributed chain ($mode): uavmot launch bringup/local.yaml --input $seq --out $tracks"
t0=$SECONDS
"$bin/uavmot" launch bringup/local.yaml --input "$seq" --out "$tracks" --set mode="$mode" --set domain=45 >"$out/launch.log" 2>&1 || {
  echo "demo: the launch failed; its log:" >&2; tail -40 "$out/launch.log" >&2; exit 1; }
echo "   $(cut -d, -f2 "$tracks/tracks.txt" | sort -u | wc -l) tracks over $(cut -d, -f1 "$tracks/tracks.txt" | sort -u | wc -l) frames in $((SECONDS - t0)) s -> $tracks/tracks.txt (log: $out/launch.log)"

step "scoring against the ground truth: uavmot eval"
if [ -x "$bin/uavmot-eval" ]; then
  "$bin/uavmot" eval --seq "$seq" --pred "$tracks/tracks.txt" --obb "$tracks/tracks_obb.csv" \
    --homographies "$tracks/homographies.txt" --features "$tracks/features.csv" --json "$out/eval.json"
else
  skip "$bin/uavmot-eval is not built"
fi

step "annotated video (moving features yellow, clusters cyan, regions red, tracks green)"
case "$video_by" in
  process)
    "$bin/uavmot" process "$seq" --out "$out/process" --video "$video" --quiet
    echo "   uavmot process --video -> $video" ;;
  view)
    for _ in $(seq 20); do kill -0 "$view_pid" 2>/dev/null || break; sleep 0.5; done
    kill -INT "$view_pid" 2>/dev/null || true
    if wait "$view_pid" && [ -s "$video" ]; then echo "   uavmot view -> $video"; else echo "   uavmot view failed (log: $out/view.log)"; fi ;;
  *) skip "neither uavmot-view nor uavmot process --video is built" ;;
esac
echo
echo "demo: done in $((SECONDS - start)) s after the build; everything is under $out"
