"""carnecky2013 Figure 14: illustration buffer stage times versus number of fragments.

A resolution sweep of one surface (the paper: a toroid, 128^2 .. 2048^2)
under a random camera set: each point is one resolution, its x the number of
fragments and its stage times averaged over the views (fragments differ per
view, so they are averaged too). Stacked areas are cumulative, as the paper's
lines are, named by the paper's passes: clear, fill, sort, connect (our
neighbors + stylize_init: the neighbour search and the fields' initial
values and boundary rules), solve (our diffuse: ONE diffusion iteration in
the sweep, as the paper's solve pass) and compose. The paper finds every
pass linear in the fragment count.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common, figure_notes  # noqa: E402

TECHNIQUE = "illustration_buffer"
# Our stage -> the paper's pass (carnecky2013 section 7: "fill (Section 4.2),
# sort (4.3), connect (4.4, 5.2, and 5.3), solve (5.4) and compose (5.5)";
# clear clears the buffer). connect is the neighbour search (4.4) and the
# fields' initial values and boundary rules (5.2, 5.3), which are our
# `neighbors` and `stylize_init`; solve is one diffusion iteration (5.4),
# our `diffuse` at iterations=1. `count` is storage=linearized's counting
# pass, the clear of its buffer. A CSV written before stylize was split has
# one `stylize` stage holding both the initial values and the iterations:
# it is drawn as an area of its own, named so.
# (the paper's pass, our stages); a label names the stages the CSV holds.
PAPER_PASSES = [("clear", ["clear", "count"]), ("fill", ["fill"]), ("sort", ["sort"]),
                ("connect", ["neighbors", "stylize_init"]), ("solve", ["diffuse"]),
                ("connect 5.2-5.3 + solve, older CSV", ["stylize", "init"]), ("compose", ["compose"])]
PATH_KEYS = ["iterations", "neighbors", "storage", "diffusion", "skip_converged", "sort"]
PAPER_FIG14 = ["carnecky2013 (GeForce 470, 1000 random views):",
               "every pass linear in the fragments; solve = one",
               "diffusion iteration (10-50 in practice)"]
PAPER_FIG15 = ["carnecky2013 (GeForce 470, 1024^2):",
               "fill grows linearly with a non-zero intercept;",
               "all other passes independent of the geometry"]


def passes(table):
    """PAPER_PASSES, then any stage of the CSV outside them (before compose)."""
    grouped = {s for _, members in PAPER_PASSES for s in members}
    others = [s for s in table.columns if s not in grouped and s != "total"]
    named = []
    for name, members in PAPER_PASSES:
        present = [m for m in members if m in table.columns]
        # "fill" stays "fill"; "connect" becomes "connect (neighbors + stylize_init)".
        label = name if present == [name] or not present else f"{name} ({' + '.join(present)})"
        named.append((label, members))
    return named[:-1] + [(s, [s]) for s in others] + named[-1:]


def scaling_figure(runs, key, x_column, x_label, what, paper):
    """Shared by Fig. 14 and 15: group the technique's rows by `key` (the swept
    quantity), x = mean of `x_column` over each group's views."""
    rows = figure_notes.quiet_runs(common.select(runs, TECHNIQUE))
    if rows.empty:
        raise common.NoData(f"no {TECHNIQUE} rows")
    if x_column not in rows:
        raise common.NoData(f"no {x_column} column (CSV written before oitbench recorded it?)")
    rows = rows.assign(point=key(rows))
    x = rows.groupby("point")[x_column].mean()
    table = common.stage_table(rows, "point")
    order = x.sort_values().index
    fig, ax = plt.subplots(figsize=(8.5, 4.8))
    common.stacked_stages(ax, x.loc[order].to_numpy(), table.loc[order], passes(table))
    if "total" in table:
        ax.plot(x.loc[order].to_numpy(), table.loc[order, "total"].to_numpy(), color="black", marker="o",
                markersize=3, linewidth=1, label="total")
    ax.set_xlabel(x_label)
    ax.set_ylabel("cumulative time per frame (ms)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left")
    figure_notes.paper_box(ax, paper)
    views = rows.groupby("point")["camera"].nunique().max()
    # The knobs that decide whether the run took the paper's path
    # (figure_configs.CARNECKY), as the rows record them.
    path = [f"{key}={','.join(values)}" for key in PATH_KEYS
            if (values := sorted({common.tokens(p)[key] for p in rows["params"] if key in common.tokens(p)}))]
    return figure_notes.finish(fig, ax, rows, f"{what}\n{rows['scene'].iloc[0]}, mean over {views} camera view(s), "
                                              f"{' '.join(path)}")


def draw(runs, args=None):
    return scaling_figure(runs, lambda r: r["width"] * r["height"], "fragments", "number of fragments",
                          "carnecky2013 Fig. 14: illustration buffer vs fragments (resolution sweep)", PAPER_FIG14)


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
