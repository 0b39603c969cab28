"""pastyrik2016 section 5: every OIT technique's total time per model, grouped bars.

Groups are models, each camera position apart (ordered by the mean total over techniques), one bar per
technique (its hatch, presentation.technique_style, and the order say which). The paper's colouring: each
technique's time range over the models is cut into thirds, the fastest third
green, the middle blue, the slowest red, so a bar's colour says how a model
ranks for that technique, independently of the other techniques.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.patches as mpatches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from analysis import common, figure_notes, presentation  # noqa: E402
from analysis.pastyrik_fig8 import model_rows  # noqa: E402

# The paper's green, blue and red, as Okabe-Ito's colour-blind-safe ones.
THIRD_COLOURS = [presentation.OKABE_ITO["bluish_green"], presentation.OKABE_ITO["blue"],
                 presentation.OKABE_ITO["vermillion"]]
# The paper's four first, then the rest in name order.
PAPER_ORDER = ["depth_peeling", "dual_depth_peeling", "linked_list", "illustration_buffer"]


def thirds(times):
    """0, 1 or 2 per value: which third of [min, max] it falls in."""
    low, high = np.nanmin(times), np.nanmax(times)
    if high <= low:
        return np.zeros(len(times), dtype=int)
    return np.minimum((3 * (np.asarray(times) - low) / (high - low)).astype(int), 2)


def draw(runs, args=None):
    rows = model_rows(runs, None)
    # One bar per technique: the peelings' canonical variant (peeling_stages shows both).
    rows = figure_notes.canonical_peels(rows[(rows["stage"] == "total") & (rows["technique"] != "reference")])
    if rows.empty:
        raise common.NoData("no total rows on the model scene")
    # Both camera positions of a model are groups of their own.
    rows = rows.assign(model=[m if v == "general" else f"{m} ({v})" for m, v in zip(rows["model"], rows["view"])])
    table = rows.pivot_table(index="model", columns="technique", values="median_ms", aggfunc="mean")
    techniques = [t for t in PAPER_ORDER if t in table] + sorted(t for t in table if t not in PAPER_ORDER)
    table = table.loc[table.mean(axis=1).sort_values().index, techniques]
    width = 0.8 / len(techniques)
    fig, ax = plt.subplots(figsize=(max(7.5, 1.2 * len(table)), 4.8))
    positions = np.arange(len(table))
    for i, technique in enumerate(techniques):
        times = table[technique].to_numpy()
        present = ~np.isnan(times)
        colours = np.array(THIRD_COLOURS)[thirds(times[present])] if present.any() else []
        ax.bar(positions[present] + (i - (len(techniques) - 1) / 2) * width, times[present], width,
               color=colours, hatch=presentation.technique_style(technique).hatch, edgecolor="black", linewidth=0.5,
               label=technique)
    ax.set_yscale("log")
    ax.set_xticks(positions, list(table.index), rotation=30, ha="right")
    ax.set_xlabel("model")
    ax.set_ylabel("total time per frame (ms, log)")
    legend = [mpatches.Patch(facecolor="white", edgecolor="black", hatch=presentation.technique_style(t).hatch,
                             label=t) for t in techniques]
    legend += [mpatches.Patch(color=c, label=f"{name} third of its range")
               for c, name in zip(THIRD_COLOURS, ["fastest", "middle", "slowest"])]
    ax.legend(handles=legend, fontsize=6, ncol=2, loc="upper left")
    peels = sorted({figure_notes.tie_break(p) for p in rows.loc[rows["technique"].str.contains("peeling"), "params"]}
                   - {""})
    ties = f", peelings tie_break={','.join(peels)}" if peels else ""
    ax.set_title(common.title(rows, "pastyrik2016 section 5: OIT techniques per model (colour: thirds per technique"
                                    f"{ties})"), fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
