#!/usr/bin/env python3
"""Where the false alarms of a simulated run lie, relative to the moving vehicles (docs/tracking.md).

A confirmed box of tracks_obb.csv (`uavmot process`) belongs to a ground-truth vehicle (gt/gt_obb.csv,
moving or not) as `uavmot eval` decides it: the exact intersection of the oriented boxes covers at
least half of the vehicle or half of the box. The boxes that belong to no vehicle are false alarms;
for each, the nearest moving vehicle (centre distance) tells where it lies: overlapping it (less than
the rule), beside it (within 1.5 vehicle lengths), or far (farther, or no moving vehicle in the frame).
It also counts the false alarms whose nearest moving vehicle has a box of its own in that frame, and
splits those overlapping a vehicle by whether that vehicle has its own box (else the box is a
misplaced box of a vehicle the run missed: one miss and one false alarm) and by the box's area
against the vehicle's (larger: over 1.5 x; smaller: under 0.67 x; else similar); for the similar-sized
ones on a missed vehicle, how far their centres lie from the vehicle's along its travel and across it,
and how far their long axes turn from its (docs/tracking.md, session 39). Last, from the
vehicles' side: the moving vehicles the run missed that have one, or two or more, false-alarm boxes
overlapping them (a box beside the car, or two tracks on its two edges: docs/tracking.md, session 27).

    python3 tools/false_alarm_places.py SEQUENCE_DIR RESULT_DIR
"""
import collections
import csv
import math
import sys


def corners(cx, cy, width, length, angle_deg):
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)
    return [(cx + dx * c - dy * s, cy + dx * s + dy * c)
            for dx, dy in ((length / 2, width / 2), (-length / 2, width / 2), (-length / 2, -width / 2), (length / 2, -width / 2))]


def area(poly):
    return abs(sum(poly[i][0] * poly[i - 1][1] - poly[i - 1][0] * poly[i][1] for i in range(len(poly)))) / 2


def counter_clockwise(poly):
    signed = sum(poly[i][0] * poly[i - 1][1] - poly[i - 1][0] * poly[i][1] for i in range(len(poly)))
    return poly if signed < 0 else poly[::-1]


def intersection_area(subject, clip):
    """Sutherland-Hodgman clipping of two convex polygons."""
    def inside(p, a, b):
        return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) >= 0

    def crossing(p, q, a, b):
        d = (p[0] - q[0]) * (a[1] - b[1]) - (p[1] - q[1]) * (a[0] - b[0])
        if abs(d) < 1e-12:
            return q
        t = ((p[0] - a[0]) * (a[1] - b[1]) - (p[1] - a[1]) * (a[0] - b[0])) / d
        return (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]))

    out, edges = counter_clockwise(subject), counter_clockwise(clip)
    for i in range(len(edges)):
        a, b = edges[i - 1], edges[i]
        points, out = out, []
        for j in range(len(points)):
            p, q = points[j - 1], points[j]
            if inside(q, a, b):
                if not inside(p, a, b):
                    out.append(crossing(p, q, a, b))
                out.append(q)
            elif inside(p, a, b):
                out.append(crossing(p, q, a, b))
        if not out:
            return 0.0
    return area(out) if len(out) >= 3 else 0.0


def quantile(ordered, q):
    """The q-quantile of an ascending list, by its lower index (no interpolation)."""
    return ordered[int(q * len(ordered))]


def offset_in_vehicle_frame(box, vehicle_row, vehicle_box):
    """A box's centre relative to a vehicle's, along its direction of travel (vx, vy of gt_obb.csv;
    its axis when it stands) and across it, and the angle between their longer sides (deg)."""
    vx, vy = float(vehicle_row["vx"]), float(vehicle_row["vy"])
    if math.hypot(vx, vy) == 0:
        vx, vy = math.cos(math.radians(vehicle_box[4])), math.sin(math.radians(vehicle_box[4]))
    speed = math.hypot(vx, vy)
    dx, dy = box[0] - vehicle_box[0], box[1] - vehicle_box[1]

    def long_axis(b):
        return b[4] if b[3] >= b[2] else b[4] + 90.0
    axis = abs((long_axis(box) - long_axis(vehicle_box) + 90.0) % 180.0 - 90.0)
    return (dx * vx + dy * vy) / speed, (-dx * vy + dy * vx) / speed, axis


def read_boxes(path, keep):
    rows = collections.defaultdict(list)
    with open(path) as f:
        for r in csv.DictReader(f):
            if keep(r):
                box = tuple(float(r[k]) for k in ("cx", "cy", "width", "length", "angle_deg"))
                rows[int(r["frame"])].append((r, box, corners(*box)))
    return rows


def belongs(box, thing):
    """`uavmot eval`'s rule: the box covers at least half of the thing, or half of the box lies on it."""
    shared = intersection_area(box, thing)
    return shared >= 0.5 * area(thing) or shared >= 0.5 * area(box)


