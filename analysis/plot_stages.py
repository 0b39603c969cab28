#!/usr/bin/python3
"""Per-stage run time of every technique, from an oitbench CSV.

Usage: python3 -m analysis.plot_stages runs.csv [--out stages.png] [--scene quads] [--clock wall]
                                        [--oitbench build/harness/oitbench]

One facet per scene configuration (scene and its parameters, size, camera
set, clock, device): runs of different configurations never share a bar.
In a facet, one horizontal stacked bar per run configuration (technique,
params, scene_rect), fastest on top: the median milliseconds of each stage,
averaged over the runs of that configuration (repeats, the views of a random
camera set; the label says how many). The total is a black tick with a
whisker from p05 to p95 of the timed frames (the widest over those runs):
stages run back to back, so their sum is at most the total. Labels name
only the parameters off the technique's defaults (from `oitbench list
--markdown`). Writes the PNG and an SVG beside it.
"""
import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

# Run as a script, analysis/ is on the path, not the repository root.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from analysis import presentation  # noqa: E402
from analysis.common import stage_order  # noqa: E402
from analysis.results_io import read_results, usable_times  # noqa: E402

TIMES = ["median_ms", "p05_ms", "p95_ms"]
MAX_HEIGHT_IN = 400


def load_runs(path, scene=None, clock=None):
    """The successful runs of the CSV with the given scene and clock whose
    every stage has a positive median (usable_times names the others)."""
    runs = read_results(path, columns=["scene", "clock", "stage", "median_ms"])
    runs = runs[runs["status"] == "ok"]
    if scene:
        runs = runs[runs["scene"] == scene]
    if clock:
        runs = runs[runs["clock"] == clock]
    if runs.empty:
        sys.exit(f"{path}: no successful runs match scene={scene!r} clock={clock!r}")
    runs = usable_times(runs, path).copy()
    for column in TIMES:
        runs[column] = pd.to_numeric(runs[column], errors="coerce") if column in runs else np.nan
    return runs


def with_labels(runs, defaults):
    """`runs` with a `label` per row: technique, its parameters off the
    defaults, and scene_rect where the CSV holds both values."""
    runs = runs.copy()
    runs["label"] = presentation.run_labels(runs, defaults)
    if "scene_rect" in runs and runs["scene_rect"].nunique() > 1:
        runs["label"] += " scene_rect=" + runs["scene_rect"]
    return runs


def bars(facet):
    """One row per label of a facet, fastest first: each stage's median
    averaged over the runs, total, its p05/p95 envelope, runs and whether
    any was noisy."""
    config = ["technique", "params"] + (["scene_rect"] if "scene_rect" in facet else [])
    clashes = facet.groupby("label")[config].apply(lambda rows: len(rows.drop_duplicates())).loc[lambda n: n > 1]
    if not clashes.empty:  # two configurations under one label would be one bar
        raise ValueError(f"labels {', '.join(clashes.index)} each name several configurations")
    table = facet.pivot_table(index="label", columns="stage", values="median_ms", aggfunc="mean")
    totals = facet[facet["stage"] == "total"].groupby("label")
    table["p05"] = totals["p05_ms"].min()
    table["p95"] = totals["p95_ms"].max()
    table["runs"] = facet.groupby(["label", "stage"]).size().groupby("label").max()
    table["noisy"] = facet.groupby("label")["noisy"].apply(lambda v: (v == "true").any()) if "noisy" in facet else False
    if "total" not in table:
        table["total"] = np.nan
    return table.sort_values(["total"], na_position="last")


def bar_label(label, row):
    notes = ([f"mean of {int(row['runs'])} runs"] if row["runs"] > 1 else []) + (["noisy"] if row["noisy"] else [])
    return presentation.wrap(label) + (f"\n({', '.join(notes)})" if notes else "")


