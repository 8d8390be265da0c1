#!/usr/bin/env bash
# Side by side, in one invocation, on the same simulated frames: `uavmot process --threads 1`
# (sequential), `uavmot process --threads 2` (pipelined) and the classic OpenCV chain
# (build/bin/uavmot-bench-classic: GFTT + LK + findHomography, motion-compensated frame
# differencing, a SORT-like tracker; OpenCV's pool at 2 threads). Every run is timed from start to
# exit (decoding included), repeated, and scored by `uavmot eval` against the simulator's truth.
# Prints a Markdown table: median fps (min-max), CPU time per frame (user + system, all threads),
# the chain's own fps as `uavmot process` measures it (summary.json: the frames, without starting the
# process and its 270 shared libraries), correct rate, false alarms, MOTA, and the ratios.
#   bash tools/bench_process.sh [--seed N] [--frames N] [--repeat N] [--size WxH] [--config FILE] [--work DIR] [--no-classic]
# --size renders the `hd` preset (1920x1080, 0.3 m/px) at another size, e.g. 3840x2160;
# --config is passed to `uavmot process` (e.g. more features for 4K, docs/benchmarks/process.md).
set -euo pipefail
cd "$(dirname "$0")/.."
seed=2 frames=150 repeat=3 size=1920x1080 work=out/bench_process classic=1 config=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seed) seed=$2; shift ;;
    --frames) frames=$2; shift ;;
    --repeat) repeat=$2; shift ;;
    --size) size=$2; shift ;;
    --work) work=$2; shift ;;
    --config) config=(--config "$2"); shift ;;
    --no-classic) classic=0 ;;
    -h|--help) sed -n 2,9p "$0"; exit 0 ;;
    *) echo "bench_process.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done
bin=build/bin
for b in uavmot uavmot-sim uavmot-process uavmot-eval uavmot-bench-classic; do
  [ -x "$bin/$b" ] || { echo "bench_process.sh: $bin/$b missing: run tools/build.sh" >&2; exit 2; }
done
width=${size%x*} height=${size#*x}
seq="$work/hd-${size}-s${seed}-f${frames}"
mkdir -p "$work"
if [ ! -f "$seq/seqinfo.ini" ]; then
  "$bin/uavmot-sim" --preset hd --print-scenario |
    sed -e "s/^  width: 1920\$/  width: $width/" -e "s/^  height: 1080\$/  height: $height/" > "$work/scenario-$size.yaml"
  "$bin/uavmot-sim" --scenario "$work/scenario-$size.yaml" --seed "$seed" --frames "$frames" --out "$seq" --quiet
fi

times="$work/times-$size.tsv"
: > "$times"
# run NAME OUT CMD...: wall seconds from start to exit, CPU seconds, the load average before it,
# and the fps in the run's summary.json (- where it writes none).
run() {
  local name=$1 out=$2; shift 2
  local load; load=$(cut -d' ' -f1 /proc/loadavg)
  rm -f "$out/summary.json"
  local t0; t0=$(date +%s.%N)
  /usr/bin/time -o "$out.cpu" -f "%U %S" "$@" > "$out.log" 2>&1 || { echo "bench_process.sh: $name failed, see $out.log" >&2; exit 1; }
  local t1; t1=$(date +%s.%N)
  local chain_fps=-
  [ -f "$out/summary.json" ] && chain_fps=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["fps"])' "$out/summary.json")
  printf '%s\t%s\t%s\t%s\t%s\n' "$name" "$(awk "BEGIN { print $t1 - $t0 }")" "$(awk '{ print $1 + $2 }' "$out.cpu")" "$load" "$chain_fps" >> "$times"
}
for r in $(seq 1 "$repeat"); do
  run "uavmot process --threads 1" "$work/t1" "$bin/uavmot" process "$seq" --out "$work/t1" --threads 1 --quiet "${config[@]}"
  run "uavmot process --threads 2" "$work/t2" "$bin/uavmot" process "$seq" --out "$work/t2" --threads 2 --quiet "${config[@]}"
  if [ "$classic" = 1 ]; then
    run "classic OpenCV chain, 2 threads" "$work/classic" "$bin/uavmot-bench-classic" "$seq" --out "$work/classic" --threads 2
  fi
