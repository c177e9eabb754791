#!/usr/bin/env python3
"""Kills surfgrow at every step of each writing command's commit and checks what is left.

For each command that writes (grow, planes, coverage, occupancy, collide, eval, scan, scan2cloud,
sweep, study, render, view) the output is first made by an earlier run (the "old" result). The
command is then run again under strace, which sends SIGKILL at the k-th call of one system call:
every fsync, rename, link, unlink, mkdir and rmdir the command makes, and a spread of its writes.
After each kill the output must be exactly the old result or exactly the new one (every file's
bytes; files with timings only by presence), the user's own file in it untouched. A last, clean
run must then leave nothing of the killed ones behind: no staging folder, no temporary.

Usage: crash_consistency.py SURFGROW [--only CMD,...]. Exit 77 (skipped) without a working strace.
"""
import argparse
import hashlib
import os
import random
import shutil
import subprocess
import sys
import tempfile

COMMIT_CALLS = ["fsync", "fdatasync", "rename", "renameat", "renameat2", "link", "linkat",
                "unlink", "unlinkat", "rmdir", "mkdir", "mkdirat"]
WRITE_SAMPLES = 4  # kills spread over the command's write() calls (staging the files)
SKIP = 77


def die(msg):
    print(f"FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def run(cmd, check=True, **kw):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)
    if check and p.returncode != 0:
        die(f"{' '.join(cmd)} exited {p.returncode}:\n{p.stderr}")
    return p


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def state(target):
    """Every file under target (a folder or one file) with its bytes' hash."""
    if not os.path.lexists(target):
        return {}
    if os.path.isfile(target):
        return {".": digest(target)}
    out = {}
    for root, dirs, files in os.walk(target):
        for name in files + [d for d in dirs if os.path.islink(os.path.join(root, d))]:
            p = os.path.join(root, name)
            out[os.path.relpath(p, target)] = digest(p)
    return out


def copy(src, dst):
    if os.path.isdir(dst) and not os.path.islink(dst):
        shutil.rmtree(dst)
    elif os.path.lexists(dst):
        os.remove(dst)
    if os.path.isdir(src):
        shutil.copytree(src, dst, symlinks=True)
    elif os.path.exists(src):
        shutil.copy2(src, dst)


def syscall_counts(cmd, cwd):
    """Calls per system call of the main thread's commit set and write(), under strace."""
    log = os.path.join(cwd, "strace.log")
    run(["strace", "-f", "-qq", "-o", log, "-e", "trace=" + ",".join(COMMIT_CALLS + ["write"]),
         "--"] + cmd, cwd=cwd)
    counts = {}
    main = None
    with open(log) as f:
        for line in f:
            pid, rest = line.split(None, 1)
            main = main or pid
            if pid != main:  # accounting is per tracee; the commit runs on the main thread
                continue
            name = rest.split("(", 1)[0]
            if name in COMMIT_CALLS + ["write"]:
                counts[name] = counts.get(name, 0) + 1
    os.remove(log)
    return counts


def leftovers(target):
    """Entries a killed run may leave that a clean run must remove: staging beside the target,
    temporaries inside it or beside a file."""
    parent, name = os.path.split(os.path.abspath(target))
    found = [e for e in os.listdir(parent)
             if e.startswith(f".{name}.staging-") or e.startswith(f".{name}.old-")
             or e.startswith(f".{name}.tmp-")]
    if os.path.isdir(target):
        found += [e for e in os.listdir(target) if ".tmp-" in e]
    return found


class Case:
    def __init__(self, name, target, prepare, command, volatile=(), writes=True):
        self.name = name          # the command tested
        self.target = target      # the output folder or file, relative to the work folder
        self.prepare = prepare    # commands making the old result (and inputs)
        self.command = command    # the command killed
        self.volatile = set(volatile)  # files with timings: compared by presence
        self.writes = writes      # also kill at a spread of write() calls


def check_case(surfgrow, work, case):
    def sg(args):
        return [surfgrow] + args

    base = os.path.join(work, case.name)
    os.makedirs(base)
    for args in case.prepare:
        run(sg(args), cwd=base)
    target = os.path.join(base, case.target)
    if os.path.isdir(target):
        with open(os.path.join(target, "notes.txt"), "w") as f:
            f.write("the user's own file\n")
    saved_old = os.path.join(work, case.name + ".old")
    copy(target, saved_old)
    old = state(target)

    # The new result, twice: files that differ between two clean runs hold timings.
    run(sg(case.command), cwd=base)
    new = state(target)
    copy(saved_old, target)
    run(sg(case.command), cwd=base)
    again = state(target)
    volatile = {f for f in new if again.get(f) != new[f]} | case.volatile
    if set(new) != set(again):
        die(f"{case.name}: two clean runs wrote different files: {sorted(set(new) ^ set(again))}")
    if old == new:
        die(f"{case.name}: the new result equals the old one: the test could not tell them apart")
    if os.path.isdir(target) and new.get("notes.txt") != old.get("notes.txt"):
        die(f"{case.name}: the user's notes.txt did not survive a clean run")

    def matches(now, ref):
        return set(now) == set(ref) and all(now[f] == ref[f] for f in ref if f not in volatile)

    copy(saved_old, target)
    counts = syscall_counts(sg(case.command), base)
    points = [(c, k) for c in COMMIT_CALLS for k in range(1, counts.get(c, 0) + 1)]
    writes = counts.get("write", 0)
    if case.writes and writes:
        points += [("write", k) for k in sorted({1 + (writes - 1) * i // (WRITE_SAMPLES - 1)
                                                 for i in range(WRITE_SAMPLES)})]
    killed = 0
    for call, k in points:
        copy(saved_old, target)
        p = run(["strace", "-f", "-qq", "-o", "/dev/null",
                 "-e", f"inject={call}:signal=KILL:when={k}", "--"] + sg(case.command),
                check=False, cwd=base)
        killed += p.returncode != 0
        now = state(target)
        is_old, is_new = matches(now, old), matches(now, new)
        if not (is_old or is_new):
            gone = sorted(set(old) - set(now))
            extra = sorted(set(now) - set(old) - set(new))
            changed = sorted(f for f in now if f in old and now[f] != old[f] and f not in volatile)
            die(f"{case.name}: killed at {call} #{k} (exit {p.returncode}): the output is neither "
                f"the old result nor the new one; missing {gone}, unknown {extra}, changed from "
                f"old {changed}")
        # The next run into the same output cleans up and gives the new result.
        if call in ("renameat2", "rename", "unlink", "unlinkat", "rmdir") or k == 1:
            run(sg(case.command), cwd=base)
            if not matches(state(target), new):
                die(f"{case.name}: after a kill at {call} #{k}, a clean run did not give the new "
                    f"result")
            left = leftovers(target)
            if left:
                die(f"{case.name}: after a kill at {call} #{k}, a clean run left {left}")
    if killed == 0:
        die(f"{case.name}: no injected kill took effect: strace did not inject")
    print(f"{case.name}: {len(points)} kill points ({killed} killed the run): the output was "
          f"always the old or the new result")


def box_cloud(path, n=24000, seed=5):
    """Three faces of a 1 m box with 1 mm noise, in metres, as text: a fast input."""
    rng = random.Random(seed)
    with open(path, "w") as f:
        for i in range(n):
            u, v, w = rng.random(), rng.random(), rng.gauss(0, 0.001)
            p = [(u, v, w), (u, w, v), (w, u, v)][i % 3]
            f.write(f"{p[0]:.5f} {p[1]:.5f} {p[2]:.5f}\n")


ROBOT = ('{"units": "m", "links": [{"name": "tool", "type": "sphere", '
         '"centre": [0.5, 0.5, 0.3], "radius": 0.05}]}\n')


def cases():
    grown = ["grow", "../box.xyz", "--mu", "40mm", "-q", "-o", "out"]
    scan = ["scan", "--scene", "room-corner", "--poses", "1", "--max-range", "1.5m", "-q"]
    acquire = ["acquire", "--emulate", "room-corner", "--tilt", "-10deg:10deg:1deg",
               "--readings", "3", "-q"]
    return [
        Case("grow", "out", [grown], ["grow", "../box.xyz", "--mu", "40mm", "--seed", "7",
                                      "-q", "-o", "out"]),
        Case("planes", "out", [grown],
             ["planes", "out", "--cloud", "../box.xyz", "--obj", "-q"]),
        Case("coverage", "out", [grown[:-2] + ["--no-coverage", "-o", "out"]],
             ["coverage", "out", "-q"]),
        Case("occupancy", "out", [grown[:-2] + ["--no-occupancy", "-o", "out"]],
             ["occupancy", "out", "--cloud", "../box.xyz", "-q"]),
        Case("collide", "out", [grown], ["collide", "out", "--robot", "../robot.json", "-q"]),
        Case("eval", "out", [scan + ["-o", "truth"],
                             ["grow", "truth/cloud.ply", "-q", "--no-picture", "-o", "out"]],
             ["eval", "out", "--truth", "truth", "-q"]),
        Case("scan", "truth", [scan + ["-o", "truth"]], scan + ["--seed", "2", "-o", "truth"],
             writes=False),
        Case("scan2cloud", "one.ply", [scan + ["-o", "truth"],
                                       ["scan2cloud", "truth/scan-000.sgraw", "-o", "one.ply"]],
             ["scan2cloud", "truth/scan-000.sgraw", "--max-range", "1m", "-o", "one.ply"]),
        Case("acquire", "one.sgraw", [acquire + ["-o", "one.sgraw"]],
             acquire + ["--seed", "2", "-o", "one.sgraw"], writes=False),
        Case("sweep", "sweep", [["sweep", "../box.xyz", "--mu", "30mm:60mm", "--steps", "2",
                                 "--min-pts", "10", "-q", "-o", "sweep"]],
             ["sweep", "../box.xyz", "--mu", "30mm:60mm", "--steps", "2", "--min-pts", "5,10",
              "-q", "-o", "sweep"], writes=False),
        Case("study", "study", [["study", "--scene", "room-corner", "--poses", "1", "--sizes",
                                 "5k,10k", "-q", "-o", "study"]],
             ["study", "--scene", "room-corner", "--poses", "1", "--sizes", "5k,20k", "-q",
              "-o", "study"], writes=False),
        Case("render", "pic.png", [grown, ["render", "out", "-o", "pic.png", "-q"]],
             ["render", "out", "--view", "front", "-o", "pic.png", "-q"]),
        Case("view", "view.html", [grown, ["view", "out", "-o", "view.html", "-q"]],
             ["view", "out", "--cloud", "../box.xyz", "-o", "view.html", "-q"]),
    ]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("surfgrow")
    ap.add_argument("--only", default="", help="comma-separated commands")
    a = ap.parse_args()
    surfgrow = os.path.abspath(a.surfgrow)
    if not shutil.which("strace"):
        print("strace is not installed: skipped", file=sys.stderr)
        sys.exit(SKIP)
    if subprocess.run(["strace", "-qq", "-o", "/dev/null", "true"]).returncode != 0:
        print("strace cannot trace here (ptrace refused): skipped", file=sys.stderr)
        sys.exit(SKIP)
    only = set(filter(None, a.only.split(",")))
    unknown = only - {case.name for case in cases()}
    if unknown:
        die(f"--only names no case: {sorted(unknown)}")
    with tempfile.TemporaryDirectory(prefix="surfgrow-crash-") as work:
        box_cloud(os.path.join(work, "box.xyz"))
        with open(os.path.join(work, "robot.json"), "w") as f:
            f.write(ROBOT)
        for case in cases():
            if not only or case.name in only:
                check_case(surfgrow, work, case)
    print("crash consistency: all outputs were whole after every kill")


if __name__ == "__main__":
    main()
