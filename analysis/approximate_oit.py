#!/usr/bin/python3
"""The approximate OIT techniques side by side: a run-time-against-error table
with the Pareto front marked, and an image grid of one view per technique with
its error heatmap under it.

Usage:
  python3 -m analysis.approximate_oit table PARETO.csv [-o TABLE.md] [--metric error_rmse|error_max] [--short]
  python3 -m analysis.approximate_oit grid --oitbench build/harness/oitbench [--scene SCENE]
        [--scene-set k=v]... [--size WxH] [--technique ID[:k=v,...]]... -o GRID.png

`table` reads the CSV of `oitbench pareto` and writes, per scene, every
configuration's median total time and error, `front` marking the runs no other
run of that scene beats in both (analysis/pareto.py's front). `grid` renders
each technique with `oitbench render` to a float PFM, the exact reference
likewise, and draws the reference and the images in one row (sRGB, as the
harness displays linear values) and |image - reference| (largest over RGB)
under them on the harness's error scale (viridis, log, 1e-4 .. 1, one colour
bar), so the heatmaps compare.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from analysis.pareto import load_totals, pareto_front  # noqa: E402
from analysis.presentation import DEFAULT_OITBENCH, FACET_COLUMNS, facet_title, varying_params  # noqa: E402

DEFAULT_TECHNIQUES = ["unsorted", "weighted_blended", "moment_oit", "hybrid_transparency",
                      "stochastic_transparency", "multi_layer_alpha_blending", "adaptive_transparency",
                      "kbuffer:k=4"]


def read_pfm(path):
    """A PFM file as a float array of rows top to bottom (the file stores them bottom-up)."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        if kind not in (b"PF", b"Pf"):
            raise ValueError(f"{path}: not a PFM file (header {kind!r})")
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        data = np.fromfile(f, dtype="<f4" if scale < 0 else ">f4", count=width * height * channels)
    if data.size != width * height * channels:
        raise ValueError(f"{path}: {data.size} values, expected {width * height * channels}")
    return np.flipud(data.reshape(height, width, channels))


def table(args):
    totals = load_totals(args.csv, args.metric)
    what = ("each technique's fastest and most accurate run" if args.short else "every run")
    lines = [f"Run time against {args.metric} from `{os.path.basename(args.csv)}`, {what}; params show the swept "
             "knobs; `front` = on the Pareto front of its scene (no run of any technique is both faster and more "
             "accurate).", ""]
    # One section per scene configuration: times of other clocks, devices or
    # camera sets are not comparable (presentation.FACET_COLUMNS).
    for key, points in totals.groupby(FACET_COLUMNS):
        front = set(pareto_front(points).index)
        params = varying_params(points)
        if args.short:
            ends = [rows.sort_values(key).index[0] for _, rows in points.groupby("technique")
                    for key in (["time_ms", "error"], ["error", "time_ms"])]
            points = points.loc[sorted(set(ends))]
        lines += [f"### {facet_title(key, totals)}", "",
                  f"| technique | params | median total ms | {args.metric} | front |", "|---|---|---|---|---|"]
        for index, row in points.sort_values(["time_ms", "error"]).iterrows():
            lines.append(f"| {row['technique']} | {params[index]} | {row['time_ms']:.2f} | {row['error']:.3g} | "
                         f"{'front' if index in front else ''} |")
        lines.append("")
    text = "\n".join(lines)
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
        print(f"wrote {args.out}")
    else:
        print(text)


def render(oitbench, technique_spec, args, out_dir):
    """Renders `technique[:k=v,...]` to a PFM in out_dir and returns its path."""
    technique, _, settings = technique_spec.partition(":")
    path = os.path.join(out_dir, technique_spec.replace(":", "_").replace(",", "_").replace("=", "-") + ".pfm")
    command = [oitbench, "render", "--technique", technique, "--scene", args.scene, "--size", args.size,
               "--out", path]
    for setting in filter(None, settings.split(",")):
        command += ["--set", setting]
    for setting in args.scene_set:
        command += ["--scene-set", setting]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed ({result.returncode}):\n{result.stdout}{result.stderr}")
    return path


# The harness's error images (`oitbench bench --images`): the largest
# channel error per pixel on one absolute log scale, viridis, 1e-4 .. 1.
ERROR_FLOOR, ERROR_CEILING = 1e-4, 1.0


