#!/usr/bin/env bash
# Records 1080p mono8 frames published at 60 Hz and reports kept frames, MB/s and recorder CPU
# for each chunk compression (docs/benchmarks/record.md).
#   record_bench.sh BUILD_DIR SEQUENCE [MODE=live] [DOMAIN=55]
# SEQUENCE: e.g. `uavmot-sim --preset hd --seed 3 --frames 300 --out SEQ`.
set -euo pipefail
build=$1
seq=$2
mode=${3:-live}
domain=${4:-55}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf "%-6s %-8s %9s %9s %9s %9s %9s %9s\n" compr mode published recorded wall_s in_MB/s file_MB/s cpu_%
for compression in none lz4 zstd; do
  rec="$out/rec_$compression.mcap"
  /usr/bin/time -f "%U %S %e" -o "$out/time_$compression" \
    "$build/bin/uavmot-record" --topics uavmot/frames --out "$rec" --compression "$compression" \
    --mode "$mode" --domain "$domain" >"$out/record_$compression.log" 2>&1 &
  recorder=$!
  until grep -q "recording uavmot/frames" "$out/record_$compression.log"; do sleep 0.1; done
  start=$(date +%s.%N)
  "$build/bin/uavmot-source" "$seq" --rate 60 --mode "$mode" --wait-subscribers 1 --domain "$domain" \
    >"$out/source_$compression.log" 2>&1
  end=$(date +%s.%N)
  sleep 1
  kill -INT "$(pgrep -P "$recorder")"  # the recorder under /usr/bin/time (which ignores SIGINT)
  wait "$recorder"
  published=$(grep -oE "published [0-9]+ frames" "$out/source_$compression.log" | tail -1 | grep -oE "[0-9]+" || echo "?")
  recorded=$(grep -oE "uavmot/frames: [0-9]+ samples" "$out/record_$compression.log" | grep -oE "[0-9]+ samples" | grep -oE "[0-9]+")
  read -r user sys wall <"$out/time_$compression"
  secs=$(echo "$end - $start" | bc -l)
  in_mb=$(echo "$recorded * 1920 * 1080 / 1000000 / $secs" | bc -l)
  file_mb=$(echo "$(stat -c %s "$rec") / 1000000 / $secs" | bc -l)
  cpu=$(echo "100 * ($user + $sys) / $secs" | bc -l)
  printf "%-6s %-8s %9s %9s %9.1f %9.1f %9.1f %9.0f\n" "$compression" "$mode" "$published" "$recorded" "$secs" "$in_mb" "$file_mb" "$cpu"
  grep -hE "published [0-9]+ frames in|queue peak" "$out/source_$compression.log" "$out/record_$compression.log" | sed "s/^/    /"
done
