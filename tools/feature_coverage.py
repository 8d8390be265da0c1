#!/usr/bin/env python3
"""How many scored vehicles carry features, by apparent size (docs/tracking.md).

For every moving vehicle instance of a simulated sequence (gt/gt_obb.csv, visibility >= 0.5, as
`uavmot eval` scores them) it counts the chain's features (features.csv of `uavmot process`) inside
the vehicle's oriented box grown by 1 px, and prints per band of length in the image (< 10,
10-20, >= 20 px): the share of instances with any feature, with a feature classified moving, the
mean number of features and the vehicle's mean speed (vx, vy of gt_obb.csv, px/frame).

    python3 tools/feature_coverage.py SEQUENCE_DIR RESULT_DIR
"""
import collections
import csv
import math
import sys


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sequence, result = sys.argv[1], sys.argv[2]
    truth = collections.defaultdict(list)
    with open(f"{sequence}/gt/gt_obb.csv") as f:
        for r in csv.DictReader(f):
            if r["moving"] != "1" or float(r["visibility"]) < 0.5:
                continue
            truth[int(r["frame"])].append(tuple(float(r[k]) for k in ("cx", "cy", "width", "length", "angle_deg", "vx", "vy")))
    features = collections.defaultdict(list)
    with open(f"{result}/features.csv") as f:
        for r in csv.DictReader(f):
            features[int(r["frame"])].append((float(r["x"]), float(r["y"]), r["moving"] == "1"))
    bands = {"<10": [0, 0, 0, 0, 0.0], "10-20": [0, 0, 0, 0, 0.0], ">=20": [0, 0, 0, 0, 0.0]}
    for frame, objects in truth.items():
        for cx, cy, width, length, angle, vx, vy in objects:
            c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
            inside = moving = 0
            for x, y, is_moving in features.get(frame, []):
                along, across = (x - cx) * c + (y - cy) * s, -(x - cx) * s + (y - cy) * c
                if abs(along) <= length / 2 + 1 and abs(across) <= width / 2 + 1:
                    inside += 1
                    moving += is_moving
            longer = max(width, length)
            band = bands["<10" if longer < 10 else "10-20" if longer < 20 else ">=20"]
            band[0] += 1
            band[1] += inside > 0
            band[2] += moving > 0
            band[3] += inside
            band[4] += math.hypot(vx, vy)
    for name, (n, any_feature, a_moving, total, speed) in bands.items():
        if n:
            print(f"{name:>6} px {n:7} instances: any feature {100 * any_feature / n:5.1f} %, a moving feature "
                  f"{100 * a_moving / n:5.1f} %, {total / n:.2f} features each, {speed / n:.2f} px/frame")


if __name__ == "__main__":
    try:
        main()
    except (OSError, KeyError, ValueError) as e:
        print(f"feature_coverage: cannot read the sequence or the results: {e}", file=sys.stderr)
        sys.exit(2)
