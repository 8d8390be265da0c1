#!/usr/bin/env bash
# End-to-end scores of the whole chain (`uavmot process`, default configuration) on every simulator
# preset, scored by `uavmot eval` against the simulator's ground truth: paper Tables I/II for the
# confirmed tracks, false alarms, MOTA/IDF1 at IoU 0.3 and 0.5 and the chain's speed.
# Prints one Markdown table (kept in docs/tracking.md).
#   bash tools/chain_scores.sh [--seed N] [--frames N] [--work DIR] [PRESET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seed=1 frames="" work=out/chain_scores presets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seed) seed=$2; shift ;;
    --frames) frames=$2; shift ;;
    --work) work=$2; shift ;;
    -h|--help) sed -n 2,6p "$0"; exit 0 ;;
    *) presets+=("$1") ;;
  esac
  shift
done
[ ${#presets[@]} -gt 0 ] || presets=(paper lowsnr fastcam dense slow small)
bin=build/bin
mkdir -p "$work"
echo "| preset | instances | correct | under | over | missed | e_x px | e_y px | e_w px | e_l px | false alarms / frame | on parked | MOTA@0.3 | IDF1@0.3 | MOTA@0.5 | chain fps |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for preset in "${presets[@]}"; do
  seq="$work/$preset-$seed" out="$work/$preset-$seed-out"
  [ -d "$seq/img1" ] || "$bin/uavmot" sim --preset "$preset" --seed "$seed" ${frames:+--frames "$frames"} --out "$seq" --quiet >&2
  "$bin/uavmot" process "$seq" --out "$out" --quiet --log-level warn >&2
  "$bin/uavmot" eval --seq "$seq" --pred "$out/tracks.txt" --obb "$out/tracks_obb.csv" --json "$out/eval.json" >/dev/null
  python3 - "$preset" "$out/eval.json" "$out/summary.json" <<'PY'
import json, sys
preset, e, s = sys.argv[1], json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
c, p, f = e["completeness"], e["precision"], e["false_alarms"]
t = {round(x["iou_threshold"], 2): x for x in e["tracking"]}
pct = lambda k: f"{100 * c[k]:.1f} %"
print(f"| {preset} | {c['instances']} | {pct('correct_rate')} | {pct('under_segmented_rate')} | {pct('over_segmented_rate')} "
      f"| {pct('missed_rate')} | {p['error_x_px']:.2f} | {p['error_y_px']:.2f} | {p['error_width_px']:.2f} "
      f"| {p['error_length_px']:.2f} | {f['per_frame']:.2f} | {f['on_parked']} | {t[0.3]['MOTA']:.3f} | {t[0.3]['IDF1']:.3f} "
      f"| {t[0.5]['MOTA']:.3f} | {s['fps']:.1f} |")
PY
done
