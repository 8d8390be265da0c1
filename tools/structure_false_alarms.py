#!/usr/bin/env python3
"""The false alarms of a simulated 3-D run that lie on static structure, by when their track started
(docs/tracking.md, issue 17).

A confirmed box of tracks_obb.csv that belongs to no vehicle (`uavmot eval`'s rule, see
tools/false_alarm_places.py) is on a structure when at least half of the box, or half of the
structure, lies in the convex hull of the structure's outline in that frame (gt/structures.csv), as
`uavmot eval` counts them. Counted by kind, and by the frame the box's track first appeared in
(tentative included): up to --early-frame (default 15) or later; those of tracks that had at least
--vehicle-boxes (default 3) boxes on a moving vehicle first (a vehicle hidden by a building or a
crown, whose track stayed on the structure); and the tracks with most such boxes.

    python3 tools/structure_false_alarms.py SEQUENCE_DIR RESULT_DIR [--early-frame N] [--top K] [--vehicle-boxes N]
"""
import argparse
import collections
import csv
import sys

from false_alarm_places import belongs, read_run


def convex_hull(points):
    points = sorted(set(points))
    if len(points) <= 2:
        return points

    def half(sequence):
        out = []
        for p in sequence:
            while len(out) >= 2 and (out[-1][0] - out[-2][0]) * (p[1] - out[-2][1]) - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0]) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(points), half(reversed(points))
    return lower[:-1] + upper[:-1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sequence")
    parser.add_argument("result")
    parser.add_argument("--early-frame", type=int, default=15)
    parser.add_argument("--top", type=int, default=5)
    parser.add_argument("--vehicle-boxes", type=int, default=3)
    args = parser.parse_args()
    try:
        truth, tracks, birth = read_run(args.sequence, args.result)
        structures = collections.defaultdict(list)
        with open(f"{args.sequence}/gt/structures.csv") as f:
            for r in csv.DictReader(f):
                v = [float(x) for x in r["outline"].split()]
                structures[int(r["frame"])].append((r["kind"], int(r["id"]), convex_hull(list(zip(v[0::2], v[1::2])))))
    except (OSError, KeyError, ValueError) as e:
        print(f"structure_false_alarms: {e}", file=sys.stderr)
        sys.exit(2)
    by_kind, by_birth, by_track = collections.Counter(), collections.Counter(), collections.Counter()
    on_vehicle = collections.Counter()  # track -> its boxes so far on a moving vehicle
    after_vehicle = 0
    for frame, boxes in sorted(tracks.items()):
        for r, _, poly in boxes:
            if any(belongs(poly, gpoly) for g, _, gpoly in truth.get(frame, []) if g["moving"] == "1"):
                on_vehicle[int(r["id"])] += 1
                continue
            if any(belongs(poly, gpoly) for _, _, gpoly in truth.get(frame, [])):
                continue
            for kind, structure_id, hull in structures.get(frame, []):
                if len(hull) >= 3 and belongs(poly, hull):
                    track = int(r["id"])
                    by_kind[kind] += 1
                    by_birth["early" if birth[track] <= args.early_frame else "later"] += 1
                    by_track[(track, kind, structure_id)] += 1
                    after_vehicle += on_vehicle[track] >= args.vehicle_boxes
                    break
    total = sum(by_kind.values())
    print(f"{args.result}: {total} false-alarm boxes on structures ({', '.join(f'{k} {v}' for k, v in sorted(by_kind.items()))}), "
          f"{len(by_track)} tracks")
    print(f"  of tracks started by frame {args.early_frame}: {by_birth['early']} ({100.0 * by_birth['early'] / max(total, 1):.1f} %), "
          f"later: {by_birth['later']}")
    print(f"  of tracks that had {args.vehicle_boxes} or more boxes on a moving vehicle before: {after_vehicle} "
          f"({100.0 * after_vehicle / max(total, 1):.1f} %)")
    for (track, kind, structure_id), boxes in by_track.most_common(args.top):
        print(f"  track {track} (started frame {birth[track]}) on {kind} {structure_id}: {boxes} boxes")


if __name__ == "__main__":
    main()
