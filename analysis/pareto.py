#!/usr/bin/python3
"""Run time against error, one plot per scene, with the Pareto front marked.

Usage: analysis/pareto.py runs.csv [--out-dir DIR] [--metric error_rmse|error_max]

Input: the CSV of `oitbench pareto` (or any bench). x = median total time
per frame (log), y = the error against the exact reference (symlog, so exact
runs sit on the zero line). A run is on the Pareto front when no other run of
the same scene and size is both at least as fast and at least as accurate.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Run as a script, analysis/ is on the path, not the repository root.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from analysis.results_io import read_results, save_figure  # noqa: E402


def load_totals(path, metric):
    runs = read_results(path, keep_default_na=False, na_values={"median_ms": [""], metric: [""]})
    runs = runs[(runs["status"] == "ok") & (runs["stage"] == "total")].copy()
    if runs.empty:
        sys.exit(f"{path}: no successful runs with a total stage")
    runs["label"] = runs["technique"] + runs["params"].map(lambda p: f" {p}" if p else "")
    runs["size"] = runs["width"].astype(str) + "x" + runs["height"].astype(str)
    # One point per run configuration: the median over repeated rows.
    group = ["scene", "scene_params", "size", "technique", "label", "clock"]
    return runs.groupby(group, as_index=False).agg(time_ms=("median_ms", "median"), error=(metric, "median"))


def pareto_front(points):
    """Rows not dominated by another row (faster-or-equal and more-accurate-or-equal, one strictly)."""
    ordered = points.sort_values(["time_ms", "error"])
    front, best_error = [], float("inf")
    for index, row in ordered.iterrows():
        if row["error"] < best_error:
            front.append(index)
            best_error = row["error"]
    return points.loc[front].sort_values("time_ms")


def plot_scene(points, title, out, metric):
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for technique, rows in points.groupby("technique"):
        ax.scatter(rows["time_ms"], rows["error"], label=technique, s=28)
    front = pareto_front(points)
    ax.step(front["time_ms"], front["error"], where="post", color="black", linewidth=1, label="Pareto front")
    for _, row in front.iterrows():
        ax.annotate(row["label"], (row["time_ms"], row["error"]), fontsize=6, xytext=(3, 3),
                    textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("symlog", linthresh=1e-4)
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("median total time per frame (ms, log)")
    ax.set_ylabel(f"{metric} against the exact reference")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    save_figure(fig, out, dpi=120)
    plt.close(fig)
    return front


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("--out-dir", default=None, help="default: next to the CSV")
    parser.add_argument("--metric", default="error_rmse", choices=["error_rmse", "error_max"])
    args = parser.parse_args()
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.csv))
    os.makedirs(out_dir, exist_ok=True)
    totals = load_totals(args.csv, args.metric)
    devices = read_results(args.csv, keep_default_na=False)["device"].unique()
    for (scene, scene_params, size, clock), points in totals.groupby(["scene", "scene_params", "size", "clock"]):
        name = f"pareto_{os.path.basename(scene).replace('.', '_')}_{size}.png"
        title = f"{scene} {scene_params} {size}, clock {clock}\n{', '.join(devices)}"
        front = plot_scene(points, title, os.path.join(out_dir, name), args.metric)
        print(f"wrote {os.path.join(out_dir, name)}: front = {', '.join(front['label'])}")


if __name__ == "__main__":
    main()
