"""pastyrik2016 section 5: does the complexity coverage Psi drive the time?

The paper finds that "only the Illustration buffer is really affected by the
complexity coverage Psi, which is caused by its FindNeighbours stage". Here
scenes whose Psi spans 0..1 (stacked quads: 1; single surfaces: near 0) are
timed with the illustration buffer and the linked lists; the time is divided
by the fragments, so that what is left is what Psi could explain. Top: total
ns per fragment against Psi; bottom: the illustration buffer's neighbour
stage per fragment. The legend gives each series' Spearman rank correlation.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common, figure_notes, presentation  # noqa: E402

TECHNIQUES = ["illustration_buffer", "linked_list"]
PAPER = ["pastyrik2016 (GTX 660): only the illustration buffer",
         "is affected by Psi, through FindNeighbours"]


def per_fragment(rows, stage):
    part = rows[(rows["stage"] == stage) & (rows["fragments"] > 0)]
    return part.assign(ns=part["median_ms"] * 1e6 / part["fragments"]).sort_values("psi")


def plot_series(ax, part, technique, label):
    rho = part[["ns", "psi"]].corr(method="spearman").iloc[0, 1] if len(part) > 2 else float("nan")
    style = presentation.technique_style(technique)
    ax.plot(part["psi"], part["ns"], marker=style.marker, color=style.colour, linestyle="",
            label=f"{label} (Spearman {rho:.2f})")
    for _, row in part.iterrows():
        ax.annotate(row["scene"], (row["psi"], row["ns"]), fontsize=5, xytext=(3, 2), textcoords="offset points")


def draw(runs, args=None):
    rows = figure_notes.quiet_runs(runs[runs["technique"].isin(TECHNIQUES)])
    if rows.empty or "psi" not in rows:
        raise common.NoData("no illustration_buffer or linked_list rows with psi")
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for technique in [t for t in TECHNIQUES if t in set(rows["technique"])]:
        plot_series(top, per_fragment(rows[rows["technique"] == technique], "total"), technique, f"{technique}, total")
    neighbors = per_fragment(rows[rows["technique"] == "illustration_buffer"], "neighbors")
    if not neighbors.empty:
        plot_series(bottom, neighbors, "illustration_buffer", "illustration_buffer, neighbors stage")
    top.set_yscale("log")
    top.set_ylabel("total ns per fragment (log)")
    bottom.set_ylabel("neighbour stage ns per fragment")
    bottom.set_xlabel("complexity coverage Psi (share of pixels with a list > 2/3 of the longest)")
    return figure_notes.finish_panels(fig, (top, bottom), rows, "pastyrik2016 section 5: time per fragment against Psi",
                                      legend_loc="best", paper=PAPER, paper_loc="lower left")


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
