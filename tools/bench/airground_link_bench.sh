#!/usr/bin/env bash
# The downlink figures of docs/benchmarks/airground.md: air and ground in two network namespaces
# joined by a veth pair (as tests/integration/airground_test.cpp), `paper` simulated for 250
# frames (seed 11), bringup/air.yaml + bringup/ground.yaml.
#   1. lossless: payload bytes per downlink topic (uavmot-downlink's count) and everything the air
#      sent into the link (veth tx counters), per frame;
#   2. live, source at 25 fps: the air's bytes/s on the wire, second by second, and `uavmot status`
#      on the ground mid-run (bytes/s per topic as the downlink and the sink count them);
#   3. the same with the JPEG preview on (air.yaml's preview defaults, 5 Hz): per topic again.
#   sudo bash tools/bench/airground_link_bench.sh [OUT]   (OUT default out/bench; needs build/bin)
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$(mkdir -p "${1:-out/bench}" && cd "${1:-out/bench}" && pwd)
bin=$PWD/build/bin
domain=138  # link; the UAV's own processes use 139
air=uavmot-bench-air-$$ ground=uavmot-bench-ground-$$ air_dev=vba$$ ground_dev=vbg$$
cleanup() {
  for ns in $air $ground; do
    for pid in $(ip netns pids $ns 2>/dev/null); do kill -9 $pid 2>/dev/null || true; done
    ip netns del $ns 2>/dev/null || true
  done
}
trap cleanup EXIT
ip netns add $air && ip netns add $ground
ip link add $air_dev type veth peer name $ground_dev
ip link set $air_dev netns $air && ip link set $ground_dev netns $ground
ip -n $air addr add 10.200.0.1/24 dev $air_dev && ip -n $ground addr add 10.200.0.2/24 dev $ground_dev
for ns in $air $ground; do ip -n $ns link set lo up; done
ip -n $air link set $air_dev up && ip -n $ground link set $ground_dev up
tx() { ip netns exec $air cat /sys/class/net/$air_dev/statistics/tx_$1; }

seq=$out/paper250
[ -f "$seq/seqinfo.ini" ] || "$bin/uavmot" sim --preset paper --seed 11 --frames 250 --out "$seq" --quiet
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average: $(cut -d' ' -f1-3 /proc/loadavg)"

# run MODE [NAME [--set ... for the air]]: both halves to the end; sets $bytes, $packets; the logs
# are in $out/link-NAME-*.log.
run() {
  local mode=$1 name=${2:-$1}
  shift $(($# < 2 ? $# : 2))
  local b0 p0
  b0=$(tx bytes) p0=$(tx packets)
  ip netns exec $ground "$bin/uavmot" launch bringup/ground.yaml --input "$seq" --out "$out/link-$name" \
    --set domain=$domain --set mode=$mode --set preview_dir="$out/link-$name-preview" >"$out/link-$name-ground.log" 2>&1 &
  local g=$!
  ip netns exec $air "$bin/uavmot" launch bringup/air.yaml --input "$seq" --out "$out/link-$name-air" \
    --set domain=$domain --set air_domain=$((domain + 1)) --set mode=$mode "$@" >"$out/link-$name-air.log" 2>&1 &
  local a=$!
  if [ "$mode" = live ]; then
    : >"$out/link-$name-tx.txt"
    while kill -0 $g 2>/dev/null; do
      echo "$(date +%s.%N) $(tx bytes) $(tx packets)" >>"$out/link-$name-tx.txt"
      sleep 1
    done &
    # Discovery and start-up (slow on a loaded machine), then data for a few seconds.
    local until=$((SECONDS + 60))
    while [ $(($(tx bytes) - b0)) -lt 300000 ] && [ $SECONDS -lt $until ]; do sleep 0.5; done
    sleep 2
    ip netns exec $ground "$bin/uavmot" status --once --wait 2.5 --domain $domain --transport udp >"$out/link-$name-status.txt" 2>&1 || true
  fi
  wait $g && wait $a
  bytes=$(($(tx bytes) - b0)) packets=$(($(tx packets) - p0))
}

run lossless
echo
echo "== lossless, 250 frames: payload per downlink topic (uavmot-downlink's count)"
grep -oE 'uavmot/(downlink/[a-z]+|health): [0-9]+ samples, [0-9]+ bytes' "$out/link-lossless-air.log" |
  awk -F'[ :,]+' '{printf "%-26s %5d samples %8d bytes %6.0f bytes/frame %.3f Mbit/s at 25 fps\n", $1, $2, $4, $4/250, $4*25*8/250/1e6}'
echo "on the wire (air veth tx): $bytes bytes, $packets packets: $((bytes / 250)) bytes/frame," \
  "$(awk -v b=$bytes 'BEGIN{printf "%.3f", b*25*8/250/1e6}') Mbit/s at 25 fps"

run live
echo
echo "== live, source at 25 fps: air -> ground on the wire, per second while data flowed (> 10 kB/s)"
awk 'NR > 1 { r = ($2 - b) / ($1 - t); if (r > 10000) { n++; s += r; if (r > m) m = r; printf "%.0f ", r * 8 / 1000 } }
     { t = $1; b = $2 } END { printf "kbit/s\nmean %.3f Mbit/s, max %.3f Mbit/s over %d s\n", s / n * 8 / 1e6, m * 8 / 1e6, n }' \
  "$out/link-live-tx.txt"
echo "whole run: $bytes bytes, $packets packets"
echo
echo "== uavmot status on the ground, mid-run"
cat "$out/link-live-status.txt"

run live live-preview --set preview_rate=5
echo
echo "== live with the preview (5 Hz, air.yaml's default size, quality and share): per second on the wire"
awk 'NR > 1 { r = ($2 - b) / ($1 - t); if (r > 10000) { n++; s += r; if (r > m) m = r; printf "%.0f ", r * 8 / 1000 } }
     { t = $1; b = $2 } END { printf "kbit/s\nmean %.3f Mbit/s, max %.3f Mbit/s over %d s\n", s / n * 8 / 1e6, m * 8 / 1e6, n }' \
  "$out/link-live-preview-tx.txt"
echo "whole run: $bytes bytes, $packets packets"
grep -E 'uavmot/(downlink/[a-z]+|health): [0-9]+ samples|preview: ' "$out/link-live-preview-air.log" | sed 's/^.*\] //'
grep -E 'received' "$out/link-live-preview-ground.log" | sed 's/^.*\] //'
echo
echo "== uavmot status on the ground, mid-run, with the preview"
cat "$out/link-live-preview-status.txt"
