#!/usr/bin/python3
"""The peers benchmark driver: clouds, runs, metrics, BENCHMARK.md. Started by run_peers.sh.

Every tool runs in its own process on the same binary PLY; the driver enforces a time limit and
a memory limit per run (reported as "timeout" / "out of memory", never dropped), reads the
per-point labels and per-segment planes each tool writes, and computes every metric here, the
same way for all tools. See bench/peers/README.md for the protocol.
"""
import argparse
import datetime
import json
import math
import os
import platform
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
REAL_DIR = ROOT.parent / "shared" / "data" / "real"

MIN_PTS = 10          # the paper's min_pts, for every tool
# Angle thresholds: each peer's best on a sweep over the single scan (bench/peers/README.md).
# PCL compares a neighbour's normal with the current point's, so its regions drift round edges
# at 8 degrees and more; CGAL compares with the region's fitted plane and does best at 25.
PCL_RG_ANGLE = 5.0
PCL_RG_CURVATURE = 1.0  # PCL's tutorial value; 1/9 (= surfgrow's alpha 4) registered less
CGAL_RG_ANGLE = 25.0  # CGAL's default
CGAL_RANSAC_ANGLE = 25.0  # normal_threshold = cos(25 deg) ~ 0.9, CGAL's default
THREAD_ROUNDS = 3     # alternating 1-thread and N-thread processes for the speed-up
MAX_PLANES = 200      # iterative RANSAC: at most this many planes
ITERATIONS = 1000     # RANSAC hypotheses per plane (PCL, Open3D)
RECOVER_SHARE = 0.5   # GT plane recovered: a segment with >= 50 % of its points on it ...
RECOVER_DEG = 30.0    # ... and a normal within 30 degrees (Araujo & Oliveira's protocol)

# The real scans at robot scale (metres, sensor or robot frame). The ISPRS airborne tiles are
# left out: they are 100-1000 m wide with y quantised to 0.5 m, not a surface-growing input.
REAL_SCANS = [
    "pcl_data/tutorials/room_scan1.pcd",
    "pcl_data/tutorials/room_scan2.pcd",
    "plane_seg/terrain_med.pcd",
    "plane_seg/terrain_close_rect.pcd",
    "plane_seg/tilted-steps.pcd",
    "bobkov_segmentation/room1_gt_fine.pcd",
    "bobkov_segmentation/room2_gt_fine.pcd",
]

TOOLS = [
    ("surfgrow", "grow"),
    # The paper's plane test, eq. (2) alone, with the adaptive radius up to 2 mu and pooling over
    # 2 mu: surfgrow's defaults before the disk test (issue 13), for before-and-after in one run.
    ("surfgrow", "grow-paper"),
    # What a robot takes its faces from: the patches merged into bound planes (planes.json), a
    # plane fitted to each face's points. The peers' segments are whole planes too.
    ("surfgrow", "planes"),
    ("pcl", "region-growing"),
    ("pcl", "ransac"),
    ("cgal", "region-growing"),
    ("cgal", "ransac"),
    ("open3d", "ransac"),
]


