#!/usr/bin/python3
"""Run time against error, one plot per scene configuration, with the Pareto front marked.

Usage: python3 -m analysis.pareto runs.csv [--out-dir DIR] [--prefix NAME] [--metric error_rmse|error_max]
                                  [--oitbench build/harness/oitbench]

Input: the CSV of `oitbench pareto` (or any bench). x = median total time
per frame (log) with a whisker over the 95% confidence interval of the
median (ci_low_ms..ci_high_ms; p05..p95 of the timed frames in a CSV
without them, and the legend says which), y = the
error against the exact reference (symlog, so exact runs sit on the zero
line). A run is on the Pareto front when no other run of the same scene
configuration (scene and parameters, size, camera set, clock, device) is
both at least as fast and at least as accurate; front points are labelled
with the parameters off their technique's defaults. A point off the front
that no front point beats for sure (as accurate or better, and faster with
the whole interval) is ringed: its time is not distinguishable from the
front's. Each technique has its colour and marker (presentation.technique_style).

One PNG and one SVG per configuration, named PREFIX_SCENE_SIZE.png (PREFIX:
the CSV's name, so sweeps written to one directory keep apart); a scene
parameter, camera set, clock or device is added to the name where the CSV
holds several. Two configurations never share a name, and a file replaced
is said so.
"""
import argparse
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

# Run as a script, analysis/ is on the path, not the repository root.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from analysis import presentation  # noqa: E402
from analysis.common import tokens  # noqa: E402
from analysis.results_io import read_results, usable_times  # noqa: E402


def load_totals(path, metric):
    """One row per run configuration (the facet columns of presentation,
    technique, params, scene_rect where present): the median over repeated
    runs of the median total time and of `metric`, the p05..p95 envelope,
    the envelope of the 95% confidence intervals of the median
    (ci_low_ms..ci_high_ms; NaN in a CSV written before the harness
    recorded them), and `label` = technique and its full params."""
    runs = read_results(path, columns=["stage", "median_ms"])
    runs = runs[(runs["status"] == "ok") & (runs["stage"] == "total")]
    if runs.empty:
        sys.exit(f"{path}: no successful runs with a total stage")
    runs = usable_times(runs, path).copy()  # a front of zero or missing times would be drawn from nothing
    for column in ["median_ms", "p05_ms", "p95_ms", "ci_low_ms", "ci_high_ms", metric]:
        runs[column] = pd.to_numeric(runs[column], errors="coerce") if column in runs else float("nan")
    runs["label"] = runs["technique"] + runs["params"].map(lambda p: f" {p}" if p else "")
    runs = presentation.with_facets(runs)
    group = presentation.FACET_COLUMNS + ["technique", "params", "label"] + (
        ["scene_rect"] if "scene_rect" in runs else [])
    return runs.groupby(group, as_index=False).agg(time_ms=("median_ms", "median"), error=(metric, "median"),
                                                   p05=("p05_ms", "min"), p95=("p95_ms", "max"),
                                                   ci_low=("ci_low_ms", "min"), ci_high=("ci_high_ms", "max"),
                                                   timestamp=("timestamp", "min"))


def pareto_front(points):
    """Rows not dominated by another row (faster-or-equal and more-accurate-or-equal, one strictly).
    Every time must be positive (load_totals leaves out the others)."""
    if not (points["time_ms"] > 0).all():
        raise ValueError(f"a Pareto front needs positive times, not {sorted(points['time_ms'])[:3]}")
    ordered = points.sort_values(["time_ms", "error"])
    front, best_error = [], float("inf")
    for index, row in ordered.iterrows():
        if row["error"] < best_error:
            front.append(index)
            best_error = row["error"]
    return points.loc[front].sort_values("time_ms")


def slug(text):
    return re.sub(r"[^A-Za-z0-9._]+", "-", str(text)).strip("-")


def file_names(totals, prefix):
    """{facet key: file name} for every configuration: PREFIX_SCENE_SIZE,
    then whatever else tells the CSV's configurations apart (the scene
    parameters that differ between a scene's configurations, camera set,
    clock, device). A name two configurations would share is an error."""
    keys = list(totals.groupby(presentation.FACET_COLUMNS).groups)
    varying = {column: len({key[i] for key in keys}) > 1 for i, column in enumerate(presentation.FACET_COLUMNS)}
    scene_keys = {}
    for key in keys:
        scene_keys.setdefault(key[2], set()).add(key[3])
    names = {}
    for key in keys:
        device, platform, scene, scene_params, size, camera, clock = key
        settings = [tokens(p) for p in scene_keys[scene]]
        differing = [f"{k}={v}" for k, v in tokens(scene_params).items() if len({s.get(k) for s in settings}) > 1]
        parts = [prefix, os.path.splitext(os.path.basename(scene))[0], *differing, size]
        parts += [camera] if varying["camera_set"] else []
        parts += [clock] if varying["clock"] else []
        parts += [f"{device} {platform}"] if varying["device"] or varying["platform"] else []
        names[key] = "_".join(slug(p) for p in parts) + ".png"
    taken = pd.Series(list(names.values())).value_counts()
    if (taken > 1).any():
        raise ValueError(f"several configurations would be written to {', '.join(taken[taken > 1].index)}")
    return names


def time_intervals(points):
    """(low, high, what) of each point's time: the 95% confidence interval
    of the median where every point has one (ci_low..ci_high), else the
    p05..p95 of the timed frames (an older CSV), `what` naming which."""
    if {"ci_low", "ci_high"} <= set(points) and points[["ci_low", "ci_high"]].notna().all(axis=None):
        return points["ci_low"], points["ci_high"], "95% CI of the median"
    return points["p05"], points["p95"], "p05..p95 of the frames (no CI in this CSV)"


