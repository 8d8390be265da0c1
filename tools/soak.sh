#!/usr/bin/env bash
# Soak test (not in CI: it runs for many minutes): the distributed chain of bringup/local.yaml in
# lossless mode on a short simulated sequence played in a loop for FRAMES frames at the fastest
# rate, with the RSS of every component sampled from /proc. Fails when a process crashed or was
# respawned, when a component's frames in/out differ from FRAMES, or when a component's RSS grew
# by more than UAVMOT_SOAK_MAX_GROWTH_MIB after the warm-up (the first 10% of the frames).
#   tools/soak.sh [FRAMES] [OUT_DIR]      (defaults: 100000, out/soak)
# Environment: UAVMOT_BUILD_DIR (build), UAVMOT_SOAK_DOMAIN (119), UAVMOT_SOAK_SIZE (160x120),
# UAVMOT_SOAK_MAX_GROWTH_MIB (16), UAVMOT_SOAK_INTERVAL (5 s between RSS samples).
# Uses DDS on its domain: do not run it beside the integration tests (flock /work/integration.lock).
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-100000}
out=${2:-out/soak}
bin=$(pwd)/${UAVMOT_BUILD_DIR:-build}/bin
size=${UAVMOT_SOAK_SIZE:-160x120}
[[ -x $bin/uavmot-launch ]] || { echo "soak: build first (bash tools/build.sh): no $bin/uavmot-launch" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)

# A 10 s (250 frame) sequence of the 'small' preset at the soak size: the loop restarts it 400 times.
seq=$out/seq_${size}
if [[ ! -f $seq/seqinfo.ini ]]; then
  "$bin/uavmot" sim --preset small --print-scenario |
    sed -e "s/^  width: .*/  width: ${size%x*}/" -e "s/^  height: .*/  height: ${size#*x}/" >"$out/scenario.yaml"
  "$bin/uavmot" sim --scenario "$out/scenario.yaml" --seed 1 --out "$seq" --quiet
fi
rm -rf "$out/results"
python3 tools/soak_monitor.py --bin "$bin" --profile bringup/local.yaml --input "$seq" --out "$out" \
  --frames "$frames" --domain "${UAVMOT_SOAK_DOMAIN:-119}" --interval "${UAVMOT_SOAK_INTERVAL:-5}" \
  --warmup-frames $((frames / 10)) --max-growth-mib "${UAVMOT_SOAK_MAX_GROWTH_MIB:-16}"
