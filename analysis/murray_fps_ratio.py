"""murray2016 Figures 1, 8, 9: frame rate of OIT against mean curvature transparency.

The paper quotes frame rates of the dual-pass k-buffer with constant
transparency (OIT) and of its stylised bucketed k-buffer on its models, 16
layers at 1000x1000 (1200x800 for the bike). Here the same ratio, OIT frame
rate / stylised frame rate = bucketed_kbuffer total / kbuffer total (k = 16),
per model, beside the paper's ratios.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from analysis import common, figure_notes  # noqa: E402
from analysis.pastyrik_fig8 import model_rows  # noqa: E402

# (figure, OIT fps, stylised fps) as the paper's captions state them.
PAPER_FPS = [("Fig. 1 (1000^2)", 64, 24), ("Fig. 8(a,b) bike (1200x800)", 120, 45),
             ("Fig. 8(c,d) powerplant (1000^2)", 20, 10), ("Fig. 9 (1000^2)", 50, 20)]


def ratios(runs):
    rows = model_rows(runs, None)
    rows = rows[(rows["stage"] == "total") & rows["technique"].isin(["kbuffer", "bucketed_kbuffer"])]
    table = rows.pivot_table(index="model", columns="technique", values="median_ms")
    if "kbuffer" not in table or "bucketed_kbuffer" not in table:
        raise common.NoData("no kbuffer and bucketed_kbuffer total rows on the models")
    return rows, (table["bucketed_kbuffer"] / table["kbuffer"]).dropna().sort_values()


def draw(runs, args=None):
    rows, ratio = ratios(runs)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    positions = np.arange(len(ratio))
    ax.bar(positions, ratio.to_numpy(), 0.6, color="tab:blue", label="ours: stylised time / OIT time")
    for i, (figure, oit, stylised) in enumerate(PAPER_FPS):
        ax.axhline(oit / stylised, color=f"C{i + 1}", linestyle="--", linewidth=1,
                   label=f"paper {figure}: {oit}/{stylised} fps = {oit / stylised:.2f}")
    ax.set_xticks(positions, list(ratio.index), rotation=30, ha="right")
    ax.set_ylabel("OIT fps / stylised fps")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left")
    return figure_notes.finish(fig, ax, rows,
                               "murray2016 Figs. 1/8/9: cost of mean curvature transparency over OIT (k=16)")


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