def draw_facet(ax, table, stages, colors, title):
    y = np.arange(len(table))
    left = np.zeros(len(table))
    for stage in stages:
        if stage in table:
            values = table[stage].fillna(0.0).to_numpy()
            ax.barh(y, values, left=left, height=0.7, color=colors[stage], edgecolor="white", linewidth=0.5)
            left += values
    totals = table["total"].to_numpy()
    ax.scatter(totals, y, marker="|", s=300, color="black", zorder=3)
    spread = table[["total", "p05", "p95"]].dropna()
    if not spread.empty:
        where = [table.index.get_loc(label) for label in spread.index]
        ax.errorbar(spread["total"], where, xerr=[(spread["total"] - spread["p05"]).clip(lower=0),
                                                  (spread["p95"] - spread["total"]).clip(lower=0)],
                    fmt="none", ecolor="black", elinewidth=1, capsize=3, zorder=3)
    ax.set_yticks(y, [bar_label(label, row) for label, row in table.iterrows()])
    ax.set_ylim(len(table) - 0.5, -0.5)  # fastest on top
    ax.set_xlim(left=0)
    ax.set_xlabel("ms per frame")
    ax.set_title(title, loc="left")
    ax.grid(axis="x", alpha=0.3)


def draw(runs, defaults):
    """The figure: one facet (axes) per scene configuration, a shared stage
    legend on top."""
    runs = presentation.with_facets(with_labels(runs, defaults))
    facets = [(key, bars(rows)) for key, rows in runs.groupby(presentation.FACET_COLUMNS, sort=True)]
    stages = stage_order(runs)
    colors = presentation.stage_colours(stages)
    lines = [sum(bar_label(label, row).count("\n") + 1 for label, row in table.iterrows()) for _, table in facets]
    heights = [0.2 * n + 0.25 * len(table) for n, (_, table) in zip(lines, facets)]
    legend_rows = math.ceil((len(stages) + 1) / 5)
    height = 0.9 + 0.3 * legend_rows + sum(h + 1.0 for h in heights)
    if height > MAX_HEIGHT_IN:  # a PNG is at most 2^16 pixels high
        raise ValueError(f"{len(facets)} scene configurations do not fit one figure ({height:.0f} in high): choose "
                         f"some with --scene or --clock")
    with plt.rc_context(presentation.READABLE):
        fig = plt.figure(figsize=(8.5, height), layout="constrained")
        grid = fig.add_gridspec(len(facets) + 1, 1, height_ratios=[0.3 * legend_rows] + heights)
        for i, (key, table) in enumerate(facets):
            draw_facet(fig.add_subplot(grid[i + 1]), table, stages, colors, presentation.facet_title(key, runs))
        legend_ax = fig.add_subplot(grid[0])
        legend_ax.axis("off")
        handles = [plt.Rectangle((0, 0), 1, 1, color=colors[s]) for s in stages]
        handles.append(legend_ax.errorbar([], [], xerr=[], fmt="|", color="black", markersize=12, capsize=3))
        legend_ax.legend(handles, stages + ["total (whisker: p05..p95)"], loc="center", ncol=5, frameon=False)
        fig.suptitle(presentation.caption(runs, "Median time per stage", defaults))
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("--out", default=None, help="PNG path, an SVG is written beside it (default: "
                                                    "<csv>_stages.png next to the CSV)")
    parser.add_argument("--scene", default=None)
    parser.add_argument("--clock", default=None, help="gl or wall (default: every clock present, one facet each)")
    parser.add_argument("--oitbench", default=None, help="the build whose parameter defaults the labels leave out "
                                                         f"(default: {presentation.DEFAULT_OITBENCH})")
    args = parser.parse_args()
    out = args.out or args.csv.rsplit(".", 1)[0] + "_stages.png"
    if not out.lower().endswith(".png"):
        parser.error(f"--out {out}: name a .png file (an .svg is written beside it)")
    try:
        fig = draw(load_runs(args.csv, args.scene, args.clock), presentation.technique_defaults(args.oitbench))
        presentation.save_png_and_svg(fig, out, dpi=120)
    except (ValueError, RuntimeError, OSError) as e:
        sys.exit(f"plot_stages: {e}")


if __name__ == "__main__":
    main()
