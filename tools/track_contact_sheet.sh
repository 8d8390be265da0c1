#!/usr/bin/env bash
# A contact sheet of every confirmed track of a `uavmot process` run with an annotated video
# (`--video RUN/annotated.mp4`, as tools/real_video_check.sh makes): per track a 96 x 96 px crop of the
# annotated frame in the middle of its confirmed life, shown at twice the size and labelled
# "ID fFIRST-LAST vSPEED" (px/frame), six to a row. For a person to judge, on video without ground
# truth, what each track is on. Also prints one line per track: id, frame shown, x, y, confirmed
# boxes, first and last confirmed frame, speed.
#   bash tools/track_contact_sheet.sh RUN_DIR OUT.png
set -euo pipefail
[ $# -eq 2 ] || { sed -n 2,8p "$0"; exit 2; }
run=$1 out=$2
for f in "$run/tracks_obb.csv" "$run/annotated.mp4"; do
  [ -f "$f" ] || { echo "track_contact_sheet: $f is missing" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$run/tracks_obb.csv" > "$tmp/list" <<'PY'
import collections, sys
rows = collections.defaultdict(list)
with open(sys.argv[1]) as f:
    next(f)
    for line in f:
        p = line.split(',')
        if p[2] == 'confirmed':
            rows[int(p[1])].append((int(p[0]), float(p[3]), float(p[4]), float(p[8]), float(p[9])))
for tid, r in sorted(rows.items()):
    frame, x, y, vx, vy = r[len(r) // 2]
    print(tid, frame, int(x), int(y), len(r), r[0][0], r[-1][0], round((vx * vx + vy * vy) ** 0.5, 2))
PY
[ -s "$tmp/list" ] || { echo "track_contact_sheet: no confirmed track in $run" >&2; exit 1; }
i=0
while read -r id frame x y boxes first last speed; do
  # Padded by 48 px so that a crop at the border stays 96 x 96; select counts frames from 0.
  ffmpeg -nostdin -loglevel error -y -i "$run/annotated.mp4" \
    -vf "select=eq(n\,$((frame - 1))),pad=iw+96:ih+96:48:48,crop=96:96:$x:$y,scale=192:192:flags=neighbor,drawtext=text='$id f$first-$last v$speed':fontcolor=yellow:fontsize=14:x=2:y=2" \
    -frames:v 1 "$tmp/c$(printf %04d $i).png"
  i=$((i + 1))
done < "$tmp/list"
cat "$tmp/list"
columns=6 rows=$(( (i + 5) / 6 ))
ffmpeg -nostdin -loglevel error -y -framerate 1 -i "$tmp/c%04d.png" -vf "tile=${columns}x${rows}:padding=4:color=white" -frames:v 1 "$out"
echo "contact sheet of $i tracks: $out"
