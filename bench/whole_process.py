#!/usr/bin/env python3
"""The whole `surfgrow grow` process (issue 14): what a user waits for, not only the kernel.

    bench/whole_process.py [--cli build/apps/surfgrow/surfgrow] [--runs 5] [--json FILE]

Makes the clouds with the CLI itself (`surfgrow scan`: the I-beam channel from 1 and 4 poses, the
room corner, and the demo's 3-pose channel), then times `surfgrow grow CLOUD -o OUT -q` from exec
to exit, every default output written, with 2 threads and with 1, --runs times each after one
warm-up run. Prints per cloud: the median wall time at 2 threads, the speed-up over 1 thread,
peak resident memory, the stage times from run.json (median), and the outputs' size against the
input's. The targets of issue 14 it checks: 2 threads >= 1.7x one thread, default outputs no
larger than the input, every robot output no slower than the growing.

Run it on a quiet machine (nothing else building or benchmarking): the spread is printed.
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLOUDS = [  # name, scan arguments
    ("channel-1pose", ["--scene", "ibeam-channel", "--poses", "1"]),
    ("channel-4poses", ["--scene", "ibeam-channel", "--poses", "4"]),
    ("room-corner", ["--scene", "room-corner", "--poses", "1"]),
    ("demo-3poses", ["--scene", "ibeam-channel", "--poses", "3"]),
]


def run_once(cli, cloud, out, threads):
    """Wall seconds and peak RSS (MiB) of one grow, and its run.json's seconds."""
    start = time.perf_counter()
    child = subprocess.Popen(
        [cli, "grow", str(cloud), "-o", str(out), "-q", "--threads", str(threads)])
    _, status, usage = os.wait4(child.pid, 0)  # this child's own peak, not the largest so far
    wall = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    if child.returncode != 0:
        sys.exit(f"whole_process.py: surfgrow grow {cloud} failed ({child.returncode})")
    with open(out / "run.json") as f:
        return wall, usage.ru_maxrss / 1024, json.load(f)["seconds"]


def size_of(folder):
    return sum(p.stat().st_size for p in folder.iterdir() if p.is_file() and
               not p.name.startswith("."))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default=str(ROOT / "build/apps/surfgrow/surfgrow"))
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--json", help="write every figure here")
    args = ap.parse_args()
    if not os.access(args.cli, os.X_OK):
        sys.exit(f"whole_process.py: no surfgrow at {args.cli} (scripts/build.sh builds it)")
    work = Path(tempfile.mkdtemp(prefix="surfgrow-whole-"))
    rows = []
    try:
        for name, scan_args in CLOUDS:
            scan = work / name
            subprocess.run([args.cli, "scan", *scan_args, "-o", str(scan), "-q"], check=True)
            cloud = scan / "cloud.ply"
            figures = {"cloud": name, "input_bytes": cloud.stat().st_size}
            for threads in (2, 1):
                out = work / f"{name}-out"
                run_once(args.cli, cloud, out, threads)  # warm-up: page cache, first run
                walls, peaks, stages = [], [], []
                for _ in range(args.runs):
                    wall, peak, seconds = run_once(args.cli, cloud, out, threads)
                    walls.append(wall)
                    peaks.append(peak)
                    stages.append(seconds)
                figures[f"wall_{threads}t"] = walls
                if threads == 2:
                    figures["peak_mib"] = max(peaks)
                    figures["output_bytes"] = size_of(out)
                    med = lambda key: statistics.median(s[key] for s in stages)  # noqa: E731
                    robot = {k: statistics.median(s["robot_outputs"].get(k, 0) for s in stages)
                             for k in ("planes", "coverage", "occupancy", "environment_bt",
                                       "collision")}
                    figures["stages"] = {k: med(k) for k in ("read", "algorithm", "write")}
                    figures["stages"]["growing"] = med("grow") + med("attach") + med("finish")
                    figures["stages"].update(robot)
            rows.append(figures)
    finally:
        shutil.rmtree(work, ignore_errors=True)

    print(f"surfgrow grow, whole process, {args.runs} runs after a warm-up; "
          f"median (min-max) wall seconds")
    print(f"{'cloud':16} {'2 threads':>20} {'1 thread':>8} {'speed-up':>8} {'peak MiB':>8} "
          f"{'out/in':>7}  stages at 2 threads (s)")
    for r in rows:
        w2, w1 = r["wall_2t"], r["wall_1t"]
        s = r["stages"]
        print(f"{r['cloud']:16} {statistics.median(w2):8.3f} ({min(w2):.3f}-{max(w2):.3f}) "
              f"{statistics.median(w1):8.3f} {statistics.median(w1) / statistics.median(w2):7.2f}x "
              f"{r['peak_mib']:8.0f} {r['output_bytes'] / r['input_bytes']:6.2f}x  "
              + " ".join(f"{k} {v:.3f}" for k, v in s.items()))
    print("targets: 2 threads >= 1.7x one; outputs no larger than the input (out/in <= 1); "
          "each robot output no slower than the growing")
    for r in rows:
        s = r["stages"]
        slow = [k for k in ("planes", "coverage", "occupancy", "environment_bt", "collision")
                if s[k] > s["growing"]]
        speed = statistics.median(r["wall_1t"]) / statistics.median(r["wall_2t"])
        print(f"  {r['cloud']:16} threads {'met' if speed >= 1.7 else 'not met'}, "
              f"size {'met' if r['output_bytes'] <= r['input_bytes'] else 'not met'}, "
              f"robot outputs {'met' if not slow else 'slower: ' + ', '.join(slow)}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