def srgb(linear):
    """Linear RGB in [0, 1] as sRGB for display (IEC 61966-2-1, as the
    harness's display PNGs: harness/output/image.h srgb_encode)."""
    c = np.clip(linear, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def draw_grid(reference, images, names, title):
    """The exact reference, then each technique's image (top row, sRGB) and
    its |image - reference| (largest over RGB) under it, viridis on the
    harness's log scale with one colour bar. Returns (figure, errors)."""
    from matplotlib.colors import LogNorm

    errors = [np.abs(image - reference).max(axis=2) for image in images]
    columns = len(images) + 1
    fig, axes = plt.subplots(2, columns, figsize=(2.1 * columns + 0.8, 4.6), squeeze=False, layout="constrained")
    axes[0][0].imshow(srgb(reference), interpolation="nearest")
    axes[0][0].set_title("reference (exact)", fontsize=7)
    axes[1][0].text(0.5, 0.5, "each technique's\nerror against\nthe reference\nunder its image", ha="center",
                    va="center", fontsize=7, transform=axes[1][0].transAxes)
    norm = LogNorm(vmin=ERROR_FLOOR, vmax=ERROR_CEILING)
    for column, (name, image, error) in enumerate(zip(names, images, errors), start=1):
        axes[0][column].imshow(srgb(image), interpolation="nearest")
        axes[0][column].set_title(name.replace(":", "\n"), fontsize=7)
        heat = axes[1][column].imshow(np.clip(error, ERROR_FLOOR, ERROR_CEILING), cmap="viridis", norm=norm,
                                      interpolation="nearest")
        axes[1][column].set_title(f"max {error.max():.3g}, rmse {np.sqrt((error ** 2).mean()):.2g}", fontsize=6)
    for ax in axes.flat:
        ax.set_xticks([])
        ax.set_yticks([])
    axes[1][0].axis("off")
    if images:
        fig.colorbar(heat, ax=axes[1].tolist(), fraction=0.02, pad=0.01,
                     label="|image - reference|, max of RGB")
    fig.suptitle(title, fontsize=8)
    return fig, errors


def grid(args):
    techniques = args.technique or DEFAULT_TECHNIQUES
    with tempfile.TemporaryDirectory() as scratch:
        reference = read_pfm(render(args.oitbench, "reference", args, scratch))
        images = [read_pfm(render(args.oitbench, t, args, scratch)) for t in techniques]
    scene = " ".join([args.scene] + args.scene_set)
    fig, errors = draw_grid(reference, images, techniques,
                            f"{scene} {args.size}: the exact reference, each technique (top, sRGB) and its error "
                            f"against the reference (bottom, one log scale)")
    top = max(max(float(e.max()) for e in errors), 0.0)
    fig.savefig(args.out, dpi=130)
    plt.close(fig)
    print(f"wrote {args.out}: largest error {top:.3g}")


def parse_arguments(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    table_parser = commands.add_parser("table", help="markdown table of a pareto CSV with the front marked")
    table_parser.add_argument("csv")
    table_parser.add_argument("-o", "--out", default=None)
    table_parser.add_argument("--metric", default="error_rmse", choices=["error_rmse", "error_max"])
    table_parser.add_argument("--short", action="store_true", help="each technique's fastest and most accurate run")
    grid_parser = commands.add_parser("grid", help="image and error heatmap per technique")
    grid_parser.add_argument("--oitbench", default=DEFAULT_OITBENCH, help="default: the repository's build")
    grid_parser.add_argument("--scene", default="spheres")
    grid_parser.add_argument("--scene-set", action="append", default=[])
    grid_parser.add_argument("--size", default="128x128")
    grid_parser.add_argument("--technique", action="append", default=[],
                             help="ID or ID:key=value,... (repeatable; default: the approximate techniques)")
    grid_parser.add_argument("-o", "--out", required=True)
    return parser.parse_args(argv)


def main(argv=None):
    args = parse_arguments(argv)
    try:
        table(args) if args.command == "table" else grid(args)
    except (RuntimeError, ValueError, OSError) as error:
        sys.exit(str(error))


if __name__ == "__main__":
    main()
