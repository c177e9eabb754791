#!/usr/bin/env python3
"""Issue 18's timing: the map's step after each scan against growing one scan alone.

    bench/map_steps.py [--cli build/apps/surfgrow/surfgrow] [--baseline OTHER_CLI] [--runs 3]
                       [--poses 12] [--work DIR]

Makes the I-beam channel's scans with the CLI itself (`surfgrow scan --poses N`), then, --runs
times in turn (with --baseline: that CLI and this one alternating, so that a burst of load from
elsewhere falls on both):
- `surfgrow map scans/ -o OUT`, reading each scan's line: its step (from reading the scan to its
  folder written) and the join, grow, outputs and write times;
- `surfgrow grow` on the scan with the most points alone (`scan2cloud`, once), exec to exit;
- `surfgrow grow` on the fused cloud of all N, from exec to exit.
Prints the medians and ranges of the last three steps, of the two grows and of the whole map,
and the ratio the issue asks about: the map's step after N scans over growing one scan. Every
map run's outputs must be the same bytes (run.json aside); it says so.

Run it on a quiet machine (nothing else building or benchmarking): the spread is printed.
"""

import argparse
import json
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
STEP = re.compile(r"^scan (\d+) .*; ([0-9.]+) s \(join ([0-9.]+), grow ([0-9.]+), "
                  r"outputs ([0-9.]+), write ([0-9.]+)\)$")


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        sys.exit(f"map_steps.py: {' '.join(map(str, cmd))} failed ({r.returncode}):\n{r.stdout}"
                 f"{r.stderr}")
    return r.stdout


def timed(cmd):
    start = time.perf_counter()
    out = run(cmd)
    return time.perf_counter() - start, out


def map_once(cli, scans, out):
    wall, text = timed([cli, "map", str(scans), "-o", str(out)])
    steps = []
    for line in text.splitlines():
        m = STEP.match(line)
        if m:
            steps.append({k: float(m.group(i)) for i, k in
                          enumerate(["step", "join", "grow", "outputs", "write"], start=2)})
    return wall, steps


def folder_bytes(out):
    return {p.name: p.read_bytes() for p in sorted(out.iterdir())
            if p.is_file() and p.name != "run.json"}


def spread(values):
    return f"{statistics.median(values):.3f} s ({min(values):.3f}-{max(values):.3f})"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", default=str(ROOT / "build/apps/surfgrow/surfgrow"))
    ap.add_argument("--baseline", help="another surfgrow CLI, run alternating with --cli")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--poses", type=int, default=12)
    ap.add_argument("--work", help="keep the scans and outputs here (default: a temporary folder)")
    a = ap.parse_args()
    work = Path(a.work) if a.work else Path(tempfile.mkdtemp(prefix="surfgrow-map-steps-"))
    work.mkdir(parents=True, exist_ok=True)
    scans = work / "scans"
    if not (scans / "cloud.ply").exists():
        run([a.cli, "scan", "--scene", "ibeam-channel", "--poses", str(a.poses), "-q", "-o",
             str(scans)])
    raws = sorted(scans.glob("scan-*.sgraw"))
    with open(scans / "scan.json") as f:  # the scan with the most points
        largest = scans / max(json.load(f)["scans"], key=lambda s: s["points"])["file"]
    one = work / "one.ply"
    if not one.exists():
        run([a.cli, "scan2cloud", str(largest), "-q", "-o", str(one)])

    clis = {"this": a.cli}
    if a.baseline:
        clis["baseline"] = a.baseline
    results = {name: {"last": [], "outputs": [], "write": [], "map": [], "one": [], "fused": [],
                      "bytes": None, "same": True} for name in clis}
    for _ in range(a.runs):
        for name, cli in clis.items():
            r = results[name]
            out = work / f"map-{name}"
            shutil.rmtree(out, ignore_errors=True)
            wall, steps = map_once(cli, scans, out)
            if len(steps) != len(raws):
                sys.exit(f"map_steps.py: {len(steps)} step lines for {len(raws)} scans")
            r["map"].append(wall)
            for s in steps[-3:]:
                r["last"].append(s["step"])
                r["outputs"].append(s["outputs"])
                r["write"].append(s["write"])
            got = folder_bytes(out)
            if r["bytes"] is None:
                r["bytes"] = got
            r["same"] = r["same"] and got == r["bytes"]
            r["one"].append(timed([cli, "grow", str(one), "-q", "-o", str(work / "g1")])[0])
            r["fused"].append(
                timed([cli, "grow", str(scans / "cloud.ply"), "-q", "-o", str(work / "gN")])[0])

    print(f"I-beam channel, {len(raws)} scans; one scan = {largest.name}; {a.runs} runs")
    for name, r in results.items():
        print(f"{name} ({clis[name]}):")
        print(f"  map's step after the last 3 scans {spread(r['last'])}: outputs "
              f"{spread(r['outputs'])}, write {spread(r['write'])}")
        print(f"  grow one scan {spread(r['one'])}; grow the fused cloud {spread(r['fused'])}; "
              f"the whole map {spread(r['map'])}")
        step = statistics.median(r["last"])
        print(f"  step / one scan: {step / statistics.median(r['one']):.2f}; "
              f"step / fused: {step / statistics.median(r['fused']):.2f}; "
              f"outputs the same bytes every run: {'yes' if r['same'] else 'NO'}")
    if a.baseline and results["this"]["bytes"] != results["baseline"]["bytes"]:
        print("  the two CLIs' map outputs differ")
    if not a.work:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
