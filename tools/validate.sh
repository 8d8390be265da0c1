#!/usr/bin/env bash
# The validation protocol (docs/tracking.md): simulates and scores many seeds of every preset with
# the whole chain (`uavmot process`, default configuration or --config) and prints one table per
# seed set with the mean and the worst seed of each figure. Tuning uses seeds 1-5 (--tuning); the
# held-out seeds 100-109 (--held-out) are the ones to report. Sequences are cached under --work.
#   bash tools/validate.sh [--tuning | --held-out | --seeds "A B ..."] [--frames N] [--jobs J]
#                          [--config FILE] [--work DIR] [--label NAME] [--vary] [PRESET...]
#   --vary: each seed also redraws the scene around its preset (`uavmot sim --vary`: road layout,
#   asphalt, vehicle mix, colours and sizes, sun, camera, GSD, frame rate, resolution, blur, noise,
#   JPEG quality), so the sequences vary as real flights do; cached apart from the plain ones.
#   (default: --held-out, 250 frames, 2 jobs, presets paper hd small lowsnr fastcam dense slow urban3d oblique)
#   UAVMOT_BIN=OTHER/bin/uavmot runs another build (an experiment's) on the same cached sequences.
#   --against OTHER: also print, per preset, this label's means against label OTHER's (the same
#   seeds under the same --work) and on how many seeds the correct rate rose or fell: how a
#   change is judged (docs/tracking.md, "Validation protocol").
#   --report: run nothing; print the tables from the results already under --work/--label.
set -euo pipefail
cd "$(dirname "$0")/.."
seeds="100 101 102 103 104 105 106 107 108 109" frames=250 jobs=2 config="" work=out/validation label=default presets=() vary=""
against="" report_only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --tuning) seeds="1 2 3 4 5" ;;
    --held-out) seeds="100 101 102 103 104 105 106 107 108 109" ;;
    --seeds) seeds=$2; shift ;;
    --frames) frames=$2; shift ;;
    --jobs) jobs=$2; shift ;;
    --config) config=$(realpath "$2"); shift ;;
    --work) work=$2; shift ;;
    --label) label=$2; shift ;;
    --vary) vary=--vary ;;
    --against) against=$2; shift ;;
    --report) report_only=1 ;;
    -h|--help) sed -n 2,16p "$0"; exit 0 ;;
    -*) echo "validate: unknown option '$1'" >&2; exit 2 ;;
    *) presets+=("$1") ;;
  esac
  shift
