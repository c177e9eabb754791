#!/usr/bin/env python3
"""Python call overhead of surfgrow.grow against the library call it wraps (issue 16).

    python_overhead.py [--runs 15] [--threads 1] [--json FILE]

Simulates the I-beam channel from one pose (233,375 points), then for three inputs (a float32
array, a float64 array, a surfgrow.Cloud) calls surfgrow.grow 2 times to warm up and --runs
times measured. Each call is timed twice: its Python wall time (time.perf_counter around
surfgrow.grow) and the library's own time of that call, summary['seconds']['call'] (measured in
C++ around the library call, GIL released). The overhead is the median over the runs of
(wall - call) / call: argument parsing, the conversion of a float64 array (a float32 one is
read in place), the result object. The
target is 5 %.
"""

import argparse
import json
import statistics
import sys
import time

import numpy as np

import surfgrow

TARGET = 0.05
WARMUP = 2


def measure(points, runs, threads):
    wall, call = [], []
    for k in range(WARMUP + runs):
        t = time.perf_counter()
        r = surfgrow.grow(points, threads=threads)
        w = time.perf_counter() - t
        if k >= WARMUP:
            wall.append(w)
            call.append(r.summary["seconds"]["call"])
    over = [(w - c) / c for w, c in zip(wall, call)]
    return {"runs": runs, "points": len(r.labels), "surfaces": len(r),
            "median_wall_s": statistics.median(wall), "median_call_s": statistics.median(call),
            "median_overhead": statistics.median(over), "max_overhead": max(over),
            "within_target": statistics.median(over) <= TARGET,
            "wall_s": wall, "call_s": call}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=15, help="measured calls per input (default 15)")
    ap.add_argument("--threads", type=int, default=1, help="grow's threads (default 1)")
    ap.add_argument("--json", metavar="FILE", help="write the numbers to FILE")
    args = ap.parse_args()
    if args.runs < 1:
        ap.error("--runs must be at least 1")

    scan = surfgrow.simulate("ibeam-channel", poses=1, seed=1)
    p32 = np.ascontiguousarray(scan.points, dtype=np.float32)
    inputs = {"float32 array": p32, "float64 array": p32.astype(np.float64),
              "Cloud": scan.cloud}
    print(f"surfgrow {surfgrow.__version__}: ibeam-channel, 1 pose, {len(p32)} points, "
          f"threads {args.threads}, {args.runs} runs after {WARMUP} warm-ups")
    results = {}
    print(f"{'input':<15} {'median wall':>12} {'median call':>12} {'overhead':>9} {'max':>8}  "
          f"within {100 * TARGET:.0f} %")
    for name, points in inputs.items():
        m = measure(points, args.runs, args.threads)
        results[name] = m
        print(f"{name:<15} {m['median_wall_s'] * 1e3:>9.2f} ms {m['median_call_s'] * 1e3:>9.2f} ms "
              f"{100 * m['median_overhead']:>7.2f} % {100 * m['max_overhead']:>6.2f} %  "
              f"{'yes' if m['within_target'] else 'no'}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"version": surfgrow.__version__, "scene": "ibeam-channel", "poses": 1,
                       "seed": 1, "points": len(p32), "threads": args.threads,
                       "warmup": WARMUP, "target": TARGET, "inputs": results}, f, indent=2)
            f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
