#!/usr/bin/env python3
"""Lucerna convergence plots: DIR/convergence.csv -> DIR/plot_spp.png and DIR/plot_time.png.

Log-log error vs samples per pixel and error vs seconds, one curve per integrator (the median over
runs), the spread over runs drawn as a min/max band, and a dashed 1/N guide (the rate of an
unbiased Monte Carlo estimator). File layout: docs/convergence.md. Needs matplotlib (Debian's
python3-matplotlib, scripts/setup.sh): run it with a python3 that has it.

usage: plot_convergence.py DIR [--metrics relmse,mse] [--title TEXT]
"""
import argparse
import csv
import json
import math
import os
import sys
from collections import defaultdict

REQUIRED = ["integrator", "run", "spp", "seconds", "mse", "rmse", "relmse"]
LABELS = {"mse": "MSE", "rmse": "RMSE", "relmse": "relMSE", "mape": "MAPE"}


def read_convergence(path):
    """Rows of convergence.csv as dicts with typed values; exits with a message on bad input."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in REQUIRED if c not in (reader.fieldnames or [])]
        if missing:
            sys.exit(f"{path}: missing columns {', '.join(missing)} (need {','.join(REQUIRED)})")
        rows = []
        for line, r in enumerate(reader, start=2):
            try:
                row = {"integrator": r["integrator"].strip(), "run": int(r["run"]), "spp": int(float(r["spp"])),
                       "seconds": float(r["seconds"])}
                for k, v in r.items():
                    if k not in row and k is not None and v not in (None, ""):
                        row[k] = float(v)
            except ValueError as e:
                sys.exit(f"{path}:{line}: {e}")
            rows.append(row)
    if not rows:
        sys.exit(f"{path}: no data rows")
    return rows


def integrator_order(names):
    """path first (the baseline), then the rest alphabetically."""
    return sorted(set(names), key=lambda n: (n != "path", n))


def colors_for(integrators):
    import matplotlib.pyplot as plt
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return {name: cycle[i % len(cycle)] for i, name in enumerate(integrators)}


def summarize(rows, integrator, metric):
    """Per spp checkpoint: (spp, mean seconds, median, min, max of the metric over runs)."""
    by_spp = defaultdict(list)
    for r in rows:
        if r["integrator"] == integrator and metric in r and r["spp"] > 0:
            by_spp[r["spp"]].append((r["seconds"], r[metric]))
    out = []
    for spp in sorted(by_spp):
        secs = [s for s, _ in by_spp[spp]]
        errs = sorted(e for _, e in by_spp[spp] if math.isfinite(e) and e > 0)
        if not errs:
            continue
        n = len(errs)
        median = errs[n // 2] if n % 2 else 0.5 * (errs[n // 2 - 1] + errs[n // 2])
        out.append((spp, sum(secs) / len(secs), median, errs[0], errs[-1], n))
    return out


def run_info(directory):
    path = os.path.join(directory, "run.json")
    if os.path.exists(path):
        try:
            with open(path) as f:
                return json.load(f)
        except (OSError, ValueError):
            pass
    return {}


def scene_title(directory, info):
    """The reference's name (cornell-box), else the scene's folder, else the directory's name."""
    if info.get("reference"):
        return os.path.splitext(os.path.basename(str(info["reference"])))[0]
    scene = info.get("scene")
    if scene:
        base = os.path.splitext(os.path.basename(str(scene)))[0]
        return base if not base.startswith("scene") else os.path.basename(os.path.dirname(str(scene)))
    return os.path.basename(os.path.abspath(directory))


def plot(rows, metrics, xkey, out_path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    integrators = integrator_order(r["integrator"] for r in rows)
    colors = colors_for(integrators)
    fig, axes = plt.subplots(1, len(metrics), figsize=(5.2 * len(metrics), 4.2), squeeze=False)
    for ax, metric in zip(axes[0], metrics):
        guide_drawn = False
        for name in integrators:
            pts = summarize(rows, name, metric)
            if not pts:
                continue
            xs = [p[0] if xkey == "spp" else p[1] for p in pts]
            keep = [i for i, x in enumerate(xs) if x > 0]
            xs = [xs[i] for i in keep]
            pts = [pts[i] for i in keep]
            if not xs:
                continue
            runs = max(p[5] for p in pts)
            label = name if runs <= 1 else f"{name} (median of {runs} runs)"
            ax.plot(xs, [p[2] for p in pts], "-o", color=colors[name], label=label, markersize=3, linewidth=1.6)
            if runs > 1:
                ax.fill_between(xs, [p[3] for p in pts], [p[4] for p in pts], color=colors[name], alpha=0.2,
                                linewidth=0)
            if not guide_drawn and len(xs) > 1 and metric in ("mse", "relmse"):
                # 1/N through the first integrator's first point: the unbiased Monte Carlo rate.
                x0, y0 = xs[0], pts[0][2]
                ax.plot([x0, xs[-1]], [y0, y0 * x0 / xs[-1]], "--", color="0.55", linewidth=1,
                        label="slope -1 (1/N)")
                guide_drawn = True
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("samples per pixel" if xkey == "spp" else "seconds")
        ax.set_ylabel(LABELS.get(metric, metric))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title(f"{LABELS.get(metric, metric)} vs {'spp' if xkey == 'spp' else 'time'}", fontsize=10)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    fig.savefig(out_path, dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir", help="directory written by `lucerna converge` (holds convergence.csv)")
    ap.add_argument("--metrics", default="relmse,mse", help="comma-separated columns to plot (default relmse,mse)")
    ap.add_argument("--title", help="figure title (default: the scene name)")
    args = ap.parse_args(argv)
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        sys.exit("plot_convergence.py: matplotlib is missing in " + sys.executable + "; install python3-matplotlib (scripts/setup.sh) or run a python3 that has it (LUCERNA_PYTHON)")
    csv_path = os.path.join(args.dir, "convergence.csv")
    if not os.path.exists(csv_path):
        sys.exit(f"plot_convergence.py: {csv_path} does not exist")
    rows = read_convergence(csv_path)
    metrics = [m.strip() for m in args.metrics.split(",") if m.strip()]
    for m in metrics:
        if not any(m in r for r in rows):
            sys.exit(f"{csv_path}: no column '{m}'")
    title = args.title or scene_title(args.dir, run_info(args.dir))
    plot(rows, metrics, "spp", os.path.join(args.dir, "plot_spp.png"), title)
    plot(rows, metrics, "seconds", os.path.join(args.dir, "plot_time.png"), title)
    print(os.path.join(args.dir, "plot_spp.png"))
    print(os.path.join(args.dir, "plot_time.png"))


if __name__ == "__main__":
    main()