def median_runs_load(results):
    """Median 1-minute load average over the runs (None without any)."""
    loads = sorted(r["load1"] for r in results.get("runs", {}).values()
                   if isinstance(r.get("load1"), (int, float)) and math.isfinite(r["load1"]))
    return loads[len(loads) // 2] if loads else None

def log(*a):
    print(*a, flush=True)


def sh(cmd):
    try:
        return subprocess.run(cmd, shell=True, capture_output=True, text=True).stdout.strip()
    except OSError:
        return ""


def machine():
    cpu = sh("lscpu | sed -n 's/^Model name: *//p' | head -1")
    mem_kb = 0
    with open("/proc/meminfo") as f:
        for line in f:
            if line.startswith("MemTotal:"):
                mem_kb = int(line.split()[1])
    os_name = sh(". /etc/os-release && echo $PRETTY_NAME")
    pk = {}
    for p in ["g++", "libpcl-dev", "libcgal-dev", "python3-open3d", "libtbb-dev", "libeigen3-dev"]:
        pk[p] = sh(f"dpkg-query -W -f='${{Version}}' {p} 2>/dev/null") or "absent"
    return {"cpu": cpu, "cores": os.cpu_count(), "memory_gib": round(mem_kb / 2**20, 1),
            "os": os_name, "kernel": platform.release(), "packages": pk,
            "python": sys.version.split()[0]}


# ---------------------------------------------------------------- running one tool, watched

def tree_rss(pid):
    """Resident bytes of pid and its descendants (the tools are single processes, but be safe)."""
    total = 0
    todo = [pid]
    while todo:
        p = todo.pop()
        try:
            with open(f"/proc/{p}/status") as f:
                for line in f:
                    if line.startswith("VmRSS:"):
                        total += int(line.split()[1]) * 1024
            with open(f"/proc/{p}/task/{p}/children") as f:
                todo += [int(c) for c in f.read().split()]
        except OSError:
            pass
    return total


def run_watched(cmd, logfile, timeout_s, mem_limit):
    """Runs cmd; kills it past timeout_s or mem_limit bytes. Returns (status, wall, maxrss)."""
    t0 = time.monotonic()
    with open(logfile, "w") as lf:
        lf.write("$ " + shlex.join(cmd) + "\n")
        lf.flush()
        p = subprocess.Popen(cmd, stdout=lf, stderr=subprocess.STDOUT, start_new_session=True)
        killed = None
        while True:
            pid, st, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if killed is None:
                if time.monotonic() - t0 > timeout_s:
                    killed = "timeout"
                elif tree_rss(p.pid) > mem_limit:
                    killed = "out of memory"
                if killed:
                    try:
                        os.killpg(p.pid, signal.SIGKILL)
                    except ProcessLookupError:
                        pass
            time.sleep(0.05)
        p.returncode = os.waitstatus_to_exitcode(st)
    wall = time.monotonic() - t0
    if killed:
        status = killed
    elif p.returncode == 0:
        status = "ok"
    elif p.returncode == -signal.SIGKILL:
        status = "out of memory"  # the kernel's OOM killer
    else:
        status = f"failed (exit {p.returncode})"
    return status, wall, ru.ru_maxrss * 1024


# ---------------------------------------------------------------- clouds

def read_ply_xyz_label(path):
    """Our own binary PLYs (make_clouds): x y z float [int label]."""
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                raise ValueError(f"{path}: no end_header")
            header += line
        props = [l.split()[-1] for l in header.decode().splitlines() if l.startswith("property")]
        n = int([l for l in header.decode().splitlines() if l.startswith("element vertex")][0]
                .split()[-1])
        fields = [(p, "<f4" if p in "xyz" else "<i4") for p in props]
        data = np.fromfile(f, dtype=np.dtype(fields), count=n)
    xyz = np.stack([data["x"], data["y"], data["z"]], axis=1).astype(np.float64)
    label = data["label"] if "label" in props else None
    return xyz, label


def make_clouds(a, build, work):
    mk = str(build / "bench/peers/make_clouds")
    clouds = []  # (name, path, meta)

    def sim(name, poses, length=None, crops=None, scene=None):
        prefix = work / "clouds" / name
        if not (prefix.with_suffix(".meta.json").exists() and prefix.with_suffix(".ply").exists()):
            cmd = [mk, "sim", "--poses", str(poses), "--out", str(prefix)]
            if scene:
                cmd += ["--scene", scene]
            if length:
                cmd += ["--length", str(length)]
            if crops:
                cmd += ["--crops", ",".join(str(c) for c in crops)]
            log("  " + shlex.join(cmd))
            subprocess.run(cmd, check=True)
        return prefix

    def add(name, prefix, scaling_only=False):
        meta = json.loads(prefix.with_suffix(".meta.json").read_text())
        clouds.append({"name": name, "path": str(prefix.with_suffix(".ply")), "meta": meta,
                       "prefix": str(prefix), "scaling_only": scaling_only})

    (work / "clouds").mkdir(parents=True, exist_ok=True)
    single = sim("channel-1scan", 1, crops=[100_000] if a.quick else None)
    add("I-beam channel, single scan", single)
    if not a.quick:
        add("I-beam channel, 4 fused scans", sim("channel-4scans", 4))
        # Issue 14's other scenes: a room where RANSAC needs only a few planes, and stairs.
        add("room corner, single scan", sim("room-corner-1scan", 1, scene="room-corner"))
        add("stairs, 2 fused scans", sim("stairs-2scans", 2, scene="stairs"))
        # 43 poses 0.5 m apart along a 26 m channel: about 10 M points at the 4-scan density.
        big = sim("channel-43scans", 43, length=26.0, crops=[100_000, 300_000, 1_000_000,
                                                             3_000_000])
        add("I-beam channel (26 m), 43 fused scans", big)
    real = REAL_SCANS[:1] if a.quick else REAL_SCANS
    for rel in real:
        src = REAL_DIR / rel
        if not src.exists():
            log(f"  (real scan {src} not present: skipped)")
            continue
        prefix = work / "clouds" / ("real-" + Path(rel).stem)
        if not prefix.with_suffix(".meta.json").exists():
            subprocess.run([mk, "real", str(src), "--out", str(prefix)], check=True)
        add("real: " + rel, prefix)
    return clouds


def tool_params(cloud):
    m = cloud["meta"]
    n = m["points"]
    mu = m["mu"]
    nb = m.get("neighbours_within_mu", {}).get("median", 20)
    return {"mu": mu, "tol": mu, "k": max(MIN_PTS, int(round(nb))), "min_pts": MIN_PTS,
            "min_plane": max(MIN_PTS, n // 1000), "pcl_angle": PCL_RG_ANGLE,
            "curvature": PCL_RG_CURVATURE, "cgal_angle": CGAL_RG_ANGLE,
            "cgal_ransac_angle": CGAL_RANSAC_ANGLE, "max_planes": MAX_PLANES,
            "iterations": ITERATIONS}


def tool_command(build, tool, method, cloud_path, out, p, threads, a):
    rep = ["--min-seconds", str(a.min_seconds), "--max-repeats", str(a.max_repeats)]
    if tool == "surfgrow":
        return [str(build / "bench/peers/peer_surfgrow"), cloud_path, "--out", out, "--mu",
                str(p["mu"]), "--min-pts", str(p["min_pts"]), "--threads", str(threads),
                "--seed", "1"] + (["--paper"] if method == "grow-paper" else []) + (
                    ["--planes"] if method == "planes" else []) + rep
    common = ["--out", out, "--k", str(p["k"]), "--tol", str(p["tol"]), "--min-pts",
              str(p["min_pts"]), "--min-plane", str(p["min_plane"])]
    if tool == "pcl":
        return [str(build / "bench/peers/peer_pcl"), cloud_path, "--method", method] + common + [
            "--angle", str(p["pcl_angle"]), "--curvature", f"{p['curvature']:.6f}",
            "--max-planes", str(p["max_planes"]), "--iterations", str(p["iterations"]),
            "--threads", str(threads)] + rep
    if tool == "cgal":
        return [str(build / "bench/peers/peer_cgal"), cloud_path, "--method", method] + common + [
            "--mu", str(p["mu"]), "--angle",
            str(p["cgal_ransac_angle"] if method == "ransac" else p["cgal_angle"]),
            "--threads", str(threads)] + rep
    if tool == "open3d":
        return ["/usr/bin/python3", str(HERE / "peer_open3d.py"), cloud_path] + common + [
            "--mu", str(p["mu"]), "--max-planes", str(p["max_planes"]), "--iterations",
            str(p["iterations"])] + rep
    raise ValueError(tool)


# ---------------------------------------------------------------- metrics

def metrics(cloud, out_dir, truth_cache):
    labels = np.fromfile(out_dir / "labels.i32", dtype="<i4")
    planes = np.fromfile(out_dir / "planes.f64", dtype="<f8").reshape(-1, 4)
    key = cloud["path"]
    if key not in truth_cache:
        truth_cache.clear()  # one cloud at a time: the 10 M one is large
        xyz, face = read_ply_xyz_label(cloud["path"])
        normals = None
        if cloud["meta"].get("truth"):
            normals = np.fromfile(cloud["prefix"] + ".normals.f32", dtype="<f4").reshape(-1, 3)
        truth_cache[key] = (xyz, face, normals)
    xyz, face, tnorm = truth_cache[key]
    n = len(xyz)
    if len(labels) != n:
        raise ValueError(f"{out_dir}: {len(labels)} labels for {n} points")
    reg = labels >= 0
    used = np.unique(labels[reg])
    r = {"points": int(n), "segments": int(len(used)), "registered_pct": 100.0 * reg.mean()}
    if reg.any():
        pl = planes[labels[reg]]
        res = np.abs(np.einsum("ij,ij->i", pl[:, :3], xyz[reg]) + pl[:, 3])
        r["residual_mean_mm"] = 1000.0 * float(res.mean())
        r["residual_p95_mm"] = 1000.0 * float(np.percentile(res, 95))
        del pl, res
    if tnorm is None:
        return r
    meta = cloud["meta"]
    # Normal error, as lines, over registered points that lie on a true face.
    m = reg & (face >= 0)
    if m.any():
        c = np.abs(np.einsum("ij,ij->i", planes[labels[m], :3], tnorm[m].astype(np.float64)))
        err = np.degrees(np.arccos(np.clip(c, 0.0, 1.0)))
        r["normal_err_median_deg"] = float(np.median(err))
        r["normal_err_p95_deg"] = float(np.percentile(err, 95))
        del c, err
    # Segment x face contingency (points on a true face only).
    nf = len(meta["faces"])
    seg = labels[m].astype(np.int64)
    fc = face[m].astype(np.int64)
    pair, cnt = np.unique(seg * nf + fc, return_counts=True)
    ps, pf = pair // nf, pair % nf
    seg_total = np.bincount(ps, weights=cnt, minlength=len(planes))
    # Majority face of each segment and its share.
    order = np.lexsort((-cnt, ps))
    first = np.ones(len(order), dtype=bool)
    first[1:] = ps[order][1:] != ps[order][:-1]
    maj_seg, maj_face, maj_cnt = ps[order][first], pf[order][first], cnt[order][first]
    r["purity_pct"] = 100.0 * maj_cnt.sum() / max(1, cnt.sum())
    # GT planes: planar faces holding at least 0.1 % of the points (the smallest plane every
    # RANSAC peer is asked to find; region growers and surfgrow are asked for less).
    min_face = max(MIN_PTS, n // 1000)
    fpts = np.array([f["points"] for f in meta["faces"]])
    fnorm = np.array([f["normal"] for f in meta["faces"]], dtype=np.float64)
    gt = np.array([f["planar"] and f["points"] >= min_face for f in meta["faces"]])
    share = maj_cnt / np.maximum(1, seg_total[maj_seg])
    cosang = np.abs(np.einsum("ij,ij->i", planes[maj_seg, :3], fnorm[maj_face]))
    ok = (share >= RECOVER_SHARE) & (cosang >= np.cos(np.radians(RECOVER_DEG))) & gt[maj_face]
    recovered = np.unique(maj_face[ok])
    r["gt_planes"] = int(gt.sum())
    r["gt_recovered"] = int(len(recovered))
    # Completeness: the largest single segment on each GT plane, as a share of the plane.
    best = np.zeros(nf)
    np.maximum.at(best, pf, cnt)
    cov = best[gt] / np.maximum(1, fpts[gt])
    r["largest_segment_share_median_pct"] = 100.0 * float(np.median(cov)) if gt.any() else 0.0
    return r


# ---------------------------------------------------------------- the runs

def run_tools(a, build, work, clouds, mem_limit, results):
    threads = os.cpu_count()
    truth = {}
    for cloud in clouds:
        p = tool_params(cloud)
        cname = Path(cloud["path"]).stem
        for tool, method in TOOLS:
            if a.only and tool not in a.only.split(","):
                continue
            rid = f"{cname}/{tool}-{method}"
            if rid in results["runs"] and not a.rerun:
                continue
            out = work / "runs" / cname / f"{tool}-{method}"
            out.mkdir(parents=True, exist_ok=True)
            for f in ("labels.i32", "planes.f64", "result.json"):
                (out / f).unlink(missing_ok=True)
            cmd = tool_command(build, tool, method, cloud["path"], str(out), p, threads, a)
            timeout = a.timeout_surfgrow if tool == "surfgrow" else a.timeout
            load = os.getloadavg()[0]
            log(f"  {rid} ...")
            status, wall, maxrss = run_watched(cmd, out / "log.txt", timeout, mem_limit)
            run = {"cloud": cloud["name"], "cloud_file": cname, "tool": tool, "method": method,
                   "status": status, "wall_s": wall, "peak_rss_bytes": maxrss, "load1": load,
                   "params": p, "command": shlex.join(cmd), "timeout_s": timeout}
            if status == "ok":
                rep = json.loads((out / "result.json").read_text())
                run["report"] = rep
                try:
                    run["metrics"] = metrics(cloud, out, truth)
                except (ValueError, OSError) as e:
                    run["status"] = f"bad output ({e})"
                (out / "labels.i32").unlink(missing_ok=True)  # large; metrics are kept
            results["runs"][rid] = run
            alg = run.get("report", {}).get("algorithm_seconds_median")
            log(f"    {status}" + (f": {alg:.4f} s algorithm, "
                                    f"{run['metrics']['registered_pct']:.1f} % registered"
                                    if alg is not None and "metrics" in run else ""))
            save(results, work)


def run_scaling(a, build, work, clouds, mem_limit, results):
    """surfgrow alone: time and memory per point over crops of the largest cloud; 1 vs N threads."""
    big = [c for c in clouds if c["meta"]["kind"] == "simulated"][-1]
    prefix = Path(big["prefix"])
    sizes = sorted(int(p.name[len(prefix.name) + 1:-4]) for p in prefix.parent.glob(
        prefix.name + "-*.ply"))
    series = [(str(prefix) + f"-{s}.ply", s) for s in sizes] + [(big["path"], big["meta"]["points"])]
    scal = results.setdefault("scaling", {})
    for path, npts in series:
        name = Path(path).stem
        if name in scal and not a.rerun:
            continue
        out = work / "scaling" / name
        out.mkdir(parents=True, exist_ok=True)
        cmd = tool_command(build, "surfgrow", "grow", path, str(out), {"mu": big["meta"]["mu"],
                           "min_pts": MIN_PTS}, os.cpu_count(), a)
        status, wall, maxrss = run_watched(cmd, out / "log.txt", a.timeout_surfgrow, mem_limit)
        row = {"status": status, "n": npts, "peak_rss_bytes": maxrss, "load1": os.getloadavg()[0]}
        if status == "ok":
            row["report"] = json.loads((out / "result.json").read_text())
            (out / "labels.i32").unlink(missing_ok=True)
        scal[name] = row
        log(f"  scaling {name}: {status}")
        save(results, work)

    thr = results.setdefault("threads", {})
    tclouds = [c for c in clouds if c["meta"]["kind"] == "simulated" and not c["scaling_only"]]
    for cloud in tclouds[:2]:
        name = Path(cloud["path"]).stem
        if name in thr and not a.rerun:
            continue
        # Rounds of alternating processes (1 thread, N threads, 1, N, ...): a burst of load from
        # other jobs then falls on both thread counts, not on one process's repeats. Seconds are
        # the median over every repeat of every round.
        row = {"rounds": THREAD_ROUNDS, "identical": True}
        reference = None  # the first run that finished: every other is compared with it
        for k in range(THREAD_ROUNDS):
            for t in (1, os.cpu_count()):
                out = work / "threads" / name / f"t{t}-r{k}"
                out.mkdir(parents=True, exist_ok=True)
                cmd = tool_command(build, "surfgrow", "grow", cloud["path"], str(out),
                                   {"mu": cloud["meta"]["mu"], "min_pts": MIN_PTS}, t, a)
                cmd[cmd.index("--max-repeats") + 1] = str(max(a.max_repeats, 5))
                status, wall, maxrss = run_watched(cmd, out / "log.txt", a.timeout_surfgrow,
                                                   mem_limit)
                cur = row.setdefault(f"t{t}", {"status": "ok", "report": None, "seconds": []})
                if status != "ok":
                    cur["status"] = status
                    row["identical"] = False
                    continue
                rep = json.loads((out / "result.json").read_text())
                cur["report"] = cur["report"] or rep
                cur["seconds"] += rep["algorithm_seconds"]
                reference = reference or out
                row["identical"] = row["identical"] and all(
                    (reference / f).read_bytes() == (out / f).read_bytes()
                    for f in ("labels.i32", "planes.f64"))
        thr[name] = row
        log(f"  threads {name}: identical={row['identical']}")
        save(results, work)

    if a.quick and "io" in results and not a.rerun:
        return
    bench_io = build / "bench/bench_io"
    if bench_io.exists():
        js = work / "bench_io.json"
        subprocess.run([str(bench_io), "--benchmark_filter=BM_ReadCloud/(ply_binary_le_float|"
                        "pcd_binary|pcd_binary_compressed)$", "--benchmark_repetitions=3",
                        "--benchmark_report_aggregates_only=true",
                        f"--benchmark_out={js}", "--benchmark_out_format=json"],
                       check=False, capture_output=True)
        if js.exists():
            rows = {}
            for b in json.loads(js.read_text()).get("benchmarks", []):
                if b.get("aggregate_name") == "median":
                    rows[b["run_name"].split("/")[-1]] = b.get("bytes_per_second", 0) / 1e6
            results["io"] = rows


# Issue 14: the whole `surfgrow grow` command, exec to exit with every default output written,
# against the fastest peer's algorithm alone on the same scan. bench/whole_process.py times it
# (in its own small process: a child's peak memory starts from its parent's size) on clouds made
# by `surfgrow scan`, as a user's would be: the same points as make_clouds' cloud of that scene,
# poses and seed, plus each point's scan and the scan origins environment.bt carves from.
PEER_CLOUD_OF = {"channel-1pose": "channel-1scan", "channel-4poses": "channel-4scans",
                 "stairs-2poses": "stairs-2scans", "room-corner": "room-corner-1scan"}
WHOLE_RATIO_TARGET = {"channel-1pose": 50, "channel-4poses": 50, "room-corner": 5}
sys.path.insert(0, str(ROOT / "bench"))
import whole_process  # noqa: E402  (the clouds, the timing and the medians: one place)


def run_whole(a, build, work, results):
    whole = results.setdefault("whole", {})
    keys = [c[0] for c in whole_process.CLOUDS[:1 if a.quick else None]
            if a.rerun or c[0] not in whole]
    if not keys:
        return
    js = work / "whole.json"
    subprocess.run(["/usr/bin/python3", str(ROOT / "bench/whole_process.py"), "--cli",
                    str(build / "apps/surfgrow/surfgrow"), "--runs", "2" if a.quick else "5",
                    "--clouds", ",".join(keys), "--work", str(work / "whole"), "--json",
                    str(js)], check=True)
    for row in json.loads(js.read_text()):
        whole[row["key"]] = row
    save(results, work)


def whole_rows(results):
    """The whole-process table's figures per cloud, with the fastest peer on the same scan."""
    rows = []
    for key, row in results.get("whole", {}).items():
        if "t1" not in row or "t2" not in row:
            continue
        r = whole_process.figures(row) | {"key": key, "title": row["title"],
                                          "identical": row["identical"],
                                          "input_bytes": row["input_bytes"],
                                          "summary": row.get("summary", "")}
        r["points"] = int(r["summary"].split(" ")[0]) if r["summary"] else None
        runs = [x for x in results["runs"].values() if x["cloud_file"] == PEER_CLOUD_OF.get(key)]
        peers = [x for x in runs if x["tool"] != "surfgrow" and x["status"] == "ok"]
        if peers:
            fastest = min(peers, key=lambda x: x["report"]["algorithm_seconds_median"])
            r["peer"] = fastest
            r["peer_s"] = fastest["report"]["algorithm_seconds_median"]
            r["ratio"] = r["peer_s"] / r["wall"]
        warm = [x for x in runs if x["tool"] == "surfgrow" and x["method"] == "grow" and
                x["status"] == "ok"]
        if warm:
            r["warm_s"] = warm[0]["report"]["algorithm_seconds_median"]
        rows.append(r)
    return rows


def whole_targets(rows, cores):
    """Issue 14's targets on the whole process: (target, measured, met) rows."""
    out = []
    for r in rows:
        goal = WHOLE_RATIO_TARGET.get(r["key"])
        if goal and "ratio" in r:
            out.append((f"whole process ≥ {goal}× faster than the fastest peer's algorithm, "
                        f"{r['title']}", f"{r['ratio']:.1f}×", r["ratio"] >= goal))
    for r in rows:
        out.append((f"{cores} threads ≥ 1.7× one on the whole process, byte-identical, "
                    f"{r['title']}", f"{r['speedup']:.2f}×, "
                    f"{'identical' if r['identical'] else 'DIFFERENT'}",
                    r["speedup"] >= 1.7 and r["identical"]))
    for r in rows:
        out.append((f"every robot output no slower than the growing, {r['title']}",
                    f"slowest {r['slowest']} {r['slowest_ratio']:.2f}×",
                    r["slowest_ratio"] <= 1.0))
    for r in rows:
        out.append((f"default outputs no larger than the input, {r['title']}",
                    f"{r['size_ratio']:.2f}×", r["size_ratio"] <= 1.0))
    for r in rows:
        if "warm_s" in r:
            q = r["algorithm"] / r["warm_s"]
            out.append((f"index + grow in a fresh process within 1.5× of the warm figure, "
                        f"{r['title']}", f"{q:.2f}× ({fmt_s(r['algorithm'])} s against "
                        f"{fmt_s(r['warm_s'])} s)", q <= 1.5))
    for r in rows:
        mbs = r["input_bytes"] / 1e6 / max(r["read"], 1e-9)
        out.append((f"reading the binary PLY in the CLI ≥ 300 MB/s, {r['title']}",
                    f"{mbs:.0f} MB/s", mbs >= 300))
    return out


def whole_section(results, cores):
    """The report's whole-process section (issue 14)."""
    rows = whole_rows(results)
    if not rows:
        return []
    L = ["## The whole process (issue 14)", "",
         "`surfgrow grow CLOUD -o OUT -q`, from exec to exit, every default output written, on "
         "clouds made by `surfgrow scan` (the same points as the peers' cloud of that scene, plus "
         "each point's scan and the scan origins). "
         f"{results['whole'][rows[0]['key']]['rounds']} rounds of alternating "
         f"processes (1 thread, {cores}) after a warm-up of each; medians. The fastest peer's "
         "figure is its algorithm alone (reading excluded) on the same scan, from the tables "
         "below; the whole-process ratio divides it by surfgrow's whole process. Algorithm: "
         "`run.json`'s index + grow + attach + finish in that process; warm: the same in "
         "`peer_surfgrow`'s repeated calls. Outputs: the result folder's bytes against the "
         "input cloud's.", "",
         f"| cloud | points | surfgrow algorithm | whole process, {cores} threads | 1 thread | "
         "speed-up | peak | outputs / input | fastest peer, algorithm alone | whole-process "
         "ratio |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        peer = (f"{label_of(r['peer']['tool'], r['peer']['method'])} {fmt_s(r['peer_s'])} s"
                if "peer" in r else "–")
        ratio = f"**{r['ratio']:.1f}×**" if "ratio" in r else "–"
        L.append(f"| {r['title']} | {r['points']:,} | {fmt_s(r['algorithm'])} s | "
                 f"{fmt_s(r['wall'])} s | {fmt_s(r['wall_1t'])} s | {r['speedup']:.2f}× | "
                 f"{r['peak_mib']:.0f} MiB | {r['size_ratio']:.2f}× | {peer} | {ratio} |")
    L += ["", f"Stages at {cores} threads (`run.json`, seconds; environment.bt is the wall time "
          "of its thread, which draws the picture meanwhile):", "",
          "| cloud | read | algorithm | planes | coverage | occupancy | environment.bt | "
          "collision | write (all files) | slowest output / algorithm |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        rb = r["robot"]
        L.append(f"| {r['title']} | {fmt_s(r['read'])} | {fmt_s(r['algorithm'])} | "
                 + " | ".join(fmt_s(rb[k]) for k in whole_process.ROBOT_OUTPUTS) +
                 f" | {fmt_s(r['write'])} | {r['slowest']} {r['slowest_ratio']:.2f}× |")
    L.append("")
    return L


def thread_seconds(row, t):
    """Seconds of surfgrow at t threads in the threads table: the median over every repeat of
    every round (a report from before the rounds: its own median)."""
    r = row.get(f"t{t}") or {}
    if r.get("seconds"):
        return float(np.median(r["seconds"]))
    return (r.get("report") or {}).get("algorithm_seconds_median")


def save(results, work):
    tmp = work / "results.json.tmp"
    tmp.write_text(json.dumps(results, indent=1))
    tmp.replace(work / "results.json")


# ---------------------------------------------------------------- the report

def fmt(v, d=1, unit=""):
    if v is None:
        return "–"
    if isinstance(v, float) and v != v:
        return "–"
    return f"{v:.{d}f}{unit}"


def fmt_s(v):
    if v is None:
        return "–"
    return f"{v:.4f}" if v < 0.1 else (f"{v:.3f}" if v < 10 else f"{v:.1f}")


def peak_of(run):
    """A run's peak resident memory, bytes. The tools' own VmHWM: wait4's ru_maxrss would also
    count this driver's memory from before the exec (Linux keeps the old mm's high-water mark).
    Runs from before the tools reported it give the algorithm phase's (input included)."""
    rep = run.get("report", {})
    return rep.get("process_peak_rss_bytes") or rep.get("algorithm_peak_rss_bytes") or 0.0


def label_of(tool, method):
    return {"surfgrow": "**surfgrow**", "pcl": "PCL", "cgal": "CGAL", "open3d": "Open3D"}[tool] + \
        " " + method


def headline(results, cloud_file, method="grow"):
    """surfgrow vs the peers on one cloud: speed ratio, registered %, normal error."""
    runs = [r for r in results["runs"].values() if r["cloud_file"] == cloud_file]
    sg = [r for r in runs if r["tool"] == "surfgrow" and r["method"] == method and "metrics" in r]
    peers = [r for r in runs if r["tool"] != "surfgrow" and "metrics" in r]
    if not sg or not peers:
        return None
    sg = sg[0]
    fastest = min(peers, key=lambda r: r["report"]["algorithm_seconds_median"])
    best_reg = max(peers, key=lambda r: r["metrics"]["registered_pct"])
    with_err = [r for r in peers if "normal_err_median_deg" in r["metrics"]]
    best_err = min(with_err, key=lambda r: r["metrics"]["normal_err_median_deg"]) \
        if with_err else None
    return {
        "surfgrow_s": sg["report"]["algorithm_seconds_median"],
        "fastest": fastest, "fastest_s": fastest["report"]["algorithm_seconds_median"],
        "ratio": fastest["report"]["algorithm_seconds_median"] /
        sg["report"]["algorithm_seconds_median"],
        "cpu_ratio": min(r["report"].get("algorithm_cpu_seconds_median") or 1e30 for r in peers) /
        max(1e-9, sg["report"].get("algorithm_cpu_seconds_median") or 1e-9),
        "sg_reg": sg["metrics"]["registered_pct"], "best_reg": best_reg,
        "sg_err": sg["metrics"].get("normal_err_median_deg"), "best_err": best_err,
    }


HEADLINE_CLOUDS = [("channel-1scan", "single scan"), ("channel-4scans", "4 fused scans")]
SG_METHODS = ["grow", "grow-paper", "planes"]


def write_report(a, results, path):
    mi = results["machine"]
    L = []
    L.append("# surfgrow against PCL, CGAL and Open3D")
    L.append("")
    L.append("Generated by `bench/peers/run_peers.py` — do not edit by hand; regenerate with the "
             "command below. Protocol, parameters and why they are comparable: "
             "[bench/peers/README.md](bench/peers/README.md).")
    L.append("")
    L.append("## Machine and command")
    L.append("")
    L.append(f"- **Command:** `{results['command']}` ({results.get('started', '?')} – {results.get('finished', 'unfinished')})")
    L.append(f"- **CPU:** {mi['cpu']}, {mi['cores']} cores; **memory:** {mi['memory_gib']} GiB; "
             f"**OS:** {mi['os']}, kernel {mi['kernel']}")
    L.append("- **Packages:** " + ", ".join(f"{k} {v}" for k, v in mi["packages"].items()))
    la = results.get("load", {})
    L.append(f"- **Load average** (1 min) at start {fmt(la.get('start'), 2)}, at end "
             f"{fmt(la.get('end'), 2)}, median over the runs {fmt(median_runs_load(results), 2)}; "
             "each run's is in its table (a run's own threads count in it). Other jobs shared this "
             f"{mi['cores']}-core machine when the load exceeds {mi['cores']}: absolute times are "
             "then noisy, ratios within a table less so.")
    lim = results.get("limits") or {
        "peer_s": max([r["timeout_s"] for r in results["runs"].values() if r["tool"] != "surfgrow"]
                      or [a.timeout]), "surfgrow_s": a.timeout_surfgrow, "mem_gb": a.mem_limit_gb}
    L.append(f"- **Limits per run:** {lim['peer_s']:g} s for a peer, {lim['surfgrow_s']:g} s for "
             f"surfgrow; {lim['mem_gb']:g} GB resident memory. Threads: {mi['cores']} for every "
             "tool that can use them (see the protocol).")
    L.append("")

    # Headline.
    L.append("## Headline")
    L.append("")
    # The start's load still holds the harness's own build (a 1-minute average), and each tool
    # adds up to its thread count: judge by the runs' median.
    median_load = median_runs_load(results)
    if median_load is None:
        median_load = max(la.get("start") or 0, la.get("end") or 0)
    if median_load > mi["cores"]:
        L.append(f"**This run shared the machine with other jobs (load average above its "
                 f"{mi['cores']} cores):** wall times are stretched, several-fold for short "
                 "multi-threaded runs; CPU seconds are given beside them. Regenerate on a quiet "
                 "machine for the figures that count.")
        L.append("")
    for (cf, title), method in [(c, m) for c in HEADLINE_CLOUDS for m in SG_METHODS]:
        h = headline(results, cf, method)
        if not h:
            continue
        title = f"{title}, surfgrow {method}"
        err = (f"median normal error {fmt(h['sg_err'], 2)}° vs the best peer's "
               f"{fmt(h['best_err']['metrics']['normal_err_median_deg'], 2)}° "
               f"({label_of(h['best_err']['tool'], h['best_err']['method'])})"
               if h["best_err"] else "")
        L.append(f"- **{title}:** surfgrow {fmt_s(h['surfgrow_s'])} s, "
                 f"**{h['ratio']:.0f}× faster** than the fastest peer "
                 f"({label_of(h['fastest']['tool'], h['fastest']['method'])}, "
                 f"{fmt_s(h['fastest_s'])} s; {h['cpu_ratio']:.0f}× in CPU time); registered {fmt(h['sg_reg'])} % vs the best peer's "
                 f"{fmt(h['best_reg']['metrics']['registered_pct'])} % "
                 f"({label_of(h['best_reg']['tool'], h['best_reg']['method'])}); {err}.")
    L.append("")

    # Targets.
    L.append("## Targets")
    L.append("")
    L.append("| target | measured | met |")
    L.append("|---|---|---|")
    for (cf, title), method in [(c, m) for c in HEADLINE_CLOUDS for m in SG_METHODS]:
        h = headline(results, cf, method)
        if not h:
            continue
        title = f"{title}, {method}"
        if method == "planes":  # the speed target is the growing's; this row is for accuracy
            L.append(f"| faster than the fastest peer (no target), {title} | {h['ratio']:.1f}× | "
                     f"– |")
        else:
            L.append(f"| ≥ 100× faster than the fastest peer, {title} | {h['ratio']:.0f}× | "
                     f"{'yes' if h['ratio'] >= 100 else 'no'} |")
        L.append(f"| registered % above every peer's, {title} | {fmt(h['sg_reg'])} % vs "
                 f"{fmt(h['best_reg']['metrics']['registered_pct'])} % | "
                 f"{'yes' if h['sg_reg'] > h['best_reg']['metrics']['registered_pct'] else 'no'} |")
        if h["best_err"] and h["sg_err"] is not None:
            be = h["best_err"]["metrics"]["normal_err_median_deg"]
            L.append(f"| median normal error ≤ the best peer's, {title} | {fmt(h['sg_err'], 2)}° "
                     f"vs {fmt(be, 2)}° | {'yes' if h['sg_err'] <= be else 'no'} |")
    sc = scaling_rows(results)
    if sc:
        per = [r["ns_per_point"] for r in sc if r.get("ns_per_point")]
        if per:
            mean = sum(per) / len(per)
            spread = max(abs(p / mean - 1) for p in per) * 100
            L.append(f"| time per point within ±30 % from {sc[0]['n']:,} to {sc[-1]['n']:,} points "
                     f"| {min(per):.0f}–{max(per):.0f} ns/point (±{spread:.0f} % of the mean) | "
                     f"{'yes' if spread <= 30 else 'no'} |")
            cper = [r["cpu_ns_per_point"] for r in sc if r.get("cpu_ns_per_point")]
            if cper:
                cm = sum(cper) / len(cper)
                cs = max(abs(p / cm - 1) for p in cper) * 100
                L.append(f"| the same in CPU time (less sensitive to load) | {min(cper):.0f}–"
                         f"{max(cper):.0f} CPU ns/point (±{cs:.0f} %) | {'yes' if cs <= 30 else 'no'} |")
        bpp = [r["bytes_beyond_outputs"] for r in sc if r.get("bytes_beyond_outputs") is not None]
        if bpp:
            L.append(f"| peak memory < 64 B/point plus the outputs | {max(bpp):.0f} B/point at most "
                     f"| {'yes' if max(bpp) < 64 else 'no'} |")
    for name, row in results.get("threads", {}).items():
        t1, tn = thread_seconds(row, 1), thread_seconds(row, mi["cores"])
        if t1 and tn:
            s = t1 / tn
            L.append(f"| {mi['cores']} threads ≥ 1.7× one, byte-identical ({name}) | {s:.2f}×, "
                     f"{'identical' if row['identical'] else 'DIFFERENT'} | "
                     f"{'yes' if s >= 1.7 and row['identical'] else 'no'} |")
    for target, measured, met in whole_targets(whole_rows(results), whole_process.THREADS[-1]):
        L.append(f"| {target} | {measured} | {'yes' if met else 'no'} |")
    io = results.get("io", {})
    if io:
        lo = min(io.get("ply_binary_le_float", 0), io.get("pcd_binary", 0))
        L.append(f"| binary PLY/PCD read ≥ 300 MB/s from page cache | PLY "
                 f"{io.get('ply_binary_le_float', 0):.0f} MB/s, PCD {io.get('pcd_binary', 0):.0f} "
                 f"MB/s | {'yes' if lo >= 300 else 'no'} |")
    L.append("")
    L += whole_section(results, whole_process.THREADS[-1])

    # Per cloud.
    L.append("## Per cloud")
    L.append("")
    L.append("Algorithm seconds: the median of the runs a tool made (it repeats while under "
             f"{a.min_seconds} s, at most {a.max_repeats} times); I/O: reading the file with the "
             "tool's own reader. CPU s: user + system seconds of the algorithm, all threads "
             "(a loaded machine stretches wall time, much less CPU time). Peak RSS: the "
             "process's resident high-water mark, VmHWM (where a run predates that report: the "
             "algorithm phase's, which holds the loaded input). Segments: segments with at "
             "least one point. Residual: mean |distance| of registered points to their segment's "
             "plane. Normal error: per registered point on a true face, the angle between its "
             "segment's normal and the true normal (as lines). GT planes: planar faces holding "
             "≥ 0.1 % of the points; recovered: some segment has ≥ 50 % of its points on it and a "
             "normal within 30°. Purity: registered points on their segment's majority face. "
             "Largest segment: the median over GT planes of the share of the plane's points in "
             "its largest segment (100 % for a plane found whole; patch-based surfgrow is low "
             "here by design).")
    L.append("")
    seen = list(results.get("clouds", {}))
    for r in results["runs"].values():
        if r["cloud_file"] not in seen:
            seen.append(r["cloud_file"])
    cinfo = results.get("clouds", {})
    seen.sort(key=lambda cf: (cinfo.get(cf, {}).get("kind") == "real",
                              cinfo.get(cf, {}).get("points", 0) if
                              cinfo.get(cf, {}).get("kind") != "real" else 0))
    for cf in seen:
        runs = [r for r in results["runs"].values() if r["cloud_file"] == cf]
        if not runs:
            L.append(f"### {cinfo.get(cf, {}).get('name', cf)}")
            L.append("")
            L.append(f"{cinfo.get(cf, {}).get('points', 0):,} points. Not run: the run that wrote "
                     "this report ended before this cloud's turn.")
            L.append("")
            continue
        done = {(r["tool"], r["method"]) for r in runs}
        runs += [{"tool": t, "method": m, "status": "not run (the run ended first)",
                  "load1": float("nan")} for t, m in TOOLS if (t, m) not in done]
        c0 = runs[0]
        truth = any("normal_err_median_deg" in r.get("metrics", {}) for r in runs)
        meta = results["clouds"].get(cf, {})
        L.append(f"### {c0['cloud']}")
        L.append("")
        p = c0["params"]
        L.append(f"{meta.get('points', 0):,} points; μ = {p['mu'] * 1000:g} mm "
                 f"(k = {p['k']}: the median number of points within μ), tolerance "
                 f"{p['tol'] * 1000:g} mm, min points {p['min_pts']}, RANSAC min plane "
                 f"{p['min_plane']} points.")
        L.append("")
        if truth:
            L.append("| tool | algorithm s | CPU s | I/O s | peak RSS MB | segments | registered % | "
                     "normal err median ° | p95 ° | GT planes recovered | purity % | "
                     "largest segment % | residual mm | load |")
            L.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        else:
            L.append("| tool | algorithm s | CPU s | I/O s | peak RSS MB | segments | registered % | "
                     "residual mean mm | residual p95 mm | load |")
            L.append("|---|---|---|---|---|---|---|---|---|---|")
        for r in runs:
            name = label_of(r["tool"], r["method"])
            if r["status"] != "ok" or "metrics" not in r:
                what = r["status"]
                if what in ("timeout", "out of memory"):
                    what += (f" (> {r['timeout_s']} s)" if what == "timeout"
                             else f" (> {a.mem_limit_gb} GB)")
                ncol = 14 if truth else 10
                L.append(f"| {name} | {what} |" + " – |" * (ncol - 3) + f" {fmt(r['load1'], 1)} |")
                continue
            rep, m = r["report"], r["metrics"]
            cells = [name, fmt_s(rep["algorithm_seconds_median"]),
                     fmt_s(rep.get("algorithm_cpu_seconds_median")), fmt_s(rep["io_seconds"]),
                     fmt(peak_of(r) / 2**20, 0), f"{m['segments']:,}",
                     fmt(m["registered_pct"])]
            if truth:
                cells += [fmt(m.get("normal_err_median_deg"), 2),
                          fmt(m.get("normal_err_p95_deg"), 1),
                          f"{m.get('gt_recovered', 0)} / {m.get('gt_planes', 0)}",
                          fmt(m.get("purity_pct")), fmt(m.get("largest_segment_share_median_pct")),
                          fmt(m.get("residual_mean_mm"), 2)]
            else:
                cells += [fmt(m.get("residual_mean_mm"), 2), fmt(m.get("residual_p95_mm"), 2)]
            cells.append(fmt(r["load1"], 1))
            L.append("| " + " | ".join(cells) + " |")
        L.append("")

    # Scaling.
    if sc:
        L.append("## Scaling (surfgrow alone)")
        L.append("")
        L.append("Crops of the largest simulated cloud around the channel's middle (same density "
                 "and structure at every size), all threads. Memory: VmHWM during the algorithm "
                 "(reset just before it) less the process's RSS before reading the input, so it "
                 "counts the input cloud (12 B/point), the index, the working memory and the "
                 "outputs; 'beyond outputs' subtracts the labels and surfaces returned.")
        L.append("")
        L.append("| points | algorithm s | ns / point | vs mean | CPU ns / point | vs mean | "
                 "peak B / point | beyond outputs B / point | surfaces | load |")
        L.append("|---|---|---|---|---|---|---|---|---|---|")
        cper = [r["cpu_ns_per_point"] for r in sc if r.get("cpu_ns_per_point")]
        cmean = sum(cper) / len(cper) if cper else 1
        per = [r["ns_per_point"] for r in sc if r.get("ns_per_point")]
        mean = sum(per) / len(per) if per else 1
        for r in sc:
            if r.get("status") != "ok":
                L.append(f"| {r['n']:,} | {r['status']} | – | – | – | – | – | – | – | "
                         f"{fmt(r['load1'], 1)} |")
                continue
            c = r.get("cpu_ns_per_point")
            L.append(f"| {r['n']:,} | {fmt_s(r['seconds'])} | {r['ns_per_point']:.1f} | "
                     f"{100 * (r['ns_per_point'] / mean - 1):+.0f} % | {fmt(c, 1)} | "
                     + (f"{100 * (c / cmean - 1):+.0f} %" if c else "–") + " | "
                     f"{fmt(r['bytes_per_point'], 1)} | "
                     f"{fmt(r['bytes_beyond_outputs'], 1)} | {r['surfaces']:,} | {fmt(r['load1'], 1)} |")
        L.append("")
    if results.get("threads"):
        L.append("## Threads (surfgrow)")
        L.append("")
        L.append(f"{THREAD_ROUNDS} rounds of alternating processes (1 thread, {mi['cores']}, 1, "
                 f"...), each repeating at least 5 times; seconds: the median over every repeat "
                 "of every round; outputs: every run's labels and planes against the first run's.")
        L.append("")
        L.append("| cloud | 1 thread s | " + f"{mi['cores']} threads s | speed-up | outputs |")
        L.append("|---|---|---|---|---|")
        for name, row in results["threads"].items():
            t1, tn = thread_seconds(row, 1), thread_seconds(row, mi["cores"])
            if not (t1 and tn):
                continue
            L.append(f"| {name} | {fmt_s(t1)} | {fmt_s(tn)} | {t1 / tn:.2f}× | "
                     f"{'byte-identical labels and planes' if row['identical'] else 'DIFFERENT'} |")
        L.append("")
    if io:
        L.append("## Reading speed (surfgrow, 1 M points from the page cache, `bench_io`)")
        L.append("")
        L.append("| format | MB/s |")
        L.append("|---|---|")
        for k, v in io.items():
            L.append(f"| {k} | {v:.0f} |")
        L.append("")
    Path(path).write_text("\n".join(L) + "\n")


def update_readme(results, readme):
    """Rewrites the headline between the peers markers in README.md (full runs only)."""
    begin, end = "<!-- peers-headline -->", "<!-- /peers-headline -->"
    text = readme.read_text()
    if begin not in text or end not in text:
        return
    lines = []
    for (cf, title), method in [(c, m) for c in HEADLINE_CLOUDS for m in SG_METHODS]:
        h = headline(results, cf, method)
        if not h:
            continue
        be = h["best_err"]["metrics"]["normal_err_median_deg"] if h["best_err"] else None
        lines.append(f"| {title} | {method} | {fmt_s(h['surfgrow_s'])} s | "
                     f"{label_of(h['fastest']['tool'], h['fastest']['method'])} "
                     f"{fmt_s(h['fastest_s'])} s | **{h['ratio']:.0f}×** ({h['cpu_ratio']:.0f}× CPU) | "
                     f"{fmt(h['sg_reg'])} % vs {fmt(h['best_reg']['metrics']['registered_pct'])} % | "
                     f"{fmt(h['sg_err'], 2)}° vs {fmt(be, 2)}° |")
    la = results.get("load", {})
    body = ["", f"Measured by `{results['command']}` on {results['machine']['cpu']} "
            f"({results['machine']['cores']} cores), load average {fmt(median_runs_load(results), 1)} "
            f"(median over the runs; a run's own threads count in it); details and every table in "
            f"[BENCHMARK.md](BENCHMARK.md).", "",
            "| cloud | surfgrow | its time | fastest peer | speed-up | registered (best peer) | "
            "median normal error (best peer) |", "|---|---|---|---|---|---|---|"] + lines + [""]
    head, rest = text.split(begin, 1)
    tail = rest.split(end, 1)[1]
    text = head + begin + "\n".join(body) + end + tail
    # The whole process against the peers (issue 14), between its own markers.
    begin, end = "<!-- whole-process -->", "<!-- /whole-process -->"
    rows = whole_rows(results)
    if rows and begin in text and end in text:
        body = ["", f"| cloud | whole process, {whole_process.THREADS[-1]} threads | "
                "fastest peer, algorithm alone | ratio | outputs / input |", "|---|---|---|---|---|"]
        for r in rows:
            peer = (f"{label_of(r['peer']['tool'], r['peer']['method'])} {fmt_s(r['peer_s'])} s"
                    if "peer" in r else "–")
            body.append(f"| {r['title']} | {fmt_s(r['wall'])} s | {peer} | "
                        + (f"**{r['ratio']:.1f}×**" if "ratio" in r else "–")
                        + f" | {r['size_ratio']:.2f}× |")
        head, rest = text.split(begin, 1)
        text = head + begin + "\n".join(body + [""]) + end + rest.split(end, 1)[1]
    readme.write_text(text)


def scaling_rows(results):
    rows = []
    for name, r in results.get("scaling", {}).items():
        rep = r.get("report")
        n = rep["points"] if rep else r["n"]
        row = {"name": name, "n": int(n), "status": r["status"], "load1": r["load1"]}
        if rep:
            s = rep["algorithm_seconds_median"]
            row["seconds"] = s
            row["ns_per_point"] = 1e9 * s / n
            cpu = rep.get("algorithm_cpu_seconds_median")
            row["cpu_ns_per_point"] = 1e9 * cpu / n if cpu else None
            row["surfaces"] = rep["segments"]
            if rep.get("algorithm_peak_rss_bytes"):
                used = rep["algorithm_peak_rss_bytes"] - rep["baseline_rss_bytes"]
                row["bytes_per_point"] = used / n
                outb = float(rep.get("notes", {}).get("outputs_bytes", 0))
                row["bytes_beyond_outputs"] = (used - outb) / n
        rows.append(row)
    return sorted(rows, key=lambda r: r["n"])


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="smoke run: single scan, one real scan")
    ap.add_argument("--build", default=str(ROOT / "build-peers"))
    ap.add_argument("--work", default=None, help="clouds and run outputs (default BUILD/peers-work)")
    ap.add_argument("--report", default=None, help="BENCHMARK.md path (quick: WORK/BENCHMARK.md)")
    ap.add_argument("--only", default="", help="comma-separated tools (surfgrow,pcl,cgal,open3d)")
    ap.add_argument("--timeout", type=float, default=None, help="seconds per peer run")
    ap.add_argument("--timeout-surfgrow", type=float, default=300)
    ap.add_argument("--mem-limit-gb", type=float, default=10.0)
    ap.add_argument("--min-seconds", type=float, default=1.0)
    ap.add_argument("--max-repeats", type=int, default=5)
    ap.add_argument("--rerun", action="store_true",
                    help="redo runs already in WORK (with --only, only those tools' runs)")
    ap.add_argument("--report-only", action="store_true", help="rewrite the report from WORK")
    ap.add_argument("--command", default=None, help="the command line to print in the report")
    a = ap.parse_args()
    if a.timeout is None:
        a.timeout = 120.0 if a.quick else 900.0
    build = Path(a.build).resolve()
    work = Path(a.work).resolve() if a.work else build / ("peers-work-quick" if a.quick
                                                         else "peers-work")
    work.mkdir(parents=True, exist_ok=True)
    report = Path(a.report) if a.report else (work / "BENCHMARK.md" if a.quick
                                              else ROOT / "BENCHMARK.md")
    rfile = work / "results.json"
    # --rerun redoes the runs it selects: all of them, or with --only those tools' alone (the other
    # tools' results are kept, so the report still compares against them).
    fresh = a.rerun and not a.only
    results = json.loads(rfile.read_text()) if rfile.exists() and not fresh else {}
    results.setdefault("runs", {})
    results["machine"] = machine()
    if not a.report_only or "command" not in results:
        results["command"] = a.command or shlex.join(["bench/peers/run_peers.sh"] + sys.argv[1:])
    mem_limit = a.mem_limit_gb * 1e9
    if not a.report_only:
        results["started"] = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
        results["load"] = {"start": os.getloadavg()[0]}
        results["limits"] = {"peer_s": a.timeout, "surfgrow_s": a.timeout_surfgrow,
                             "mem_gb": a.mem_limit_gb}
        log("clouds:")
        clouds = make_clouds(a, build, work)
        results["clouds"] = {Path(c["path"]).stem: c["meta"] | {"faces": len(c["meta"].get(
            "faces", [])), "name": c["name"]} for c in clouds}
        # The 10 M-point cloud's peers last: they are the slowest runs and may hit the limits.
        small = [c for c in clouds if c["meta"]["points"] < 5_000_000]
        large = [c for c in clouds if c["meta"]["points"] >= 5_000_000]
        log("tools:")
        run_tools(a, build, work, small, mem_limit, results)
        log("scaling, threads, reading:")
        run_scaling(a, build, work, clouds, mem_limit, results)
        log("the whole process:")
        run_whole(a, build, work, results)
        log("tools on the largest clouds:")
        run_tools(a, build, work, large, mem_limit, results)
        results["load"]["end"] = os.getloadavg()[0]
        results["finished"] = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
        save(results, work)
    write_report(a, results, report)
    if not a.quick and not a.report:
        update_readme(results, ROOT / "README.md")
    log(f"report: {report}")


if __name__ == "__main__":
    main()
