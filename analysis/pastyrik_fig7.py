"""pastyrik2016 Figure 7: the sort variants per model.

The paper compares sorting the linked list in place (the dynamic sort,
Algorithm 2) with a selection sort in three static arrays of 64 entries
(section 3.2, 4.1), per model. The sweep times the illustration buffer's
sort=dynamic and sort=static_arrays (analysis/figure_configs.py) where the
build has them, else every `sort` of `linked_list` (the lists the buffer is
built on, sorted while composing). Top: total time per model and variant;
bottom: the stage that sorts (`sort`, else `compose`). Both camera positions
are groups of their own.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common, figure_notes  # noqa: E402
from analysis.pastyrik_fig8 import model_rows  # noqa: E402

PAPER = ["pastyrik2016 (GTX 660, 600x600): the dynamic sort",
         "(in the linked list) beats the static arrays (3 x 64 entries)",
         "on every model; spikes where Psi is large"]

# What each illustration_buffer sort is, for the legend.
SORT_LABELS = {"static_arrays": "static arrays (3 x 64, selection sort)",
               "dynamic": "dynamic (Algorithm 2, in the list)",
               "array": "array sized to the longest list (carnecky2013 4.3)"}


def legend(variant):
    return f"sort={variant}: {SORT_LABELS[variant]}" if variant in SORT_LABELS else f"sort={variant}"


def draw(runs, args=None):
    candidates = [t for t in ("illustration_buffer", "linked_list")
                  if common.select(runs, t)["params"].map(lambda p: "sort" in common.tokens(p)).any()]
    if not candidates:
        raise common.NoData("no illustration_buffer or linked_list rows with a sort parameter")
    technique = candidates[0]
    rows = model_rows(runs, technique)
    rows = rows.assign(model=[m if v == "general" else f"{m} ({v})" for m, v in zip(rows["model"], rows["view"])],
                       sort=rows["params"].map(lambda p: common.tokens(p).get("sort", "")))
    stage = "sort" if (rows["stage"] == "sort").any() else "compose"
    totals = rows[rows["stage"] == "total"].pivot_table(index="model", columns="sort", values="median_ms")
    sorting = rows[rows["stage"] == stage].pivot_table(index="model", columns="sort", values="median_ms")
    order = list(totals.min(axis=1).sort_values().index)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8.5, 7), sharex=True)
    positions = list(range(len(order)))
    for variant in totals.columns:
        top.plot(positions, totals.loc[order, variant].to_numpy(), marker="o", markersize=3, label=legend(variant))
        if variant in sorting:
            bottom.plot(positions, sorting.reindex(order)[variant].to_numpy(), marker="o", markersize=3,
                        label=legend(variant))
    top.set_ylabel("total time per frame (ms)")
    bottom.set_ylabel(f"{stage} stage (ms)")
    for ax in (top, bottom):
        ax.set_yscale("log")
    bottom.set_xticks(positions, order, rotation=30, ha="right")
    bottom.set_xlabel("model (sorted by the fastest variant's total)")
    return figure_notes.finish_panels(fig, (top, bottom), rows, f"pastyrik2016 Fig. 7: sort variants of {technique}",
                                      paper=PAPER)


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
