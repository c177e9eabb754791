#!/usr/bin/python3
"""Open3D 0.16 (Debian python3-open3d) in the peers' harness.

    /usr/bin/python3 peer_open3d.py CLOUD --out DIR [--k 20] [--mu 0.012] [--tol 0.012]
        [--min-pts 10] [--min-plane 0] [--max-planes 200] [--iterations 1000]
        [--min-seconds 1] [--max-repeats 5]

I/O = o3d.io.read_point_cloud. Algorithm = iterative segment_plane (RANSAC, ransac_n = 3,
distance_threshold = tol, at most --iterations hypotheses, stopping early at --probability 0.99
as PCL does; Open3D's default 0.99999999 never stops early) on the points not yet taken, while a plane has at least --min-plane
inliers (0: max(min-pts, N/1000)) and fewer than --max-planes were found; the plane is the
returned model. estimate_normals (hybrid search: radius mu, at most k) runs first, as in the
usual recipe, and is timed as its own stage but NOT counted in the algorithm time: segment_plane
does not use normals, and counting them would slow Open3D down for nothing. Open3D uses all
cores (OpenMP) for both.
"""
import argparse
import json
import os
import resource
import sys
import time

import numpy as np
import open3d as o3d


def status_bytes(field):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return float(line.split()[1]) * 1024.0
    return 0.0


HWM_BEFORE_RESET = [0.0]


def reset_peak():
    HWM_BEFORE_RESET[0] = status_bytes("VmHWM")
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


def segment(pcd, a, n):
    stages = {}
    t, c = time.perf_counter(), time.process_time()
    pcd.estimate_normals(o3d.geometry.KDTreeSearchParamHybrid(radius=a.mu, max_nn=a.k))
    stages["normals_not_counted"] = time.perf_counter() - t
    stages["normals_cpu_not_counted"] = time.process_time() - c

    t = time.perf_counter()
    min_plane = a.min_plane or max(a.min_pts, n // 1000)
    labels = np.full(n, -1, dtype=np.int32)
    planes = []
    rest = pcd
    rest_ids = np.arange(n)  # original index of each point of `rest`
    while len(rest_ids) >= min_plane and len(planes) < a.max_planes:
        model, inliers = rest.segment_plane(distance_threshold=a.tol, ransac_n=3,
                                            num_iterations=a.iterations,
                                            probability=a.probability)
        if len(inliers) < min_plane:
            break
        m = np.asarray(model, dtype=np.float64)
        m /= np.linalg.norm(m[:3])
        labels[rest_ids[np.asarray(inliers)]] = len(planes)
        planes.append(m)
        keep = np.ones(len(rest_ids), dtype=bool)
        keep[np.asarray(inliers)] = False
        rest = rest.select_by_index(inliers, invert=True)
        rest_ids = rest_ids[keep]
    stages["ransac"] = time.perf_counter() - t
    return labels, np.array(planes, dtype=np.float64).reshape(-1, 4), stages


def main():
    p = argparse.ArgumentParser()
    p.add_argument("cloud")
    p.add_argument("--out", default=".")
    p.add_argument("--method", default="ransac")
    p.add_argument("--k", type=int, default=20)
    p.add_argument("--mu", type=float, default=0.012)
    p.add_argument("--tol", type=float, default=0.012)
    p.add_argument("--min-pts", type=int, default=10)
    p.add_argument("--min-plane", type=int, default=0)
    p.add_argument("--max-planes", type=int, default=200)
    p.add_argument("--iterations", type=int, default=1000)
    p.add_argument("--probability", type=float, default=0.99)
    p.add_argument("--min-seconds", type=float, default=1.0)
    p.add_argument("--max-repeats", type=int, default=5)
    a = p.parse_args()

    baseline = status_bytes("VmRSS")
    t0 = time.perf_counter()
    pcd = o3d.io.read_point_cloud(a.cloud)
    io_s = time.perf_counter() - t0
    n = len(pcd.points)
    if n == 0:
        sys.exit("peer_open3d: cannot read " + a.cloud)
    input_rss = status_bytes("VmRSS")

    peak_valid = reset_peak()
    times, cpu, result, algo_peak = [], [], None, None
    while True:
        work = o3d.geometry.PointCloud(pcd)  # normals are added in place: start clean each run
        t, c = time.perf_counter(), time.process_time()
        r = segment(work, a, n)
        times.append(time.perf_counter() - t - r[2]["normals_not_counted"])
        cpu.append(time.process_time() - c - r[2]["normals_cpu_not_counted"])
        if result is None:
            result = r
            algo_peak = status_bytes("VmHWM")
        del work
        if sum(times) >= a.min_seconds or len(times) >= a.max_repeats:
            break
    labels, planes, stages = result
    labels.astype("<i4").tofile(os.path.join(a.out, "labels.i32"))
    planes.astype("<f8").tofile(os.path.join(a.out, "planes.f64"))
    rep = {
        "tool": "open3d", "method": "ransac", "input": a.cloud, "points": n,
        "threads": os.cpu_count(), "segments": len(planes), "io_seconds": io_s,
        "algorithm_seconds": times, "algorithm_seconds_median": float(np.median(times)),
        "algorithm_cpu_seconds": cpu, "algorithm_cpu_seconds_median": float(np.median(cpu)),
        "stage_seconds": stages,
        # VmHWM, not ru_maxrss: that one also counts the spawning driver's pre-exec memory.
        "process_peak_rss_bytes": max(HWM_BEFORE_RESET[0], status_bytes("VmHWM")),
        "ru_maxrss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024.0,
        "baseline_rss_bytes": baseline, "input_rss_bytes": input_rss,
        "algorithm_peak_rss_bytes": algo_peak if peak_valid else None,
        "params": {"k": a.k, "mu": a.mu, "tol": a.tol, "min-pts": a.min_pts,
                   "min-plane": a.min_plane or max(a.min_pts, n // 1000),
                   "max-planes": a.max_planes, "iterations": a.iterations,
                   "probability": a.probability},
        "notes": {"open3d_version": o3d.__version__},
    }
    with open(os.path.join(a.out, "result.json"), "w") as f:
        json.dump(rep, f, indent=2)
    print(f"open3d ransac: {n} points -> {len(planes)} segments in {np.median(times):.3f} s")


if __name__ == "__main__":
    main()