def read_run(sequence, result):
    """Every ground-truth vehicle, the confirmed track boxes and the frame each track first appeared
    in (tentative included), by frame; tracks_obb.csv is read once."""
    truth = read_boxes(f"{sequence}/gt/gt_obb.csv", lambda r: True)
    every_track = read_boxes(f"{result}/tracks_obb.csv", lambda r: True)
    confirmed = collections.defaultdict(list)
    started = {}
    for frame in sorted(every_track):
        for row in every_track[frame]:
            started.setdefault(int(row[0]["id"]), frame)
            if row[0]["state"] == "confirmed":
                confirmed[frame].append(row)
    return truth, confirmed, started


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sequence, result = sys.argv[1], sys.argv[2]
    try:
        truth, tracks, _ = read_run(sequence, result)
    except KeyError as e:
        print(f"false_alarm_places: a column is missing in gt_obb.csv or tracks_obb.csv: {e}", file=sys.stderr)
        sys.exit(2)
    except (OSError, ValueError) as e:
        print(f"false_alarm_places: {e}", file=sys.stderr)
        sys.exit(2)
    places = collections.Counter()
    overlapping = collections.Counter()  # (vehicle has its own box or was missed, box size) -> boxes
    beside_a_found_vehicle = 0
    misplaced = []  # (along, across, axis error) of the similar-sized boxes on a vehicle the run missed
    missed_with_boxes = collections.Counter()  # missed moving vehicles by false-alarm boxes on them (0, 1, 2 = two or more)
    for frame, boxes in sorted(tracks.items()):
        vehicles = truth.get(frame, [])
        owner = []
        for _, _, poly in boxes:
            found = None
            for g, _, gpoly in vehicles:
                if belongs(poly, gpoly):
                    found = g["id"]
                    break
            owner.append(found)
        found_vehicles = {o for o in owner if o is not None}
        for g, _, gpoly in vehicles:
            if g["moving"] != "1" or g["id"] in found_vehicles:
                continue
            on_it = sum(1 for (_, _, poly), o in zip(boxes, owner) if o is None and intersection_area(poly, gpoly) > 0)
            missed_with_boxes[min(on_it, 2)] += 1
        for (_, box, poly), o in zip(boxes, owner):
            if o is not None:
                continue
            moving = [(math.hypot(gbox[0] - box[0], gbox[1] - box[1]), g, gbox, gpoly)
                      for g, gbox, gpoly in vehicles if g["moving"] == "1"]
            if not moving:
                places["far"] += 1
                continue
            distance, g, gbox, gpoly = min(moving, key=lambda m: m[0])
            if intersection_area(poly, gpoly) > 0:
                places["overlapping"] += 1
                ratio = area(poly) / max(area(gpoly), 1e-9)
                size = "larger" if ratio > 1.5 else "smaller" if ratio < 0.67 else "similar"
                overlapping["own box" if g["id"] in found_vehicles else "missed", size] += 1
                if size == "similar" and g["id"] not in found_vehicles:
                    misplaced.append(offset_in_vehicle_frame(box, g, gbox))
            elif distance < 1.5 * gbox[3]:
                places["beside"] += 1
            else:
                places["far"] += 1
                continue
            beside_a_found_vehicle += g["id"] in found_vehicles
    total = sum(places.values())
    print(f"{result}: {total} false-alarm boxes")
    for place in ("overlapping", "beside", "far"):
        print(f"  {place:12s} {places[place]:6d}  {100.0 * places[place] / max(total, 1):5.1f} %")
    print(f"  near a vehicle that has its own box: {beside_a_found_vehicle} ({100.0 * beside_a_found_vehicle / max(total, 1):.1f} %)")
    for own in ("missed", "own box"):
        label = "on a vehicle the run missed" if own == "missed" else "on a vehicle with its own box"
        sizes = ", ".join(f"{size} {overlapping[own, size]}" for size in ("similar", "larger", "smaller"))
        print(f"  overlapping, {label}: {sum(overlapping[own, s] for s in ('similar', 'larger', 'smaller'))} ({sizes})")
    if misplaced:
        along = sorted(m[0] for m in misplaced)
        across = sorted(abs(m[1]) for m in misplaced)
        axis = sorted(m[2] for m in misplaced)
        print(f"  similar-sized boxes on a vehicle the run missed, against it: offset along its travel median "
              f"{quantile(along, 0.5):+.2f} px (quartiles {quantile(along, 0.25):+.2f}, {quantile(along, 0.75):+.2f}), "
              f"across {quantile(across, 0.5):.2f} px; axis off by a median {quantile(axis, 0.5):.1f} deg, "
              f"more than 30 deg in {100.0 * sum(a > 30 for a in axis) / len(axis):.0f} %")
    missed = sum(missed_with_boxes.values())
    print(f"missed moving instances in frames with boxes: {missed}; with a false-alarm box on them: "
          f"{missed_with_boxes[1] + missed_with_boxes[2]} (one {missed_with_boxes[1]}, two or more {missed_with_boxes[2]})")


if __name__ == "__main__":
    main()