done

identical=yes
for f in tracks.txt tracks_obb.csv homographies.txt features.csv clusters.txt regions.txt; do
  cmp -s "$work/t1/$f" "$work/t2/$f" || { identical="NO ($f differs)"; break; }
done
"$bin/uavmot" eval --seq "$seq" --pred "$work/t2/tracks.txt" --obb "$work/t2/tracks_obb.csv" --json "$work/t2/eval.json" > /dev/null
"$bin/uavmot" eval --seq "$seq" --pred "$work/t1/tracks.txt" --obb "$work/t1/tracks_obb.csv" --json "$work/t1/eval.json" > /dev/null
[ "$classic" = 1 ] && "$bin/uavmot" eval --seq "$seq" --pred "$work/classic/tracks.txt" --json "$work/classic/eval.json" > /dev/null

echo "$size, $frames frames (uavmot sim --preset hd, seed $seed)${config[*]:+, process ${config[*]}}, $repeat runs each, $(nproc) cores; machine load average before the runs: $(cut -f4 "$times" | tr '\n' ' ')"
echo "tracks and all result files of --threads 1 and --threads 2 byte-identical: $identical"
echo
python3 - "$times" "$frames" "$work" <<'PY'
import json, statistics, sys
times, frames, work = sys.argv[1], int(sys.argv[2]), sys.argv[3]
runs, cpu, chain = {}, {}, {}
for line in open(times):
    name, seconds, cpu_seconds, _, chain_fps = line.rstrip("\n").split("\t")
    runs.setdefault(name, []).append(frames / float(seconds))
    cpu.setdefault(name, []).append(1e3 * float(cpu_seconds) / frames)
    if chain_fps != "-":
        chain.setdefault(name, []).append(float(chain_fps))
folders = {"uavmot process --threads 1": "t1", "uavmot process --threads 2": "t2", "classic OpenCV chain, 2 threads": "classic"}
print("| method | fps median | fps min-max | CPU ms / frame (median) | chain fps (summary.json) | correct | missed | false alarms / frame | MOTA@0.3 |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
median = {}
for name, fps in runs.items():
    e = json.load(open(f"{work}/{folders[name]}/eval.json"))
    c = e["completeness"]
    mota = next(t["MOTA"] for t in e["tracking"] if abs(t["iou_threshold"] - 0.3) < 1e-6)
    median[name] = statistics.median(fps)
    chain_fps = f"{statistics.median(chain[name]):.1f}" if name in chain else "-"
    print(f"| {name} | {median[name]:.1f} | {min(fps):.1f}-{max(fps):.1f} | {statistics.median(cpu[name]):.1f} | {chain_fps} | {100 * c['correct_rate']:.1f} % "
          f"| {100 * c['missed_rate']:.1f} % | {e['false_alarms']['per_frame']:.2f} | {mota:.3f} |")
t1, t2 = median["uavmot process --threads 1"], median["uavmot process --threads 2"]
print(f"\nratio --threads 2 / --threads 1 (median fps): {t2 / t1:.2f}")
c1, c2 = (statistics.median(chain.get(n, [float("nan")])) for n in ("uavmot process --threads 1", "uavmot process --threads 2"))
print(f"ratio --threads 2 / --threads 1 (median chain fps, summary.json): {c2 / c1:.2f}")
if "classic OpenCV chain, 2 threads" in median:
    print(f"ratio uavmot --threads 2 / classic at 2 threads (median fps): {t2 / median['classic OpenCV chain, 2 threads']:.2f}")
PY