done
[ ${#presets[@]} -gt 0 ] || presets=(paper hd small lowsnr fastcam dense slow urban3d oblique)
bin=${UAVMOT_BIN:-build/bin/uavmot}
if [ -n "$against" ] && [ ! -d "$work/$against" ]; then
  echo "validate: no results of label '$against' under $work to compare with" >&2; exit 2
fi
if [ -n "$report_only" ] && [ ! -d "$work/$label" ]; then
  echo "validate: no results of label '$label' under $work" >&2; exit 2
fi
# Runs of another length (or varied scenes) are not comparable. With --report this label's own
# record says how it was run; otherwise the arguments do.
this_run="frames=$frames${vary:+ vary}"
if [ -n "$report_only" ] && [ -f "$work/$label/run.txt" ]; then this_run=$(cat "$work/$label/run.txt"); fi
if [ -n "$against" ] && [ -f "$work/$against/run.txt" ] && [ "$(cat "$work/$against/run.txt")" != "$this_run" ]; then
  echo "validate: label '$against' was run with $(cat "$work/$against/run.txt"), this one with $this_run" >&2
  exit 2
fi
if [ -z "$report_only" ]; then  # run the chain; --report only prints what is there
  [ -x "$bin" ] || { echo "validate: $bin is missing; build first (bash tools/build.sh)" >&2; exit 1; }
  mkdir -p "$work"

  # One run: simulate (cached), process, evaluate; leaves $work/<label>/<preset>-<seed>/eval.json.
  run_one() {
    local preset=$1 seed=$2 seq="$work/seq/$1${vary:+-vary}-$2-f$frames" out="$work/$label/$1${vary:+-vary}-$2"
    if [ ! -f "$seq/done" ]; then
      rm -rf "$seq"
      "$bin" sim --preset "$preset" --seed "$seed" --frames "$frames" --out "$seq" --quiet $vary >/dev/null 2>&1 && touch "$seq/done"
    fi
    rm -rf "$out"
    "$bin" process "$seq" --out "$out" --quiet --log-level warn ${config:+--config "$config"} >"$out.log" 2>&1 &&
      "$bin" eval --seq "$seq" --pred "$out/tracks.txt" --obb "$out/tracks_obb.csv" --features "$out/features.csv" \
        --json "$out/eval.json" >/dev/null 2>>"$out.log" || echo "validate: $preset seed $seed failed (log: $out.log)" >&2
  }
  export -f run_one
  export bin work frames label config vary
  mkdir -p "$work/$label"
  echo "$this_run" > "$work/$label/run.txt"  # what --against checks
  for preset in "${presets[@]}"; do for seed in $seeds; do echo "$preset $seed"; done; done |
    xargs -P "$jobs" -L 1 bash -c 'run_one "$0" "$1"'
fi

python3 - "$work/$label" "$seeds" "${vary:+-vary}" "${against:+$work/$against}" "${presets[@]}" <<'PY'
import json, os, sys
root, seeds, suffix, other, presets = sys.argv[1], sys.argv[2].split(), sys.argv[3], sys.argv[4], sys.argv[5:]
def band_correct(e, band):
    # Correct % of one apparent-size band (docs/eval.md); None where the seed has none of that size.
    for b in e["completeness"].get("by_length_px", []):
        if b["band"] == band and b["instances"] > 0:
            return 100 * b["correct_rate"]
    return None
cols = [("correct %", lambda e: 100 * e["completeness"]["correct_rate"], min),
        ("correct % < 10 px", lambda e: band_correct(e, "<10"), min),
        ("correct % >= 20 px", lambda e: band_correct(e, ">=20"), min),
        ("under %", lambda e: 100 * e["completeness"]["under_segmented_rate"], max),
        ("over %", lambda e: 100 * e["completeness"]["over_segmented_rate"], max),
        ("e_x px", lambda e: e["precision"]["error_x_px"], max),
        ("e_y px", lambda e: e["precision"]["error_y_px"], max),
        ("FA / frame", lambda e: e["false_alarms"]["per_frame"], max),
        ("on parked", lambda e: e["false_alarms"]["on_parked"], max),
        ("on structure / frame", lambda e: e["false_alarms"].get("on_structure_per_frame", 0.0), max),
        ("feature precision", lambda e: e["features"]["precision"], min),
        ("feature recall", lambda e: e["features"]["recall"], min)]
print(f"seeds {seeds}{' (scenes varied by the seed)' if suffix else ''}, root {root}: mean (worst seed)\n")
print("| preset | seeds | " + " | ".join(c[0] for c in cols) + " |")
print("|---|---:|" + "---:|" * len(cols))
for p in presets:
    runs = []
    for s in seeds:
        f = os.path.join(root, f"{p}{suffix}-{s}", "eval.json")
        if os.path.exists(f):
            runs.append(json.load(open(f)))
    if not runs:
        print(f"| {p} | 0 |" + " |" * len(cols)); continue
    cells = []
    for name, get, worst in cols:
        vals = [v for v in (get(e) for e in runs) if v is not None]
        cells.append(f"{sum(vals) / len(vals):.2f} ({worst(vals):.2f})" if vals else "-")
    print(f"| {p} | {len(runs)} | " + " | ".join(cells) + " |")

if other:
    # Only seeds both labels have, so that the means compare like with like.
    figure = {name: get for name, get, _ in cols}
    compared = ["correct %", "FA / frame", "on structure / frame", "feature precision", "feature recall"]
    print(f"\n{os.path.basename(other)} -> {os.path.basename(root)}: means over the seeds both have; "
          "seeds: on how many the correct rate rose / fell by more than 0.1 point\n")
    print("| preset | seeds | " + " | ".join(compared) + " | correct % up / down |")
    print("|---|---:|" + "---|" * len(compared) + "---:|")
    for p in presets:
        pairs = []
        for s in seeds:
            a, b = (os.path.join(r, f"{p}{suffix}-{s}", "eval.json") for r in (other, root))
            if os.path.exists(a) and os.path.exists(b):
                pairs.append((json.load(open(a)), json.load(open(b))))
        if not pairs:
            print(f"| {p} | 0 |" + " |" * (len(compared) + 1)); continue
        cells = []
        for name in compared:
            before = sum(figure[name](a) for a, _ in pairs) / len(pairs)
            after = sum(figure[name](b) for _, b in pairs) / len(pairs)
            cells.append(f"{before:.2f} -> {after:.2f}")
        rates = [(figure["correct %"](a), figure["correct %"](b)) for a, b in pairs]
        up = sum(1 for x, y in rates if y > x + 0.1)
        down = sum(1 for x, y in rates if y < x - 0.1)
        print(f"| {p} | {len(pairs)} | " + " | ".join(cells) + f" | {up} / {down} |")
PY
