"""pastyrik2016 Figure 10: list-length heatmaps of every model.

The heatmaps are the PNGs `oitbench stats --heatmap DIR/heatmap_<model>.png`
writes (blue 0 .. red the longest list); the CSV gives the order (by
illustration buffer total, as Fig. 8), each model's longest list and Psi, and
the device/resolution/date of the title.
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common  # noqa: E402
from analysis.pastyrik_fig8 import model_rows, models_by_total  # noqa: E402


def heatmap_path(directory, model):
    return os.path.join(directory, f"heatmap_{model}.png")


def draw(runs, args):
    rows = model_rows(runs)
    # The heatmaps are of the default camera: its runs give order and counts.
    rows = rows[rows["view"] == "general"] if (rows["view"] == "general").any() else rows
    order = [m for m in models_by_total(rows) if os.path.exists(heatmap_path(args.heatmaps, m))]
    if not order:
        raise common.NoData(f"no heatmap_<model>.png in {args.heatmaps} for the models of the CSV")
    columns = min(4, len(order))
    lines = (len(order) + columns - 1) // columns
    fig, axes = plt.subplots(lines, columns, figsize=(2.6 * columns, 2.8 * lines + 0.6), squeeze=False)
    totals = rows[rows["stage"] == "total"].groupby("model")
    for ax, model in zip(axes.flat, order):
        ax.imshow(mpimg.imread(heatmap_path(args.heatmaps, model)))
        ax.set_title(f"{model}\nlongest {int(totals['max_depth_complexity'].max()[model])}, "
                     f"Psi {totals['psi'].mean()[model]:.3f}", fontsize=7)
        ax.set_xticks([])
        ax.set_yticks([])
    for ax in list(axes.flat)[len(order):]:
        ax.axis("off")
    fig.suptitle(common.title(rows, "pastyrik2016 Fig. 10: list-length heatmaps (blue 0 .. red longest)"),
                 fontsize=8)
    fig.tight_layout()
    return fig


def arguments(parser):
    parser.add_argument("--heatmaps", required=True, help="folder with heatmap_<model>.png")


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw, arguments)
