#!/usr/bin/env python3
"""The over- and under-segmented vehicles of a simulated run, one line each (docs/tracking.md).

A confirmed box of tracks_obb.csv belongs to a moving vehicle (gt/gt_obb.csv, at least half visible)
by `uavmot eval`'s rule (false_alarm_places.belongs). A vehicle is over-segmented in a frame when two
or more confirmed boxes belong to it; a box is under-segmented when it belongs to two or more
vehicles (each of them counts once per frame, as in eval's table). Per vehicle: the frames it was
over-segmented in, the first and last of them, and in the middle one its box and the tracks' boxes
(cx, cy, width, length, angle_deg, px); then each under-segmenting box, by frame.

    python3 tools/segmentation_errors.py SEQUENCE_DIR RESULT_DIR [--top N]
"""
import argparse
import collections
import sys

from false_alarm_places import belongs, read_run
from miss_causes import MIN_VISIBILITY


def rounded(box):
    return "[" + ", ".join(f"{v:.1f}" for v in box) + "]"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sequence")
    parser.add_argument("result")
    parser.add_argument("--top", type=int, default=10, help="over-segmented vehicles to list (most frames first)")
    args = parser.parse_args()
    try:
        truth, confirmed, _ = read_run(args.sequence, args.result)
    except (OSError, KeyError, ValueError) as e:
        print(f"segmentation_errors: cannot read the run: {e}", file=sys.stderr)
        sys.exit(2)
    over = collections.defaultdict(list)  # vehicle id -> [(frame, vehicle box, [(track id, box)])]
    under = []
    for frame in sorted(truth):
        moving = [(r, box, poly) for r, box, poly in truth[frame] if r["moving"] == "1" and float(r["visibility"]) >= MIN_VISIBILITY]
        tracks = confirmed.get(frame, [])
        for r, box, poly in moving:
            owners = [(int(t["id"]), tbox) for t, tbox, tpoly in tracks if belongs(tpoly, poly)]
            if len(owners) >= 2:
                over[int(r["id"])].append((frame, box, owners))
        for t, tbox, tpoly in tracks:
            covered = [(int(r["id"]), box) for r, box, poly in moving if belongs(tpoly, poly)]
            if len(covered) >= 2:
                under.append((frame, int(t["id"]), tbox, covered))
    print(f"over-segmented: {sum(len(v) for v in over.values())} instances of {len(over)} vehicles")
    for vehicle, frames in sorted(over.items(), key=lambda kv: (-len(kv[1]), kv[0]))[:args.top]:
        frame, box, owners = frames[len(frames) // 2]
        print(f"  vehicle {vehicle}: {len(frames)} frames, {frames[0][0]}-{frames[-1][0]}; frame {frame}: vehicle {rounded(box)}")
        for track, tbox in owners:
            print(f"      track {track} {rounded(tbox)}")
    print(f"under-segmented: {sum(len(c) for _, _, _, c in under)} instances in {len(under)} boxes")
    for frame, track, tbox, covered in under:
        vehicles = ", ".join(f"{v} {rounded(b)}" for v, b in covered)
        print(f"  frame {frame}: track {track} {rounded(tbox)} over vehicles {vehicles}")


if __name__ == "__main__":
    main()
