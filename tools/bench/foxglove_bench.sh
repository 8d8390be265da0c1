#!/usr/bin/env bash
# The bridge-overhead figures of docs/benchmarks/foxglove.md: the chain (bringup/local.yaml) on a
# simulated `paper` sequence (1024x768, 25 fps, 250 frames) with no bridge, then with
# `uavmot foxglove` serving 0, 1 and 4 viewers (tests/foxglove_js/bench_viewer.mjs: subscribed
# to every channel, counting, not decoding). Per configuration and run:
#   live:     uavmot-bench-live (mode=live): end-to-end latency median / p99, track lists, drops,
#             CPU seconds of the chain's components / the bridge / the viewers during the run;
#   lossless: `uavmot launch` (mode=lossless) wall time -> frames per second (start-up and
#             shutdown included; tools/bench/foxglove_summary.py takes the throughput from the
#             launch logs instead and summarises the runs: `python3 tools/bench/foxglove_summary.py
#             OUT.txt OUT` with this script's output saved as OUT.txt).
#   bash tools/bench/foxglove_bench.sh [OUT] [RUNS] [VIEWER ARGS...]   (OUT default out/foxglove_bench, RUNS 2;
#   VIEWER ARGS e.g. `--prefix uavmot/foxglove/`: viewers take only the Foxglove channels;
#   DDS domain $UAVMOT_BENCH_DOMAIN, default 64; needs build/bin and tests/foxglove_js's packages;
#   UAVMOT_BENCH_BRIDGE: another uavmot-foxglove binary to measure, e.g. a copy of main's for A/B runs;
#   UAVMOT_BENCH_BRIDGE_ARGS: more bridge options, e.g. "--cpu-priority normal";
#   UAVMOT_BENCH_VIEWER_PRIORITY: idle (default) or normal. The viewers stand in for Foxglove on
#   the operators' own machines; at idle they take only CPU time the chain leaves, as remote ones
#   would take none, while they still receive and count every message)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
out=${1:-out/foxglove_bench}
runs=${2:-2}
viewer_args=("${@:3}")
domain=${UAVMOT_BENCH_DOMAIN:-64}
bin=$root/build/bin
js=$root/tests/foxglove_js
bridge_bin=${UAVMOT_BENCH_BRIDGE:-$bin/uavmot-foxglove}
read -r -a bridge_args <<<"${UAVMOT_BENCH_BRIDGE_ARGS:-}"
viewer_priority=${UAVMOT_BENCH_VIEWER_PRIORITY:-idle}
case $viewer_priority in
  idle) viewer_prefix=(chrt --idle 0) ;;
  normal) viewer_prefix=() ;;
  *) echo "UAVMOT_BENCH_VIEWER_PRIORITY must be idle or normal, not '$viewer_priority'" >&2; exit 2 ;;
esac
source "$root/tests/support/node_packages.sh"
require_tools foxglove_bench node npm
install_node_packages "$js"
mkdir -p "$out"
# CPU seconds (user + system) used so far by the given processes (none: 0).
cpu_seconds() {
  local total=0 pid
  for pid in "$@"; do
    [[ -r /proc/$pid/stat ]] || continue
    total=$((total + $(awk '{print $14 + $15}' "/proc/$pid/stat")))
  done
  python3 -c "print(f'{$total / $(getconf CLK_TCK):.2f}')"
}
seq=$out/paper
[ -f "$seq/seqinfo.ini" ] || "$bin/uavmot" sim --preset paper --seed 1 --frames 250 --out "$seq" --quiet
gsd=$(sed -n 's/^gsd=//p' "$seq/seqinfo.ini")
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average: $(cut -d' ' -f1-3 /proc/loadavg), bridge $bridge_bin ${bridge_args[*]}, viewers at $viewer_priority priority"
printf '%-8s %3s | %-11s %-9s %-8s %-12s | %-20s | %-12s | %s\n' config run "live lists" "median" "p99" "drops s/m/s/t" \
  "cpu s chain/br/view" "lossless fps" "bridge"
