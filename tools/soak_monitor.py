#!/usr/bin/env python3
"""Runs one long lossless chain (`uavmot launch`) and watches it: the RSS of every component process
from /proc, and the frames each one received and published from the health topic (`uavmot status
--json`). Prints a report and exits non-zero when a process crashed or was respawned, when the
frame counts of a component disagree, or when a component's RSS grew beyond the bound after the
warm-up. tools/soak.sh prepares the input and calls this; see docs/developing.md (Soak)."""

import argparse
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time

COMPONENTS = ["source", "motion", "segmentation", "tracking", "sink"]


def rss_kib(pid):
    """VmRSS and VmHWM (peak) of a live process in KiB, or None once it is gone."""
    try:
        with open(f"/proc/{pid}/status") as f:
            fields = dict(line.split(":", 1) for line in f if ":" in line)
        return int(fields["VmRSS"].split()[0]), int(fields["VmHWM"].split()[0])
    except (FileNotFoundError, ProcessLookupError, KeyError):
        return None


class LoggedProcess:
    """A child process whose output lines are copied to a log and handed to on_line() on a thread.
    Subclasses set up their own state before calling this constructor: lines may arrive at once."""

    def __init__(self, command, log_path, stderr):
        self.log = open(log_path, "w")
        self.proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=stderr, text=True)
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        for line in self.proc.stdout:
            self.log.write(line)
            self.log.flush()
            self.on_line(line)

    def on_line(self, line):
        raise NotImplementedError


class Launch(LoggedProcess):
    """`uavmot launch` with its output copied to a log and parsed for pids, exits and respawns."""

    START = re.compile(r"^\[launch\s*\] started (\S+) \(pid (\d+)\)")
    TROUBLE = re.compile(r"respawning|no respawns left|failed|killed by signal|SIGKILL")
    PUBLISHED = re.compile(r"\[source\] \[info\] published (\d+) frames in ")

    def __init__(self, command, log_path):
        self.pids = {}
        self.published = None  # the source's own count at its end (its log)
        self.trouble = []
        super().__init__(command, log_path, subprocess.STDOUT)

    def on_line(self, line):
        m = self.START.match(line)
        if m:
            name, pid = m.group(1), int(m.group(2))
            if name in self.pids:
                self.trouble.append(f"{name} started again (pid {pid})")
            self.pids[name] = pid
        elif line.startswith("[launch") and self.TROUBLE.search(line):
            self.trouble.append(line.strip())
        m = self.PUBLISHED.search(line)
        if m:
            self.published = int(m.group(1))


class Status(LoggedProcess):
    """`uavmot status --json`: keeps the last row of every component."""

    def __init__(self, command, log_path):
        self.rows = {}
        super().__init__(command, log_path, subprocess.DEVNULL)

    def on_line(self, line):
        try:
            table = json.loads(line)
        except json.JSONDecodeError:
            return
        for row in table:
            self.rows[row["component"]] = row

    def frames(self, component):
        row = self.rows.get(component)
        return row["frames_out"] if row else 0

    def stop(self):
        self.proc.send_signal(signal.SIGINT)
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        self.thread.join(timeout=5)
        self.log.close()


