#!/usr/bin/env bash
# The live-mode figures of docs/benchmarks/live.md: simulate `paper` (1024x768) and `hd` (1920x1080),
# both 25 fps, and run each through `uavmot launch bringup/local.yaml --set mode=live` under
# uavmot-bench-live (end-to-end latency median/p99, CPU time and drops per component).
#   bash tools/bench/live_bench.sh [OUT]   (OUT default out/bench; needs build/bin; DDS domain
#   $UAVMOT_BENCH_DOMAIN, default 48)
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/bench}
bin=build/bin
mkdir -p "$out"
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average: $(cut -d' ' -f1-3 /proc/loadavg)"
for preset in paper hd; do
  [ -f "$out/$preset/seqinfo.ini" ] || "$bin/uavmot" sim --preset "$preset" --seed 1 --frames 250 --out "$out/$preset" --quiet
  echo
  echo "== $preset"
  "$bin/uavmot-bench-live" --input "$out/$preset" --out "$out/$preset-tracks" --json "$out/live-$preset.json" --domain "${UAVMOT_BENCH_DOMAIN:-48}" \
    2>"$out/live-$preset.log"
  echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
done
