"""pastyrik2016 Figures 11-14: depth peeling against dual depth peeling, from stage times.

Per model and camera position: the total time of both peelings (top) and
the time per geometry pass (`peel` stage / `passes`, bottom); where the CSV
holds both tie_break variants (the canonical submission order, solid, and
exact triangle-id ties, hollow), each is a bar of its own, labelled. Dual depth
peeling needs about half the geometry passes (ceil(d/2) + 2 against d + 2)
but each of its passes blends two layers into several float targets with
MAX blending. Which wins depends on what a pass costs: where the vertex work
dominates (the paper's GTX 660 on large CAD models) half the passes is the
gain; where the per-pixel work dominates, the heavier dual pass eats it.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from analysis import common, figure_notes, presentation  # noqa: E402
from analysis.pastyrik_fig8 import model_rows  # noqa: E402

PEELINGS = ["depth_peeling", "dual_depth_peeling"]
PAPER = ["pastyrik2016 (GTX 660): dual depth peeling 'much slower'",
         "than depth peeling on its models (Figs. 11-14)"]


def series_names(rows):
    """Per row its series: the technique and its tie_break where the row's
    params record one (figure_configs times the canonical submission order
    and the exact triangle_id ties; a CSV may hold either or both)."""
    variant = rows["params"].map(figure_notes.tie_break)
    return [f"{t} tie_break={v}" if v else t for t, v in zip(rows["technique"], variant)]


def peel_table(runs):
    """model x (series, quantity): total ms, peel ms, passes; the series in
    PEELINGS order, canonical tie_break first."""
    rows = model_rows(runs, None)
    rows = rows[rows["technique"].isin(PEELINGS)]
    if rows.empty:
        raise common.NoData("no depth_peeling or dual_depth_peeling rows on the models")
    rows = rows.assign(model=[m if v == "general" else f"{m} ({v})" for m, v in zip(rows["model"], rows["view"])],
                       series=series_names(rows))
    total = rows[rows["stage"] == "total"].pivot_table(index="model", columns="series", values="median_ms")
    peel = rows[rows["stage"] == "peel"].pivot_table(index="model", columns="series", values="median_ms")
    passes = rows[rows["stage"] == "total"].pivot_table(index="model", columns="series", values="passes")
    order = sorted(total.columns, key=lambda s: (PEELINGS.index(s.split()[0]), "submission" not in s, s))
    return rows, total[order], peel, passes


def bar_look(series):
    """The technique's colour and hatch; its exact-ties variant hollow, in
    the technique's colour."""
    style = presentation.technique_style(series.split()[0])
    if series.endswith("tie_break=triangle_id"):
        return dict(color="white", hatch=style.hatch, edgecolor=style.colour, linewidth=0.8, label=series)
    return dict(color=style.colour, hatch=style.hatch, edgecolor="white", linewidth=0.5, label=series)


def draw(runs, args=None):
    rows, total, peel, passes = peel_table(runs)
    order = list(total.mean(axis=1).sort_values().index)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(max(8.5, 0.5 * len(order)), 7.5), sharex=True)
    positions = np.arange(len(order))
    width = 0.8 / len(total.columns)
    for i, technique in enumerate(total.columns):
        offset = (i - (len(total.columns) - 1) / 2) * width
        look = bar_look(technique)
        top.bar(positions + offset, total.loc[order, technique], width, **look)
        if technique in peel and technique in passes:
            per_pass = peel.reindex(order)[technique] / passes.reindex(order)[technique]
            bottom.bar(positions + offset, per_pass, width, **look)
            for x, n in zip(positions + offset, passes.reindex(order)[technique]):
                if np.isfinite(n):
                    # x in data, y in axes units: the foot of the bar on a log axis.
                    top.text(x, 0.01, f"{int(n)}", ha="center", va="bottom", fontsize=5, rotation=90,
                             transform=top.get_xaxis_transform())
    top.set_yscale("log")
    top.set_ylabel("total time per frame (ms, log)\n(bar foot: geometry passes)")
    bottom.set_yscale("log")
    bottom.set_ylabel("peel stage per geometry pass (ms, log)")
    bottom.set_xticks(positions, order, rotation=30, ha="right")
    bottom.set_xlabel("model (camera position)")
    return figure_notes.finish_panels(fig, (top, bottom), rows,
                                      "pastyrik2016 Figs. 11-14: depth peeling vs dual depth peeling", paper=PAPER,
                                      paper_loc="upper right")


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