def mib(kib):
    return kib / 1024.0


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--bin", required=True, help="folder with uavmot and the uavmot-* programs")
    p.add_argument("--profile", required=True)
    p.add_argument("--input", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--frames", type=int, required=True)
    p.add_argument("--domain", type=int, required=True)
    p.add_argument("--interval", type=float, default=5.0, help="seconds between RSS samples")
    p.add_argument("--warmup-frames", type=int, required=True, help="RSS growth is measured from here")
    p.add_argument("--max-growth-mib", type=float, required=True, help="allowed RSS growth after the warm-up")
    a = p.parse_args()

    os.makedirs(a.out, exist_ok=True)
    uavmot = os.path.join(a.bin, "uavmot")
    status = Status([uavmot, "status", "--json", "--interval", "1", "--stale", "30", "--domain", str(a.domain)],
                    os.path.join(a.out, "status.jsonl"))
    launch_cmd = [uavmot, "launch", a.profile, "--input", a.input, "--out", os.path.join(a.out, "results"),
                  "--set", f"domain={a.domain}", "--set", "mode=lossless", "--set", f"frames={a.frames}",
                  "--set", "loop=true"]
    start = time.monotonic()
    launch = Launch(launch_cmd, os.path.join(a.out, "launch.log"))

    samples = []  # (seconds, source frames, {component: rss KiB})
    peak = {}
    warm = None  # index into samples of the first one after the warm-up
    with open(os.path.join(a.out, "rss.tsv"), "w") as tsv:
        tsv.write("seconds\tframes\t" + "\t".join(f"{c}_rss_kib" for c in COMPONENTS) + "\n")
        while launch.proc.poll() is None:
            time.sleep(a.interval)
            rss = {}
            for c in COMPONENTS:
                pid = launch.pids.get(c)
                r = rss_kib(pid) if pid else None
                if r:
                    rss[c], peak[c] = r[0], max(peak.get(c, 0), r[1])
            frames = status.frames("source")
            # Only samples with every process alive: the end of the run, when they exit one by one, is not steady state.
            if len(rss) == len(COMPONENTS):
                samples.append((time.monotonic() - start, frames, rss))
                tsv.write(f"{samples[-1][0]:.1f}\t{frames}\t" + "\t".join(str(rss[c]) for c in COMPONENTS) + "\n")
                tsv.flush()
                if warm is None and frames >= a.warmup_frames:
                    warm = len(samples) - 1
    duration = time.monotonic() - start
    launch.thread.join(timeout=10)
    time.sleep(3)  # the last health reports (state finished) reach the status reader
    status.stop()

    failures = list(launch.trouble)
    notes = []
    if launch.proc.returncode != 0:
        failures.append(f"uavmot launch exited with {launch.proc.returncode}")
    lines = [f"soak: {a.frames} frames, lossless, domain {a.domain}, input {a.input}",
             f"soak: duration {duration:.0f} s ({a.frames / duration:.1f} frames/s end to end), "
             f"{len(samples)} RSS samples every {a.interval:g} s, warm-up {a.warmup_frames} frames",
             f"{'component':<13} {'pid':>7} {'state':>9} {'frames in':>10} {'frames out':>10} {'invalid':>7} "
             f"{'RSS warm MiB':>12} {'RSS end MiB':>11} {'growth MiB':>10} {'peak MiB':>8}"]
    for c in COMPONENTS:
        row = status.rows.get(c, {})
        fin, fout = row.get("frames_in", -1), row.get("frames_out", -1)
        if c == "source" and row.get("state") != "finished" and launch.published is not None:
            # Seen once under heavy load: the source's health reports stopped reaching `uavmot status`
            # while it kept publishing; its own end-of-run count is then the one to check.
            notes.append(f"source: last health report at frame {fout} ({row.get('state', '?')}); "
                         f"its log says it published {launch.published}")
            fin = fout = launch.published
        warm_rss = samples[warm][2][c] if warm is not None else None
        end_rss = samples[-1][2][c] if samples else None
        growth = mib(end_rss - warm_rss) if warm_rss is not None and end_rss is not None else None
        lines.append(f"{c:<13} {launch.pids.get(c, 0):>7} {row.get('state', '?'):>9} {fin:>10} {fout:>10} "
                     f"{row.get('invalid_samples', -1):>7} "
                     f"{mib(warm_rss) if warm_rss else float('nan'):>12.1f} {mib(end_rss) if end_rss else float('nan'):>11.1f} "
                     f"{growth if growth is not None else float('nan'):>10.1f} {mib(peak.get(c, 0)):>8.1f}")
        if fin != a.frames or fout != a.frames:
            failures.append(f"{c}: frames in/out {fin}/{fout}, expected {a.frames}/{a.frames}")
        if row.get("invalid_samples", 0) != 0:
            failures.append(f"{c}: {row.get('invalid_samples')} invalid samples")
        if growth is None:
            failures.append(f"{c}: no RSS sample after the warm-up")
        elif growth > a.max_growth_mib:
            failures.append(f"{c}: RSS grew by {growth:.1f} MiB after the warm-up (bound {a.max_growth_mib:g} MiB)")
    lines += [f"soak: note: {n}" for n in notes]
    lines += [f"soak: FAIL: {f}" for f in failures] or [f"soak: PASS (RSS growth bound {a.max_growth_mib:g} MiB per component)"]
    report = "\n".join(lines) + "\n"
    sys.stdout.write(report)
    with open(os.path.join(a.out, "report.txt"), "w") as f:
        f.write(report)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
