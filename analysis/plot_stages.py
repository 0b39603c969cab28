#!/usr/bin/python3
"""Per-stage run time of every technique, from an oitbench CSV.

Usage: analysis/plot_stages.py runs.csv [--out stages.png] [--scene quads] [--clock wall]

One stacked bar per (technique, params): the median milliseconds of each
stage (the total is drawn as a marker: stages run back to back, so their sum
is at most the total). The device and clock are in the title, because times
are only comparable within one device and one clock.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

# Run as a script, analysis/ is on the path, not the repository root.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from analysis.common import stage_order  # noqa: E402
from analysis.results_io import read_results, save_figure  # noqa: E402


def load_runs(path, scene=None, clock=None):
    runs = read_results(path, keep_default_na=False, na_values={"median_ms": [""]})
    runs = runs[runs["status"] == "ok"]
    if scene:
        runs = runs[runs["scene"] == scene]
    if clock:
        runs = runs[runs["clock"] == clock]
    if runs.empty:
        sys.exit(f"{path}: no successful runs match scene={scene!r} clock={clock!r}")
    runs = runs.copy()
    runs["label"] = runs["technique"] + runs["params"].map(lambda p: f"\n{p}" if p else "")
    return runs


def plot(runs, out):
    medians = runs.pivot_table(index="label", columns="stage", values="median_ms", aggfunc="median")
    totals = medians.pop("total") if "total" in medians else None
    stages = [s for s in stage_order(runs) if s in medians.columns]
    order = totals.sort_values().index if totals is not None else medians.index
    medians = medians.loc[order, stages].fillna(0.0)
    fig, ax = plt.subplots(figsize=(max(6, 1.1 * len(medians)), 4.5))
    bottom = pd.Series(0.0, index=medians.index)
    for stage in stages:
        ax.bar(medians.index, medians[stage], bottom=bottom, label=stage)
        bottom += medians[stage]
    if totals is not None:
        ax.scatter(medians.index, totals.loc[order], color="black", marker="_", s=400, label="total", zorder=3)
    devices = ", ".join(sorted(runs["device"].unique()))
    clocks = ", ".join(sorted(runs["clock"].unique()))
    scenes = ", ".join(sorted(runs["scene"].unique()))
    ax.set_title(f"{scenes} on {devices}\n(clock: {clocks}; medians over timed frames)", fontsize=9)
    ax.set_ylabel("ms per frame")
    ax.tick_params(axis="x", labelsize=7)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, out, dpi=120)
    print(f"wrote {out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("--out", default=None, help="PNG path (default: next to the CSV)")
    parser.add_argument("--scene", default=None)
    parser.add_argument("--clock", default=None, help="gl or wall (default: every clock present)")
    args = parser.parse_args()
    out = args.out or args.csv.rsplit(".", 1)[0] + "_stages.png"
    plot(load_runs(args.csv, args.scene, args.clock), out)


if __name__ == "__main__":
    main()
