#!/usr/bin/env python3
"""Signed position error of a simulated run's boxes (docs/tracking.md, "Vehicle shadows").

`uavmot eval` reports the mean absolute centre error (e_x, e_y); this splits it into a bias that
every box shares and the scatter around it. For each confirmed box of tracks_obb.csv that belongs to
a moving vehicle by eval's rule, the centre minus the vehicle's true centre is taken in image x and
y and along and across the vehicle's travel (vehicles under 0.2 px/frame left out there). A bias in
x and y that is the same whatever way the vehicles drive is the scene's doing (vehicle shadows: the
sun is the same for all), one along the travel the tracker's (lag or lead).

    python3 tools/box_bias.py SEQUENCE_DIR RESULT_DIR [SEQUENCE_DIR RESULT_DIR ...]
"""
import math
import statistics
import sys

from false_alarm_places import belongs, read_run


def errors(sequence, result):
    truth, tracks, _ = read_run(sequence, result)
    image, travel = [], []
    for frame, boxes in tracks.items():
        vehicles = [v for v in truth.get(frame, []) if v[0]["moving"] == "1"]
        for _, box, poly in boxes:
            for g, gbox, gpoly in vehicles:
                if not belongs(poly, gpoly):
                    continue
                ex, ey = box[0] - gbox[0], box[1] - gbox[1]
                image.append((ex, ey))
                vx, vy = float(g["vx"]), float(g["vy"])
                speed = math.hypot(vx, vy)
                if speed > 0.2:
                    travel.append(((ex * vx + ey * vy) / speed, (ey * vx - ex * vy) / speed))
                break
    return image, travel


def summary(name, pairs):
    if not pairs:
        return f"{name}: no box"
    a, b = zip(*pairs)
    return (f"{name} mean {statistics.mean(a):+.2f} / {statistics.mean(b):+.2f} px, "
            f"mean |.| {statistics.mean(map(abs, a)):.2f} / {statistics.mean(map(abs, b)):.2f} px")


def main():
    args = sys.argv[1:]
    if not args or len(args) % 2 or args[0] in ("-h", "--help"):
        print(__doc__, file=sys.stderr)
        sys.exit(0 if args and args[0] in ("-h", "--help") else 2)
    for sequence, result in zip(args[::2], args[1::2]):
        try:
            image, travel = errors(sequence, result)
        except (OSError, KeyError, ValueError) as e:
            print(f"box_bias: {e}", file=sys.stderr)
            sys.exit(2)
        print(f"{result}: {len(image)} boxes; {summary('x / y', image)}; {summary('along / across travel', travel)}")


if __name__ == "__main__":
    main()
