"""pastyrik2016 Figure 9: vertices, fragments, longest list, time and Psi per model.

Models in the order of Fig. 8 (illustration buffer total), one column per
camera position (general, max_list). Top: the workload counts on a log axis
(vertices, fragments, the longest per-pixel list) and, dashed on a second
axis, the complexity coverage Psi, the share of pixels whose list is longer
than 2/3 of the longest, which the paper finds explains times the other
quantities do not. Bottom: the illustration buffer's total time and its
neighbour stage on their own (linear) axis, so that whether the time follows
Psi or the counts can be read off.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common, figure_notes  # noqa: E402
from analysis.pastyrik_fig8 import model_rows, models_by_total, views  # noqa: E402

SERIES = [("vertices", "extra_scene_vertices"), ("fragments", "fragments"), ("max list length", "max_depth_complexity")]


def counts_panel(ax, part, order, positions):
    totals = part[part["stage"] == "total"].groupby("model")
    for label, column in SERIES:
        if column in part:
            ax.plot(positions, totals[column].mean().loc[order].to_numpy(), marker="o", markersize=3, label=label)
    ax.set_yscale("log")
    ax.set_ylabel("count (log)")
    psi_ax = ax.twinx()
    psi_ax.plot(positions, totals["psi"].mean().loc[order].to_numpy(), color="black", linestyle="--", marker="^",
                markersize=3, label="Psi")
    psi_ax.set_ylabel("complexity coverage Psi")
    psi_ax.set_ylim(bottom=0)
    handles = ax.get_legend_handles_labels()
    psi_handles = psi_ax.get_legend_handles_labels()
    ax.legend(handles[0] + psi_handles[0], handles[1] + psi_handles[1], fontsize=7, loc="upper left")


def time_panel(ax, part, order, positions):
    table = common.stage_table(part, "model").loc[order]
    for stage, style in (("total", "-"), ("neighbors", ":")):
        if stage in table:
            ax.plot(positions, table[stage].to_numpy(), color="black", linestyle=style, marker="s", markersize=3,
                    label=f"{'total' if stage == 'total' else 'neighbour stage'} time (ms)")
    ax.set_ylabel("time per frame (ms)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left")


def draw(runs, args=None):
    rows = model_rows(runs)
    panels = views(rows)
    fig, axes = plt.subplots(2, len(panels), figsize=(7.5 * len(panels), 7), squeeze=False, sharex="col",
                             gridspec_kw={"height_ratios": [3, 2]})
    for column, view in enumerate(panels):
        part = rows[rows["view"] == view]
        order = models_by_total(part)
        positions = list(range(len(order)))
        counts_panel(axes[0][column], part, order, positions)
        time_panel(axes[1][column], part, order, positions)
        axes[1][column].set_xticks(positions, order, rotation=30, ha="right")
        axes[1][column].set_xlabel(f"model (sorted by illustration buffer total time), camera: {view}")
        axes[0][column].set_title(common.title(part, f"pastyrik2016 Fig. 9: model complexity against illustration "
                                                     f"buffer time ({view} camera{figure_notes.noisy_note(part)})"),
                                  fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