for run in $(seq "$runs"); do
  for config in none 0 1 4; do
    tag=$config-$run
    rm -f "$out/done-$tag" "$out"/ready-$tag-*
    pids=()
    if [[ $config != none ]]; then
      "$bridge_bin" --port 0 --domain "$domain" --transport local --gsd "$gsd" --fps 25 "${bridge_args[@]}" >"$out/bridge-$tag.log" 2>&1 &
      bridge=$!
      for _ in $(seq 100); do grep -q serving "$out/bridge-$tag.log" && break; sleep 0.1; done
      port=$(sed -n 's/.*ws:\/\/127\.0\.0\.1:\([0-9]*\).*/\1/p' "$out/bridge-$tag.log" | head -1)
      for v in $(seq "$config"); do
        "${viewer_prefix[@]}" node "$js/bench_viewer.mjs" "ws://127.0.0.1:$port" --ready "$out/ready-$tag-$v" --done "$out/done-$tag" "${viewer_args[@]}" >"$out/viewer-$tag-$v.log" 2>&1 &
        pids+=($!)
      done
      for v in $(seq "$config"); do
        for _ in $(seq 100); do [[ -f "$out/ready-$tag-$v" ]] && break; sleep 0.1; done
      done
    fi
    # CPU of the bridge and its viewers during the live run, beside the chain's own: on a machine
    # the chain saturates, what they take is what the chain loses.
    bridge_pid=$([[ $config != none ]] && echo "$bridge" || true)
    bridge_cpu0=$(cpu_seconds $bridge_pid) viewers_cpu0=$(cpu_seconds "${pids[@]}")
    # A failed run is reported as such and the next one goes on (a shared machine kills things).
    "$bin/uavmot-bench-live" --input "$seq" --out "$out/live-$tag" --json "$out/live-$tag.json" --domain "$domain" \
      >"$out/live-$tag.txt" 2>"$out/live-$tag.log" || echo '{"failed": true}' >"$out/live-$tag.json"
    bridge_cpu=$(python3 -c "print(f'{$(cpu_seconds $bridge_pid) - $bridge_cpu0:.2f}')")
    viewers_cpu=$(python3 -c "print(f'{$(cpu_seconds "${pids[@]}") - $viewers_cpu0:.2f}')")
    start=$(date +%s.%N)
    "$bin/uavmot" launch bringup/local.yaml --input "$seq" --out "$out/lossless-$tag" --set domain="$domain" >"$out/lossless-$tag.log" 2>&1 ||
      start=failed
    end=$(date +%s.%N)
    touch "$out/done-$tag"
    for p in "${pids[@]}"; do wait "$p"; done
    bridge_line=-
    if [[ $config != none ]]; then
      kill -TERM "$bridge"
      wait "$bridge" || true
      bridge_line=$(grep -o '[0-9]* messages sent, [0-9]* dropped' "$out/bridge-$tag.log" | tail -1)
    fi
    python3 - "$out/live-$tag.json" "$start" "$end" "$config" "$run" "$bridge_line" "$bridge_cpu" "$viewers_cpu" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
cpu = "-"
fps = "failed" if sys.argv[2] == "failed" else f"{250 / (float(sys.argv[3]) - float(sys.argv[2])):.1f}"
if j.get("failed"):
    live = f'{"failed":<11} {"":<9} {"":<8} {"":<12}'
else:
    c = j["components"]
    drops = "/".join(str(c.get(n, {}).get("dropped", "?")) for n in ["source", "motion", "segmentation", "tracking"])
    live = f'{j["track_lists"]:<11} {j["latency_ms"]["median"]:<9.1f} {j["latency_ms"]["p99"]:<8.1f} {drops:<12}'
    chain = sum(v.get("cpu_s", 0) for v in c.values())
    cpu = f'{chain:.2f} / {float(sys.argv[7]):.2f} / {float(sys.argv[8]):.2f}'
print(f'{sys.argv[4]:<8} {sys.argv[5]:>3} | {live} | {cpu:<20} | {fps:<12} | {sys.argv[6]}')
PY
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
