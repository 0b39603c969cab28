"""pastyrik2016 Figure 9: vertices, fragments, longest list, time and Psi per model.

Models in the order of Fig. 8 (illustration buffer total). Primary axis
(log): vertices, fragments, the longest per-pixel list and the total time in
ms; secondary axis (dashed): the complexity coverage Psi, the share of
pixels whose list is longer than 2/3 of the longest, which the paper finds
explains times the other quantities do not.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common  # noqa: E402
from analysis.pastyrik_fig8 import model_rows, models_by_total  # noqa: E402


def draw(runs, args=None):
    rows = model_rows(runs)
    order = models_by_total(rows)
    totals = rows[rows["stage"] == "total"].groupby("model")
    series = [("vertices", "extra_scene_vertices"), ("fragments", "fragments"),
              ("max list length", "max_depth_complexity"), ("total time (ms)", "median_ms")]
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    positions = list(range(len(order)))
    for label, column in series:
        if column not in rows:
            continue
        ax.plot(positions, totals[column].mean().loc[order].to_numpy(), marker="o", markersize=3, label=label)
    ax.set_yscale("log")
    ax.set_xticks(positions, order, rotation=30, ha="right")
    ax.set_xlabel("model (sorted by illustration buffer total time)")
    ax.set_ylabel("count / ms (log)")
    psi_ax = ax.twinx()
    psi_ax.plot(positions, totals["psi"].mean().loc[order].to_numpy(), color="black", linestyle="--", marker="^",
                markersize=3, label="Psi")
    psi_ax.set_ylabel("complexity coverage Psi")
    psi_ax.set_ylim(bottom=0)
    handles = ax.get_legend_handles_labels()
    psi_handles = psi_ax.get_legend_handles_labels()
    ax.legend(handles[0] + psi_handles[0], handles[1] + psi_handles[1], fontsize=7, loc="upper left")
    ax.set_title(common.title(rows, "pastyrik2016 Fig. 9: model complexity against illustration buffer time"),
                 fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
