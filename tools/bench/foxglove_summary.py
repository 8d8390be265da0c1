#!/usr/bin/env python3
"""Summarises tools/bench/foxglove_bench.sh output: per configuration the median over the runs of
the live chain's median latency and the lossless chain's throughput, each also as the median of every run's change
against the same run's `none` (runs interleave the configurations, so pairing takes out the drift of
the host between runs), and the bridge's and viewers' CPU seconds against the chain's.

    python3 tools/bench/foxglove_summary.py BENCH_OUTPUT.txt BENCH_DIR

The throughput is taken from the lossless launch's log in BENCH_DIR (lossless-CONFIG-RUN.log): frames
over the time from the source's first frame published to the sink's last frame written. The bench's
own "lossless fps" (the launch's wall time) also counts start-up, discovery and shutdown, 3-4 s of
a 9 s run that vary more between runs than the chain does.
"""
import os
import re
import statistics
import sys

STAMP = r"\[(\d\d):(\d\d):(\d\d\.\d+)\]"


def seconds(match):
    return int(match[0]) * 3600 + int(match[1]) * 60 + float(match[2])


def throughput(log_path):
    """Frames per second from the source's first frame published to the sink's last frame written."""
    published = written = None
    for line in open(log_path, errors="replace"):
        m = re.search(STAMP + r" \[source\] \[info\] published (\d+) frames in ([\d.]+) s", line)
        if m:
            published = (seconds(m.groups()[:3]) - float(m[5]), int(m[4]))
        m = re.search(STAMP + r" \[sink\] \[info\] stream '[^']*': (\d+) frames written", line)
        if m:
            written = (seconds(m.groups()[:3]), int(m[4]))
    if not published or not written or written[1] != published[1]:
        return None
    return written[1] / (written[0] - published[0])


def parse(path, bench_dir):
    runs = {}  # (config, run) -> fields
    for line in open(path):
        parts = [p.strip() for p in line.split("|")]
        if len(parts) != 5:
            continue
        head = parts[0].split()
        if len(head) != 2 or head[0] not in ("none", "0", "1", "4") or not head[1].isdigit():
            continue
        live = parts[1].split()
        if not live or live[0] == "failed" or parts[3] == "failed":
            continue
        cpu = [float(x) for x in parts[2].split("/")]
        fps = throughput(os.path.join(bench_dir, f"lossless-{head[0]}-{head[1]}.log"))
        if fps is None:
            continue
        runs[(head[0], int(head[1]))] = {
            "lists": int(live[0]), "median_ms": float(live[1]), "p99_ms": float(live[2]),
            "fps": fps, "wall_fps": float(parts[3]), "chain_cpu": cpu[0], "bridge_cpu": cpu[1], "viewer_cpu": cpu[2],
        }
    return runs


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    runs = parse(sys.argv[1], sys.argv[2])
    if not runs:
        sys.exit(f"{sys.argv[1]}: no result lines of tools/bench/foxglove_bench.sh")
    numbers = sorted({r for _, r in runs})
    print(f"{len(numbers)} runs; median over runs, paired change = median of (config - none) / none of each run (min .. max)")
    print("| config | live median latency | paired change | lossless throughput fps | paired change | bridge CPU s / 10 s | of the chain's CPU | viewers' CPU s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for config in ("none", "0", "1", "4"):
        rows = [(r, runs[(config, r)]) for r in numbers if (config, r) in runs]
        if not rows:
            continue
        med = lambda key: statistics.median(row[key] for _, row in rows)

        def paired(key):
            changes = [100.0 * (row[key] / runs[("none", r)][key] - 1.0) for r, row in rows if ("none", r) in runs]
            if config == "none" or not changes:
                return "-"
            return f"{statistics.median(changes):+.1f} % ({min(changes):+.0f} .. {max(changes):+.0f})"

        share = statistics.median(row["bridge_cpu"] / row["chain_cpu"] for _, row in rows) * 100.0
        label = {"none": "none", "0": "0 viewers", "1": "1 viewer", "4": "4 viewers"}[config]
        print(f"| {label} | {med('median_ms'):.1f} ms | {paired('median_ms')} | {med('fps'):.1f} | {paired('fps')} | "
              f"{med('bridge_cpu'):.2f} | {share:.1f} % | {med('viewer_cpu'):.2f} |")
    lists = [row["lists"] for row in runs.values()]
    print(f"track lists received per live run: {min(lists)}-{max(lists)} of 250")


if __name__ == "__main__":
    main()
