#!/usr/bin/env bash
# Records 1080p mono8 frames published at 60 Hz and reports kept frames, MB/s and recorder CPU
# for each chunk compression (docs/benchmarks/record.md).
#   record_bench.sh BUILD_DIR SEQUENCE [MODE=live] [DOMAIN=55] [COMPRESSIONS="none lz4 zstd"]
# SEQUENCE: e.g. `uavmot-sim --preset hd --seed 3 --frames 300 --out SEQ`.
# Rates are over the source's publishing time (from its last log line), so the processes'
# start-up and shutdown do not dilute them; recorder CPU is its whole user + system time over
# that span (start-up and closing the file included, so an upper bound).
set -euo pipefail
build=$1
seq=$2
mode=${3:-live}
domain=${4:-55}
compressions=${5:-none lz4 zstd}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average: $(cut -d' ' -f1-3 /proc/loadavg)"
printf "%-6s %-8s %9s %8s %9s %6s %8s %9s %9s %8s\n" compr mode published skipped recorded lost src_fps in_MB/s file_MB/s rec_cpu%
for compression in $compressions; do
  rec="$out/rec_$compression.mcap"
  /usr/bin/time -f "%U %S %e" -o "$out/time_$compression" \
    "$build/bin/uavmot-record" --topics uavmot/frames --out "$rec" --compression "$compression" \
    --mode "$mode" --domain "$domain" >"$out/record_$compression.log" 2>&1 &
  recorder=$!
  until grep -q "recording uavmot/frames" "$out/record_$compression.log"; do sleep 0.1; done
  "$build/bin/uavmot-source" "$seq" --rate 60 --mode "$mode" --wait-subscribers 1 --domain "$domain" \
    >"$out/source_$compression.log" 2>&1
  sleep 1
  kill -INT "$(pgrep -P "$recorder")"  # the recorder under /usr/bin/time (which ignores SIGINT)
  wait "$recorder"
  summary=$(grep -E "published [0-9]+ frames in" "$out/source_$compression.log" | tail -1)
  published=$(echo "$summary" | grep -oE "published [0-9]+" | grep -oE "[0-9]+")
  secs=$(echo "$summary" | grep -oE "in [0-9.]+ s" | grep -oE "[0-9.]+")
  fps=$(echo "$summary" | grep -oE "\([0-9.]+ fps\)" | grep -oE "[0-9.]+")
  skipped=$(echo "$summary" | grep -oE "skipped [0-9]+ it was late" | grep -oE "[0-9]+" || echo 0)
  samples=$(grep -oE "uavmot/frames: [0-9]+ samples" "$out/record_$compression.log" | grep -oE "[0-9]+ samples" | grep -oE "[0-9]+")
  recorded=$((samples - 1))  # the end-of-stream sample carries no frame
  read -r user sys wall <"$out/time_$compression"
  in_mb=$(echo "$recorded * 1920 * 1080 / 1000000 / $secs" | bc -l)
  file_mb=$(echo "$(stat -c %s "$rec") / 1000000 / $secs" | bc -l)
  cpu=$(echo "100 * ($user + $sys) / $secs" | bc -l)
  printf "%-6s %-8s %9s %8s %9s %6s %8s %9.1f %9.1f %8.0f\n" "$compression" "$mode" "$published" "$skipped" "$recorded" \
    "$((published - recorded))" "$fps" "$in_mb" "$file_mb" "$cpu"
  grep -hE "queue peak|uavmot/frames:" "$out/record_$compression.log" | sed "s/^.*\] /    /"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
