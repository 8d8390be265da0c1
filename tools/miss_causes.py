#!/usr/bin/env python3
"""Why the vehicles of a simulated run were missed (docs/tracking.md).

An instance (a moving vehicle at least half visible, in a frame from --first-frame on) is missed when
no confirmed box of tracks_obb.csv belongs to it by `uavmot eval`'s rule (the exact intersection of
the oriented boxes covers half of the vehicle or half of the box). Each miss is counted by
  - its features: whether a feature the run classified moving (features.csv) lies on the vehicle's
    box grown by 1.5 px on each side (eval's feature tolerance), i.e. motion layer or later;
  - its neighbourhood: crowded when another moving vehicle's centre is within 1.5 of its lengths;
  - its speed (gt vx, vy: ground motion in px/frame): slow under 0.3 px/frame, then accelerating or
    decelerating when its speed 5 frames earlier differs by more than 0.02 px/frame, else steady;
  - how long it has been in view (frames since it was first at least half visible).
The default first frame, 11, leaves out the chain's start (no motion before frame 2, confirmation).
With --by-vehicle N, also the N vehicles with the most misses, one line each: how many of its
instances were missed, the first and last missed frame, its size and mean speed over the misses, and
how many of the misses had a moving feature on it (a seed's losses are often one or two vehicles).

    python3 tools/miss_causes.py SEQUENCE_DIR RESULT_DIR [--first-frame N] [--by-vehicle N]
"""
import argparse
import collections
import csv
import math
import sys

from false_alarm_places import belongs, corners, read_run

MIN_VISIBILITY = 0.5  # an instance is scored, and a vehicle in view, from half visible


def inside_convex(point, poly):
    signs = set()
    for i in range(len(poly)):
        a, b = poly[i - 1], poly[i]
        cross = (b[0] - a[0]) * (point[1] - a[1]) - (b[1] - a[1]) * (point[0] - a[0])
        if cross != 0:
            signs.add(cross > 0)
    return len(signs) <= 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sequence")
    parser.add_argument("result")
    parser.add_argument("--first-frame", type=int, default=11)
    parser.add_argument("--by-vehicle", type=int, default=0, metavar="N")
    args = parser.parse_args()
    try:
        every_vehicle, tracks, _ = read_run(args.sequence, args.result)
        moving_features = collections.defaultdict(list)
        with open(f"{args.result}/features.csv") as f:
            for r in csv.DictReader(f):
                if r["moving"] == "1":
                    moving_features[int(r["frame"])].append((float(r["x"]), float(r["y"])))
    except (OSError, KeyError, ValueError) as e:
        print(f"miss_causes: {e}", file=sys.stderr)
        sys.exit(2)
    # Speeds of every vehicle (a stopped one too: what a vehicle starting off did 5 frames ago).
    speed = {(int(g["id"]), frame): math.hypot(float(g["vx"]), float(g["vy"]))
             for frame, rows in every_vehicle.items() for g, _, _ in rows}
    truth = {frame: [v for v in rows if v[0]["moving"] == "1"] for frame, rows in every_vehicle.items()}
    def speed_class(vehicle_id, frame):
        now = speed[(vehicle_id, frame)]
        if now >= 0.3:
            return None
        before = speed.get((vehicle_id, frame - 5))
        if before is not None and before > now + 0.02:
            return "decelerating"
        if before is not None and before < now - 0.02:
            return "accelerating"
        return "steady"

    # Frames since each vehicle was first in view (visible at least half, moving or not): a vehicle
    # that has just come in has no feature history yet, whatever else is wrong.
    first_seen = {}
    for frame, rows in sorted(every_vehicle.items()):
        for g, _, _ in rows:
            if float(g["visibility"]) >= MIN_VISIBILITY:
                first_seen.setdefault(int(g["id"]), frame)
    age_bands = ((0, 2), (3, 5), (6, 10), (11, 20), (21, None))
    def age_band(vehicle_id, frame):
        age = frame - first_seen[vehicle_id]
        return next(b for b in age_bands if age >= b[0] and (b[1] is None or age <= b[1]))
    age_instances, age_missed = collections.Counter(), collections.Counter()
    instances = 0
    causes = collections.Counter()
    slow_instances, slow_missed = collections.Counter(), collections.Counter()
    per_vehicle = collections.defaultdict(list)  # id -> (frame, box, speed, has_feature) per miss
    vehicle_instances = collections.Counter()
    for frame, vehicles in sorted(truth.items()):
        if frame < args.first_frame:
            continue
        for g, box, poly in vehicles:
            if float(g["visibility"]) < MIN_VISIBILITY:
                continue
            instances += 1
            vehicle_instances[int(g["id"])] += 1
            slow = speed_class(int(g["id"]), frame)
            slow_instances[slow] += 1
            age = age_band(int(g["id"]), frame)
            age_instances[age] += 1
            if any(belongs(p, poly) for _, _, p in tracks.get(frame, [])):
                continue
            slow_missed[slow] += 1
            age_missed[age] += 1
            grown = corners(box[0], box[1], box[2] + 3.0, box[3] + 3.0, box[4])
            has_feature = any(inside_convex(p, grown) for p in moving_features.get(frame, []))
            crowded = any(math.hypot(b[0] - box[0], b[1] - box[1]) < 1.5 * box[3]
                          for h, b, _ in vehicles if h is not g)
            causes[("crowded" if crowded else "alone", "moving features" if has_feature else "no moving feature")] += 1
            per_vehicle[int(g["id"])].append((frame, box, speed[(int(g["id"]), frame)], has_feature))
    missed = sum(causes.values())
    print(f"{args.result}: {instances} instances from frame {args.first_frame}, {missed} missed ({100.0 * missed / max(instances, 1):.1f} %)")
    for key in sorted(causes):
        print(f"  {key[0]:8s} {key[1]:18s} {causes[key]:6d}  {100.0 * causes[key] / max(missed, 1):5.1f} % of the misses")
    for kind in ("accelerating", "decelerating", "steady"):
        print(f"  slower than 0.3 px/frame, {kind:12s}: {slow_missed[kind]:5d} missed of {slow_instances[kind]:5d} instances")
    for band in age_bands:
        name = f"{band[0]}-{band[1]}" if band[1] is not None else f"{band[0]}+"
        print(f"  in view for {name:5s} frames: {age_missed[band]:5d} missed of {age_instances[band]:5d} instances")
    if args.by_vehicle > 0:
        print(f"  the {args.by_vehicle} vehicles with the most misses:")
    for vehicle_id, misses in sorted(per_vehicle.items(), key=lambda kv: -len(kv[1]))[:max(args.by_vehicle, 0)]:
        frames = [m[0] for m in misses]
        width = sum(m[1][2] for m in misses) / len(misses)
        length = sum(m[1][3] for m in misses) / len(misses)
        mean_speed = sum(m[2] for m in misses) / len(misses)
        with_feature = sum(1 for m in misses if m[3])
        first = misses[0][1]
        print(f"    vehicle {vehicle_id}: {len(misses)} of {vehicle_instances[vehicle_id]} missed, frames {min(frames)}-{max(frames)},"
              f" {width:.1f} x {length:.1f} px, {mean_speed:.2f} px/frame, {with_feature} with a moving feature;"
              f" at frame {misses[0][0]} ({first[0]:.1f}, {first[1]:.1f}) angle {first[4]:.0f} deg")

if __name__ == "__main__":
    main()
