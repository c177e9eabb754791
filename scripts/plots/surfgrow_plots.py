#!/usr/bin/python3
"""Plots of `surfgrow sweep` and `surfgrow study` (paper Figs. 5, 7 and 8) from their CSV files.

    surfgrow_plots.py sweep DIR [--title TEXT]   DIR/mu.csv -> DIR/mu.png, DIR/min_pts.csv -> DIR/min_pts.png
    surfgrow_plots.py study DIR [--title TEXT]   DIR/study.csv -> DIR/scaling.png, DIR/stages.png

surfgrow runs this with /usr/bin/python3 (Debian's python3-matplotlib) on a temporary folder and
publishes the pictures with the CSV files; it can also be run by hand on a sweep or study folder to
draw the plots again. Every picture is 1600x1200 pixels (stages.png: 1600x900). Headless: the Agg
backend, no display needed.

Exit status: 0 drawn, 2 usage, 3 matplotlib cannot be imported, 4 a CSV file is missing or empty.
"""

import argparse
import csv
import math
import os
import sys

DPI = 100


def die(code, message):
    print(f"surfgrow_plots: {message}", file=sys.stderr)
    sys.exit(code)


def load_matplotlib():
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except Exception as e:  # ImportError, or a broken installation
        die(3, f"matplotlib cannot be imported ({type(e).__name__}: {e}); "
               "install Debian's python3-matplotlib")
    # Plain styling whatever the user's matplotlibrc says.
    plt.style.use("default")
    matplotlib.rcParams.update({"font.size": 13, "axes.grid": True, "grid.alpha": 0.3})
    return plt


