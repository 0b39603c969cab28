"""pastyrik2016 Figures 11-14: each exact technique's time per model as parallel coordinates.

The paper draws one parallel-coordinates plot per technique (Fig. 11 depth
peeling, 12 dual depth peeling, 13 linked lists, 14 the illustration
buffer): one polyline per model through its workload (vertices, fragments,
longest list, complexity coverage Psi) and the technique's total time,
coloured by the third of the technique's own time range it falls in (green
fastest, blue, red slowest), as analysis.oit_comparison colours its bars.
Each axis runs from its smallest to its largest value over the models
(both written at its ends; vertices, fragments and time on a log scale), so a line's slope between two axes says how the
model ranks on both. Both camera positions are lines of their own.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.patches as mpatches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from analysis import common, figure_notes  # noqa: E402
from analysis.oit_comparison import THIRD_COLOURS, thirds  # noqa: E402
from analysis.pastyrik_fig8 import model_rows  # noqa: E402

FIGURES = [("Fig. 11", "depth_peeling"), ("Fig. 12", "dual_depth_peeling"), ("Fig. 13", "linked_list"),
           ("Fig. 14", "illustration_buffer")]
# (axis label, column): the workload of the view, then the technique's time.
# Counts and times span orders of magnitude over the models: log axes.
AXES = [("vertices", "extra_scene_vertices"), ("fragments", "fragments"), ("longest list", "max_depth_complexity"),
        ("Psi", "psi"), ("total ms", "median_ms")]
LOG_AXES = {"extra_scene_vertices", "fragments", "median_ms"}


def model_table(runs, technique):
    """One row per model position (index 'model (view)'), the AXES columns."""
    rows = figure_notes.canonical_peels(model_rows(runs, technique))
    rows = rows[rows["stage"] == "total"]
    rows = rows.assign(model=[m if v == "general" else f"{m} ({v})" for m, v in zip(rows["model"], rows["view"])])
    columns = [c for _, c in AXES if c in rows]
    return rows, rows.groupby("model")[columns].mean()


def scaled(table):
    """Each column to [0, 1] over its range, LOG_AXES by their logarithm (a
    constant column: 0.5)."""
    table = table.copy()
    for column in table:
        if column in LOG_AXES and (table[column] > 0).all():
            table[column] = np.log10(table[column])
    low, high = table.min(), table.max()
    span = (high - low).replace(0, np.nan)
    return ((table - low) / span).fillna(0.5)


def draw_panel(ax, table, title):
    axes = [(label, column) for label, column in AXES if column in table]
    positions = np.arange(len(axes))
    values = scaled(table[[c for _, c in axes]])
    colour_of = np.array(THIRD_COLOURS)[thirds(table["median_ms"].to_numpy())]
    for (model, row), colour in zip(values.iterrows(), colour_of):
        ax.plot(positions, row.to_numpy(), color=colour, linewidth=1.2, alpha=0.85, marker="o", markersize=2.5,
                label=model)
    for x, (label, column) in zip(positions, axes):
        ax.axvline(x, color="black", linewidth=0.8)
        low, high = table[column].min(), table[column].max()
        ax.text(x, -0.04, f"{low:.3g}", ha="center", va="top", fontsize=7)
        ax.text(x, 1.04, f"{high:.3g}", ha="center", va="bottom", fontsize=7)
    ax.set_xticks(positions, [f"{label} (log)" if column in LOG_AXES else label for label, column in axes])
    ax.set_yticks([])
    ax.set_ylim(-0.15, 1.15)
    ax.set_xlim(-0.2, len(axes) - 0.8)
    for side in ("left", "right", "top"):
        ax.spines[side].set_visible(False)
    ax.set_title(title, fontsize=9)


def draw(runs, args=None):
    panels = []
    for figure, technique in FIGURES:
        try:
            rows, table = model_table(runs, technique)
        except common.NoData:
            continue
        if not table.empty and "median_ms" in table:
            panels.append((figure, technique, rows, table))
    if not panels:
        raise common.NoData("no total rows of depth_peeling, dual_depth_peeling, linked_list or illustration_buffer "
                            "on the models")
    fig, axes = plt.subplots(len(panels), 1, figsize=(8.5, 2.6 * len(panels) + 1.0), squeeze=False)
    for ax, (figure, technique, rows, table) in zip(axes[:, 0], panels):
        draw_panel(ax, table, f"{figure}: {technique} ({len(table)} model positions)")
    legend = [mpatches.Patch(color=c, label=f"{name} third of its time range")
              for c, name in zip(THIRD_COLOURS, ["fastest", "middle", "slowest"])]
    fig.legend(handles=legend, loc="lower center", ncol=3, fontsize=8, frameon=False)
    every = pd.concat([rows for _, _, rows, _ in panels])
    fig.suptitle(common.title(every, "pastyrik2016 Figs. 11-14: parallel coordinates per technique (each axis "
                                     "min..max over the models)" + figure_notes.noisy_note(every)), fontsize=9)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
