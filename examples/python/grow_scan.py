#!/usr/bin/env python3
"""Grows a cloud as `surfgrow grow` does and shows what came out.

    grow_scan.py [CLOUD] [--mu 0.012] [--seed 1] [--threads 0] [--plot out.png] [--no-view]

CLOUD: a PLY, PCD or text file (metres); without it, a simulated scan of the I-beam channel from
one pose. Prints the CLI's summary line, the bound planes and the coverage goals; plots the
registered share by range band to a PNG; opens the surfaces in Open3D's viewer (home points with
their normals, coloured by bound plane) when a display is present and --no-view is not given.
"""

import argparse
import os
import sys

import numpy as np

import surfgrow


def summary_line(r):
    """The CLI's line: points in, surfaces, registered %, reduction, algorithm seconds."""
    s = r.summary
    line = (f"{s['points_in']} points -> {s['surfaces']} surfaces, "
            f"{100 * s['registered_fraction']:.1f}% registered, "
            f"{s['data_reduction']:.1f}x reduction, {s['seconds']['total']:.3f} s")
    if s["invalid_points"] or s["cropped_points"]:
        line += f" ({s['invalid_points']} invalid, {s['cropped_points']} outside the workspace)"
    return line


def plot_range_bands(r, path, title):
    """Bar chart of the registered share per range band (from the cloud's range origin)."""
    import matplotlib
    matplotlib.use("Agg")  # a file only: no window, so no display is needed
    import matplotlib.pyplot as plt

    bands = [b for b in r.summary["range_bands"] if b["points"] > 0]
    labels = [f"{b['from']:g}–{b['to']:g}" for b in bands]
    share = [100 * b["registered_fraction"] for b in bands]
    fig, ax = plt.subplots(figsize=(6, 3.5), dpi=120)
    bars = ax.bar(labels, share, color="#4878a8")
    for bar, b in zip(bars, bands):
        ax.annotate(f"{b['points']:,} pts", (bar.get_x() + bar.get_width() / 2, bar.get_height()),
                    ha="center", va="bottom", fontsize=8)
    low = min(share, default=100.0)
    ax.set_ylim(max(0.0, low - 5.0), 100.5)
    ax.set_xlabel("range from the sensor [cloud units]")
    ax.set_ylabel("registered [%]")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def view(r, planes):
    """Open3D's viewer: one point per surface at its home, with its normal, coloured by plane."""
    import open3d as o3d

    pcd = o3d.geometry.PointCloud()
    pcd.points = o3d.utility.Vector3dVector(r.homes)
    pcd.normals = o3d.utility.Vector3dVector(r.normals)
    face = planes.plane_of_surface
    rng = np.random.default_rng(7)
    palette = rng.uniform(0.15, 0.95, size=(max(len(planes), 1), 3))
    colours = np.where(face[:, None] >= 0, palette[np.maximum(face, 0)], 0.6)
    pcd.colors = o3d.utility.Vector3dVector(colours)
    o3d.visualization.draw_geometries([pcd], window_name="surfgrow: surfaces by bound plane",
                                      point_show_normal=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cloud", nargs="?", help="PLY, PCD or text cloud (default: a simulated scan)")
    ap.add_argument("--mu", type=float, default=0.012, help="cube side, cloud units (0.012: 12 mm)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=0, help="0: one per core")
    ap.add_argument("--plot", default="registration_by_range.png", help="PNG to write")
    ap.add_argument("--no-view", action="store_true", help="do not open the 3D viewer")
    args = ap.parse_args()

    try:
        if args.cloud:
            cloud, name = surfgrow.read_cloud(args.cloud), args.cloud
        else:
            cloud, name = surfgrow.simulate("ibeam-channel", poses=1).cloud, "ibeam-channel, 1 pose"
        r = surfgrow.grow(cloud, mu=args.mu, seed=args.seed, threads=args.threads)
    except surfgrow.Error as e:
        print(f"grow_scan: {e}", file=sys.stderr)
        return e.code
    print(summary_line(r))

    planes = surfgrow.bound_planes(r)
    faces = planes.stats
    print(f"{len(planes)} bound planes: {faces['area']:.2f} units^2, "
          f"{faces['points']} points, {faces['degenerate']} degenerate")
    for k in range(min(len(planes), 5)):
        n, a = planes.normals[k], planes.areas[k]
        print(f"  plane {k}: normal ({n[0]:+.3f}, {n[1]:+.3f}, {n[2]:+.3f}), area {a:.3f}")
    plan = surfgrow.coverage(planes)
    c = plan.stats
    print(f"{len(plan)} coverage goals on {c['planes']} planes: {100 * c['coverage']:.1f}% covered, "
          f"tool path {c['tool_path_length']:.1f} units, {c['transitions']} transitions")

    plot_range_bands(r, args.plot, f"{name}\n{summary_line(r)}")
    print(f"wrote {args.plot}")

    if not args.no_view and (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        view(r, planes)
    return 0


if __name__ == "__main__":
    sys.exit(main())