def read_csv(path):
    """The rows of a CSV file as dicts of floats (an empty field is NaN)."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        die(4, f"{path}: no rows")
    out = []
    for row in rows:
        out.append({k: (float(v) if v not in ("", None) else math.nan) for k, v in row.items()})
    return out


def column(rows, name):
    return [r.get(name, math.nan) for r in rows]


def has_values(rows, name):
    return name in rows[0] and any(not math.isnan(v) for v in column(rows, name))


STAGES = [("index_s", "index", "#8da0cb"), ("grow_s", "grow", "#66c2a5"),
          ("attach_s", "attach", "#fc8d62"), ("finish_s", "finish", "#e78ac3")]


def points_label(v, _=None):
    """A point count as people write it: 500, 20k, 1.5M."""
    if v >= 1e6:
        return f"{v / 1e6:g}M"
    if v >= 1e3:
        return f"{v / 1e3:g}k"
    return f"{v:g}"


def save(fig, path):
    # No bbox_inches="tight": the picture keeps exactly figsize * DPI pixels.
    fig.savefig(path, dpi=DPI, metadata={"Software": None})


# ---------------------------------------------------------------------------------------------
# sweep: paper Fig. 5


def plot_sweep(plt, rows, param, path, title):
    if param == "mu":
        x = [v * 1000.0 for v in column(rows, "mu_m")]
        xlabel = "μ (mm)"
        fixed = f"min_pts = {int(rows[0]['min_pts'])}"
    else:
        x = column(rows, "min_pts")
        xlabel = "min_pts"
        fixed = f"μ = {rows[0]['mu_m'] * 1000.0:g} mm"
    truth = has_values(rows, "normal_err_median_deg")

    fig, axes = plt.subplots(2, 2, figsize=(16, 12), layout="constrained")
    (a, b), (c, d) = axes
    fig.suptitle(f"{title}\nagainst {xlabel}, {fixed}", fontsize=15)

    # (a) time: the stages stacked, the total as dots (the paper's "• time").
    stack = [column(rows, key) for key, _, _ in STAGES]
    a.stackplot(x, stack, labels=[label for _, label, _ in STAGES],
                colors=[colour for _, _, colour in STAGES], alpha=0.75)
    a.plot(x, column(rows, "seconds"), "ko", label="total (algorithm)")
    a.set_ylabel("time (s)")
    a.set_title("(a) time")
    a.legend(loc="best", fontsize=11, framealpha=0.9)

    b.plot(x, column(rows, "surfaces"), "o-", color="#1f77b4")
    b.set_ylabel("surfaces")
    b.set_title("(b) number of surfaces")
    b.set_ylim(bottom=0)

    c.plot(x, column(rows, "registered_pct"), "o-", color="#2ca02c", label="after leftover pass")
    if has_values(rows, "registered_grown_pct"):
        c.plot(x, column(rows, "registered_grown_pct"), "s--", color="#98df8a",
               label="by growing alone (paper)")
    c.set_ylabel("points registered (%)")
    c.set_title("(c) points registered")
    c.set_ylim(0, 102)
    c.legend(loc="lower right", fontsize=11)

    if truth:
        d.plot(x, column(rows, "normal_err_median_deg"), "o-", color="#d62728", label="median")
        d.plot(x, column(rows, "normal_err_p95_deg"), "^--", color="#ff9896",
               label="95th percentile")
        d.set_ylabel("normal error (degrees)")
        d.set_title("(d) normal error against ground truth")
        errors = [v for v in column(rows, "normal_err_median_deg") + column(rows, "normal_err_p95_deg")
                  if not math.isnan(v)]
        if errors and min(errors) > 0 and max(errors) / min(errors) > 20:
            # Errors from tenths of a degree to 90: a log scale keeps the small ones readable.
            d.set_yscale("log")
            d.yaxis.set_major_formatter(plt.FuncFormatter(lambda v, _: f"{v:g}"))
        else:
            d.set_ylim(bottom=0)
        d.legend(loc="upper right", fontsize=11)
    else:
        d.plot(x, column(rows, "reduction"), "o-", color="#9467bd")
        d.set_ylabel("points per surface")
        d.set_title("(d) data reduction (no ground truth: no normal error)")
        d.set_ylim(bottom=0)

    for ax in (a, b, c, d):
        ax.set_xlabel(xlabel)
        if param == "mu" and len(x) > 1 and max(x) / min(x) >= 8:
            ax.set_xscale("log")
            ax.xaxis.set_major_formatter(plt.FuncFormatter(lambda v, _: f"{v:g}"))
    save(fig, path)
    plt.close(fig)


def run_sweep(plt, folder, title):
    drawn = 0
    for param in ("mu", "min_pts"):
        rows = read_csv(os.path.join(folder, f"{param}.csv"))
        if rows is None:
            continue
        plot_sweep(plt, rows, param, os.path.join(folder, f"{param}.png"), title)
        drawn += 1
    if drawn == 0:
        die(4, f"{folder}: neither mu.csv nor min_pts.csv")


# ---------------------------------------------------------------------------------------------
# study: paper Figs. 8 (scaling) and 7 (time per stage)


def linear_fit(x, y):
    n = len(x)
    if n < 2:
        return None
    mx, my = sum(x) / n, sum(y) / n
    sxx = sum((v - mx) ** 2 for v in x)
    if sxx == 0:
        return None
    slope = sum((u - mx) * (v - my) for u, v in zip(x, y)) / sxx
    return slope, my - slope * mx


def plot_scaling(plt, rows, path, title):
    pts = column(rows, "points")
    secs = column(rows, "seconds")
    surf = column(rows, "surfaces")
    red = column(rows, "reduction")
    reg = column(rows, "registered_pct")

    fig, axes = plt.subplots(2, 2, figsize=(16, 12), layout="constrained")
    (a, b), (c, d) = axes
    fig.suptitle(f"{title}\nresults for increasing number of points ({len(rows)} tests)",
                 fontsize=15)

    a.plot(pts, secs, "o", color="0.55", markersize=8, label="tests")
    fit = linear_fit(pts, secs)
    if fit:
        slope, icpt = fit
        xs = [min(pts), max(pts)]
        a.plot(xs, [icpt + slope * v for v in xs], "k-",
               label=f"trend: {slope * 1e6:.3g} µs/point {'+' if icpt >= 0 else '−'} "
                     f"{abs(icpt) * 1e3:.3g} ms")
    a.set_xlabel("points")
    a.set_ylabel("time (s)")
    a.set_title("(a) overall algorithm time")
    a.legend(loc="upper left", fontsize=11)

    b.plot(pts, surf, "o", color="#1f77b4", markersize=8)
    b.set_xlabel("points")
    b.set_ylabel("surfaces")
    b.set_title("(b) number of surfaces")
    b.set_ylim(bottom=0)

    tests = list(range(1, len(rows) + 1))
    c.semilogy(tests, pts, "r*", markersize=12, label="original (points)")
    c.semilogy(tests, surf, "bo", markersize=8, fillstyle="none", label="post processing (surfaces)")
    c.set_xlabel("test")
    c.set_ylabel("values describing the surface")
    c.set_title("(c) data reduction")
    c.legend(loc="upper left", fontsize=11)

    d.plot(pts, red, "o-", color="#9467bd", label="points per surface")
    d.set_xlabel("points")
    d.set_ylabel("reduction (points per surface)")
    d.set_ylim(bottom=0)
    d2 = d.twinx()
    d2.plot(pts, reg, "s--", color="#2ca02c", label="registered %")
    d2.set_ylabel("points registered (%)")
    d2.set_ylim(0, 102)
    d2.grid(False)
    d.set_title("(d) reduction and registration")
    lines = d.get_lines() + d2.get_lines()
    d.legend(lines, [ln.get_label() for ln in lines], loc="lower right", fontsize=11)

    for ax in (a, b, d):
        ax.set_xlim(left=0)
        ax.xaxis.set_major_formatter(plt.FuncFormatter(points_label))
    save(fig, path)
    plt.close(fig)


def plot_stages(plt, rows, path, title):
    fig, (a, b) = plt.subplots(1, 2, figsize=(16, 9), width_ratios=[2.2, 1], layout="constrained")
    fig.suptitle(f"{title}\ntime per stage", fontsize=15)
    labels = [points_label(p) for p in column(rows, "points")]
    xs = list(range(len(rows)))
    bottom = [0.0] * len(rows)
    for key, label, colour in STAGES:
        vals = column(rows, key)
        a.bar(xs, vals, bottom=bottom, color=colour, label=label, width=0.7)
        bottom = [u + v for u, v in zip(bottom, vals)]
    a.set_xticks(xs, labels, rotation=45 if len(rows) > 10 else 0)
    a.set_xlabel("points in the test")
    a.set_ylabel("time (s)")
    a.set_title("(a) per test")
    a.legend(loc="upper left", fontsize=11)

    # Fig. 7: the overall breakdown, each test's stage shares averaged over the tests.
    shares = []
    for key, _, _ in STAGES:
        s = [r[key] / r["seconds"] for r in rows if r["seconds"] > 0]
        shares.append(sum(s) / len(s) if s else 0.0)
    if sum(shares) > 0:
        b.pie(shares, labels=[label for _, label, _ in STAGES],
              colors=[colour for _, _, colour in STAGES], autopct="%1.1f%%", startangle=90,
              counterclock=False, wedgeprops={"edgecolor": "white"})
    b.set_title("(b) overall breakdown:\neach stage's share, averaged over the tests")
    save(fig, path)
    plt.close(fig)


def run_study(plt, folder, title):
    rows = read_csv(os.path.join(folder, "study.csv"))
    if rows is None:
        die(4, f"{folder}: no study.csv")
    plot_scaling(plt, rows, os.path.join(folder, "scaling.png"), title)
    plot_stages(plt, rows, os.path.join(folder, "stages.png"), title)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("kind", choices=["sweep", "study"])
    parser.add_argument("folder", help="a sweep or study folder holding the CSV files")
    parser.add_argument("--title", default=None, help="first line of every picture's title")
    args = parser.parse_args()
    plt = load_matplotlib()
    title = args.title or f"surfgrow {args.kind}"
    if args.kind == "sweep":
        run_sweep(plt, args.folder, title)
    else:
        run_study(plt, args.folder, title)


if __name__ == "__main__":
    main()
