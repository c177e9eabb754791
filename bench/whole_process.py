#!/usr/bin/env python3
"""The whole `surfgrow grow` process (issue 14): what a user waits for, not only the kernel.

    bench/whole_process.py [--cli build/apps/surfgrow/surfgrow] [--runs 5] [--clouds a,b]
                           [--work DIR] [--json FILE]

Makes the clouds with the CLI itself (`surfgrow scan`: the I-beam channel from 1, 3, 4 and 12
poses, the stairs from 2, the room corner from 1), then times `surfgrow grow CLOUD -o OUT -q`
from exec to exit, every default output written: --runs rounds of alternating processes (1
thread, 2 threads) after a warm-up of each, so that a burst of load from elsewhere falls on both.
Prints per cloud: the median wall time at 2 threads, the speed-up over 1 thread, peak resident
memory, the stage times from run.json (median), the outputs' size against the input's, and
whether every run's outputs are byte-identical. The targets of issue 14 it checks: 2 threads >=
1.7x one thread, default outputs no larger than the input, every robot output no slower than the
algorithm (index + grow). bench/peers/run_peers.sh runs this too and sets the figures beside the
peers' (BENCHMARK.md, "The whole process").

Run it on a quiet machine (nothing else building or benchmarking): the spread is printed. Peak
memory is wait4's: this driver is kept small, because a child's peak starts from its parent's
resident size before the exec.
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
CLOUDS = [  # key, title, `surfgrow scan` arguments
    ("channel-1pose", "I-beam channel, 1 pose", ["--scene", "ibeam-channel", "--poses", "1"]),
    ("channel-4poses", "I-beam channel, 4 poses", ["--scene", "ibeam-channel", "--poses", "4"]),
    ("stairs-2poses", "stairs, 2 poses", ["--scene", "stairs", "--poses", "2"]),
    ("room-corner", "room corner, 1 pose", ["--scene", "room-corner", "--poses", "1"]),
    ("demo-3poses", "the README's demo (channel, 3 poses)",
     ["--scene", "ibeam-channel", "--poses", "3"]),
    ("channel-12poses", "I-beam channel, 12 poses",
     ["--scene", "ibeam-channel", "--poses", "12"]),
]
ROBOT_OUTPUTS = ("planes", "coverage", "occupancy", "environment_bt", "collision")
THREADS = (1, 2)


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


def folder_bytes(folder):
    """Every file but run.json (its seconds differ from run to run), for byte-identity."""
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())
            if p.is_file() and p.name != "run.json" and not p.name.startswith(".")}


def measure(cli, key, title, scan_args, work, runs):
    """Every figure of one cloud: the raw runs per thread count, sizes, identity."""
    scan = work / key
    cloud = scan / "cloud.ply"
    if not cloud.exists():
        subprocess.run([cli, "scan", *scan_args, "-o", str(scan), "-q"], check=True)
    out = work / f"{key}-out"
    row = {"key": key, "title": title, "input_bytes": cloud.stat().st_size, "rounds": runs,
           "load1": os.getloadavg()[0], "identical": True}
    reference = None
    for t in THREADS:
        run_once(cli, cloud, out, t)  # warm-up: page cache, first run
    for _ in range(runs):
        for t in THREADS:
            wall, peak, seconds = run_once(cli, cloud, out, t)
            cur = row.setdefault(f"t{t}", {"wall": [], "peak_mib": [], "seconds": []})
            cur["wall"].append(wall)
            cur["peak_mib"].append(peak)
            cur["seconds"].append(seconds)
            now = folder_bytes(out)
            reference = reference or now
            row["identical"] = row["identical"] and now == reference
    row["output_bytes"] = size_of(out)
    with open(out / "run.json") as f:
        row["summary"] = json.load(f).get("summary", "")
    shutil.rmtree(out, ignore_errors=True)
    return row


def figures(row):
    """The medians the tables print, from one measured row."""
    t2, t1 = row["t2"], row["t1"]
    med = statistics.median
    stage = lambda k: med(s[k] for s in t2["seconds"])  # noqa: E731
    f = {"wall": med(t2["wall"]), "wall_1t": med(t1["wall"]), "peak_mib": max(t2["peak_mib"]),
         "size_ratio": row["output_bytes"] / row["input_bytes"], "read": stage("read"),
         "algorithm": stage("algorithm"), "write": stage("write"),
         "robot": {k: med(s["robot_outputs"].get(k, 0.0) for s in t2["seconds"])
                   for k in ROBOT_OUTPUTS}}
    f["speedup"] = f["wall_1t"] / f["wall"]
    f["slowest"] = max(f["robot"], key=f["robot"].get)
    f["slowest_ratio"] = f["robot"][f["slowest"]] / f["algorithm"]
    f["spread"] = (min(t2["wall"]), max(t2["wall"]))
    return f


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default=str(ROOT / "build/apps/surfgrow/surfgrow"))
    ap.add_argument("--runs", type=int, default=5, help="rounds of 1 and 2 threads")
    ap.add_argument("--clouds", default="", help="comma-separated keys (default: all): " +
                    ", ".join(c[0] for c in CLOUDS))
    ap.add_argument("--work", help="keep the clouds here and reuse them (default: a temporary "
                    "folder, removed)")
    ap.add_argument("--json", help="write every figure here")
    args = ap.parse_args()
    if not os.access(args.cli, os.X_OK):
        sys.exit(f"whole_process.py: no surfgrow at {args.cli} (scripts/build.sh builds it)")
    chosen = [c for c in CLOUDS if not args.clouds or c[0] in args.clouds.split(",")]
    if not chosen:
        sys.exit(f"whole_process.py: no cloud named {args.clouds!r}")
    work = Path(args.work) if args.work else Path(tempfile.mkdtemp(prefix="surfgrow-whole-"))
    work.mkdir(parents=True, exist_ok=True)
    rows = []
    try:
        for key, title, scan_args in chosen:
            rows.append(measure(args.cli, key, title, scan_args, work, args.runs))
    finally:
        if not args.work:
            shutil.rmtree(work, ignore_errors=True)

    print(f"surfgrow grow, whole process, {args.runs} rounds of 1 and 2 threads after a warm-up; "
          f"median (min-max) wall seconds")
    print(f"{'cloud':16} {'2 threads':>20} {'1 thread':>8} {'speed-up':>8} {'peak MiB':>8} "
          f"{'out/in':>7}  stages at 2 threads (s)")
    for r in rows:
        f = figures(r)
        stages = {"read": f["read"], "algorithm": f["algorithm"], **f["robot"],
                  "write": f["write"]}
        print(f"{r['key']:16} {f['wall']:8.3f} ({f['spread'][0]:.3f}-{f['spread'][1]:.3f}) "
              f"{f['wall_1t']:8.3f} {f['speedup']:7.2f}x {f['peak_mib']:8.0f} "
              f"{f['size_ratio']:6.2f}x  " + " ".join(f"{k} {v:.3f}" for k, v in stages.items()))
    print("targets: 2 threads >= 1.7x one, outputs byte-identical; outputs no larger than the "
          "input (out/in <= 1); each robot output no slower than the algorithm")
    for r in rows:
        f = figures(r)
        print(f"  {r['key']:16} threads {'met' if f['speedup'] >= 1.7 else 'not met'}"
              f"{'' if r['identical'] else ' (outputs DIFFER)'}, "
              f"size {'met' if f['size_ratio'] <= 1 else 'not met'}, robot outputs "
              + ("met" if f["slowest_ratio"] <= 1 else
                 f"not met ({f['slowest']} {f['slowest_ratio']:.2f}x)"))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