def indistinguishable_from_front(points, front, low, high):
    """Index of the points off the front that no front point beats for sure:
    none is at least as accurate AND faster with its whole interval below
    this point's interval. Their times could put them on the front. A
    point without an interval (a CSV without p05/p95) is not judged."""
    close = []
    for index, row in points.drop(index=front.index).iterrows():
        if pd.isna(low.loc[index]) or pd.isna(high.loc[index]):
            continue
        better = front[front["error"] <= row["error"]]
        if not (high.loc[better.index] < low.loc[index]).any():
            close.append(index)
    return close


def draw_configuration(points, title, metric):
    low, high, interval = time_intervals(points)
    with plt.rc_context(presentation.READABLE):
        fig, ax = plt.subplots(figsize=(9, 6), layout="constrained")
        for technique, rows in points.groupby("technique"):
            style = presentation.technique_style(technique)
            ax.scatter(rows["time_ms"], rows["error"], label=technique, s=36, zorder=3, color=style.colour,
                       marker=style.marker, edgecolors="black", linewidths=0.4)
            spread = rows[low.loc[rows.index].notna() & high.loc[rows.index].notna()]
            ax.errorbar(spread["time_ms"], spread["error"],
                        xerr=[(spread["time_ms"] - low.loc[spread.index]).clip(lower=0),
                              (high.loc[spread.index] - spread["time_ms"]).clip(lower=0)],
                        fmt="none", ecolor=style.colour, elinewidth=1, capsize=2, alpha=0.8)
        front = pareto_front(points)
        ax.step(front["time_ms"], front["error"], where="post", color="black", linewidth=1, label="Pareto front")
        close = points.loc[indistinguishable_from_front(points, front, low, high)]
        if not close.empty:
            ax.scatter(close["time_ms"], close["error"], s=140, facecolors="none", edgecolors="black",
                       linewidths=1, linestyle="--", zorder=4,
                       label="off the front, not distinguishable\nfrom it (intervals overlap)")
        ax.errorbar([], [], xerr=[], fmt="none", ecolor="grey", capsize=2, label=f"whisker: {interval}")
        # Front points carry numbers (staggered: several often sit on the
        # zero line side by side); their labels are listed beside the plot.
        for i, (_, row) in enumerate(front.iterrows(), start=1):
            ax.annotate(str(i), (row["time_ms"], row["error"]), xytext=(0, 5 + 10 * ((i - 1) % 2)),
                        textcoords="offset points", ha="center", fontweight="bold")
        listing = "\n".join(f"{i} {presentation.wrap(label)}" for i, label in enumerate(front["short"], start=1))
        ax.text(1.01, 0.0, f"Pareto front, fastest first:\n{listing}", transform=ax.transAxes, va="bottom")
        ax.set_xscale("log")
        ax.set_yscale("symlog", linthresh=1e-4)
        ax.set_ylim(0.0, max(points["error"].max(), 1e-4) * 3)  # room above the worst run
        ax.set_xlabel(f"median total time per frame (ms, log); whisker: {interval}")
        ax.set_ylabel(f"{metric} against the exact reference")
        ax.set_title(title, loc="left")
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
        ax.grid(alpha=0.3)
    return fig, front


def figures(totals, defaults, metric, prefix):
    """(file name, figure, front) for each configuration of `totals`, one
    at a time; every name is checked before the first figure. Runs without
    a time or `metric` are left out, and stderr says how many."""
    totals = totals.copy()
    short = presentation.short_params(totals, defaults)
    totals["short"] = totals["technique"] + short.map(lambda s: f" {s}" if s else "")
    names = file_names(totals, prefix)
    for key, points in totals.groupby(presentation.FACET_COLUMNS):
        measured = points.dropna(subset=["time_ms", "error"])
        if len(measured) < len(points):  # e.g. a bench without --reference writes no error
            print(f"{presentation.facet_title(key, totals)}: {len(points) - len(measured)} run(s) without a time or "
                  f"{metric} left out", file=sys.stderr)
        if measured.empty:
            continue
        points = measured
        title = presentation.facet_title(key, totals) + "\n" + presentation.caption(points, "Run time against error",
                                                                                    defaults)
        yield (names[key],) + draw_configuration(points, title, metric)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("--out-dir", default=None, help="default: next to the CSV")
    parser.add_argument("--prefix", default=None, help="start of every file name (default: the CSV's name without "
                                                       ".csv)")
    parser.add_argument("--metric", default="error_rmse", choices=["error_rmse", "error_max"])
    parser.add_argument("--oitbench", default=None, help="the build whose parameter defaults the labels leave out "
                                                         f"(default: {presentation.DEFAULT_OITBENCH})")
    args = parser.parse_args()
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.csv))
    prefix = args.prefix or os.path.splitext(os.path.basename(args.csv))[0]
    try:
        totals = load_totals(args.csv, args.metric)
        drawn = 0
        for name, fig, front in figures(totals, presentation.technique_defaults(args.oitbench), args.metric, prefix):
            presentation.save_png_and_svg(fig, os.path.join(out_dir, name), dpi=120)
            plt.close(fig)
            print(f"  front = {', '.join(front['short'])}")
            drawn += 1
        if not drawn:
            raise ValueError(f"{args.csv}: no run has both a time and {args.metric} (see above): no plot written")
    except (ValueError, RuntimeError, OSError) as e:
        sys.exit(f"pareto: {e}")


if __name__ == "__main__":
    main()
