#!/usr/bin/env bash
# CI stage fresh-clone: clones this repository (its committed HEAD) into an empty folder with
# nothing beside it and runs the README's demo there, so a user's bare clone is proven to build,
# simulate, run the distributed chain, score and write the video without anything outside it
# (no ../shared, no UAVMOT_DATA_DIR).
#   bash tools/fresh_clone_demo.sh [--frames N]     (default 60 frames; the demo's own default is the preset's)
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
frames=60
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames=$2; shift ;;
    -h|--help) sed -n 2,7p "$0"; exit 0 ;;
    *) echo "fresh_clone_demo: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done
if [ -n "$(git -C "$repo" status --porcelain --untracked-files=no)" ]; then
  echo "fresh_clone_demo: note: uncommitted changes in $repo are not in the clone (it takes HEAD)"
fi
parent=$(mktemp -d /tmp/uavmot-fresh.XXXXXX)
trap 'rm -rf "$parent"' EXIT
# The clone keeps the repo's folder name: tools/build.sh keys ccache on paths relative to the
# clone's parent, so the same name reuses this build's cache.
clone="$parent/$(basename "$repo")"
git clone --quiet --no-hardlinks "$repo" "$clone"
echo "fresh_clone_demo: cloned $(git -C "$clone" rev-parse --short HEAD) into $clone; beside it: $(ls -A "$parent" | tr '\n' ' ')"
cd "$clone"
env -u UAVMOT_DATA_DIR -u UAVMOT_BUILD_DIR bash tools/demo.sh --frames "$frames" out/demo
for f in out/demo/tracks/tracks.txt out/demo/eval.json out/demo/demo.mp4; do
  [ -s "$f" ] || { echo "fresh_clone_demo: the demo left no $f" >&2; exit 1; }
done
echo "fresh_clone_demo: the demo ran from a bare clone: $(cut -d, -f2 out/demo/tracks/tracks.txt | sort -u | wc -l) tracks, $(du -h out/demo/demo.mp4 | cut -f1) video"
