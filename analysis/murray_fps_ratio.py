"""murray2016 Figures 1, 8, 9: frame rate of OIT against mean curvature transparency.

The paper quotes frame rates of the dual-pass k-buffer with constant
transparency (OIT) and of its stylised bucketed k-buffer on its models, 16
layers at 1000x1000 (1200x800 for the bike). Here the same ratio, OIT frame
rate / stylised frame rate = bucketed_kbuffer total / kbuffer total (k = 16),
per model (and per size where the CSV holds both the paper's 1000x1000 and
its Fig. 8's 1200x800), beside the paper's ratios, once per slot layout the
CSV holds: the paper's (slot_layout=paper: 8-byte k-buffer slots, 128-bit
bucketed ones) and ours (slot_layout=full: 24 and 20 bytes), each ratio
taken within one layout. The legend says which neighbour search the
stylised runs used (figure_configs pins the paper's bucket query).
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from analysis import common, figure_notes, presentation  # noqa: E402
from analysis.pastyrik_fig8 import model_rows  # noqa: E402

# (figure, OIT fps, stylised fps) as the paper's captions state them.
PAPER_FPS = [("Fig. 1 (1000^2)", 64, 24), ("Fig. 8(a,b) bike (1200x800)", 120, 45),
             ("Fig. 8(c,d) powerplant (1000^2)", 20, 10), ("Fig. 9 (1000^2)", 50, 20)]


# slot_layout -> what the legend calls it (runs from before the parameter: ours).
LAYOUTS = {"paper": "the paper's slots (8 B k-buffer, 16 B bucketed)", "full": "our slots (24 B k-buffer, 20 B bucketed)"}


def ratios(runs):
    """The rows and, per slot layout, the ratio per model (and per size
    where the rows hold several: the paper's 1000x1000 and its Fig. 8's
    1200x800; the index names the model, with the size after it then)."""
    rows = model_rows(runs, None)
    rows = rows[(rows["stage"] == "total") & rows["technique"].isin(["kbuffer", "bucketed_kbuffer"])]
    sizes = rows["width"].astype(int).astype(str) + "x" + rows["height"].astype(int).astype(str)
    rows = rows.assign(point=rows["model"] + ((" " + sizes) if sizes.nunique() > 1 else ""),
                       layout=rows["params"].map(lambda p: common.tokens(p).get("slot_layout", "full")))
    out = {}
    for layout in [l for l in LAYOUTS if l in set(rows["layout"])]:
        table = rows[rows["layout"] == layout].pivot_table(index="point", columns="technique", values="median_ms")
        if "kbuffer" in table and "bucketed_kbuffer" in table:
            out[layout] = (table["bucketed_kbuffer"] / table["kbuffer"]).dropna()
    if not out:
        raise common.NoData("no kbuffer and bucketed_kbuffer total rows of one slot layout on the models")
    return rows, out


def variant(rows):
    """Which neighbour search the stylised runs used: the paper's bucket
    query or our default merge search (params of the CSV)."""
    searches = sorted({common.tokens(p).get("neighbor_search", "?") for p in
                       rows.loc[rows["technique"] == "bucketed_kbuffer", "params"]})
    return f"neighbor_search={','.join(searches)}"


def draw(runs, args=None):
    rows, by_layout = ratios(runs)
    points = sorted(set().union(*(r.index for r in by_layout.values())),
                    key=lambda p: min(r.get(p, np.inf) for r in by_layout.values()))
    fig, ax = plt.subplots(figsize=(max(9.0, 2.0 + 0.42 * len(points)), 5))
    positions = np.arange(len(points))
    width = 0.8 / len(by_layout)
    colour = presentation.technique_style("bucketed_kbuffer").colour
    for i, (layout, ratio) in enumerate(by_layout.items()):
        ax.bar(positions + (i - (len(by_layout) - 1) / 2) * width, ratio.reindex(points).to_numpy(), width,
               color=colour, alpha=1.0 if layout == "paper" else 0.45,
               label=f"ours, {LAYOUTS[layout]}: stylised time / OIT time")
    for i, (figure, oit, stylised) in enumerate(PAPER_FPS):
        ax.axhline(oit / stylised, color="black", linestyle=["--", ":", "-.", (0, (5, 1, 1, 1))][i % 4], linewidth=1,
                   label=f"paper {figure}: {oit}/{stylised} fps = {oit / stylised:.2f}")
    ax.set_xticks(positions, points, rotation=30, ha="right")
    ax.set_ylabel("OIT fps / stylised fps")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left", title=f"bucketed_kbuffer {variant(rows)}", title_fontsize=7)
    return figure_notes.finish(fig, ax, rows,
                               "murray2016 Figs. 1/8/9: cost of mean curvature transparency over OIT (k=16)")


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
