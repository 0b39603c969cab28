"""murray2016 Figure 10: bucketed k-buffer stage times versus number of objects.

Scene: 32 stacked full-screen quads (`--scene quads --scene-set
objects=1,2,..,32`): the fragment count is fixed, only the number of distinct
object ids (hence buckets in use) changes. Stacked areas are the cumulative
stage times of `bucketed_kbuffer`; the dotted line is the total of its
brute-force variant (`buckets=off`), whose time should not depend on the
number of objects; the dashed line is a plain `kbuffer` (constant
transparency), the paper's "around 10 ms" reference; the dash-dotted line,
where the runs have it, is the total with the merge search
(`neighbor_search=merge`, not in the paper). A second panel draws the total
and each stage on its own (not cumulative), bucketed solid, brute force
dotted and the merge search's neighbour stage dash-dotted, so the stage the
buckets change can be read off.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common, figure_notes, presentation  # noqa: E402

TECHNIQUE = "bucketed_kbuffer"
# The paper's areas: everything that builds the buckets, then the three
# screen-space passes.
GROUPS = [("clear", ["clear"]), ("fill/sort/bucket/store", ["count", "fill", "sort", "bucket", "store"]),
          ("neighbors", ["neighbors"]), ("stylize", ["stylize"]), ("compose", ["compose"])]
PAPER = ["murray2016 (GTX 980, 512x512, 32 layers, k = 32):",
         "k-buffer alone ~10 ms; bucketed = brute force at 1 object,",
         "half of it from 6 buckets on, a fifth with many objects"]


def objects_of(rows):
    return rows["scene_params"].map(lambda p: int(common.tokens(p)["objects"]))


def totals_by_objects(rows):
    rows = rows[rows["stage"] == "total"].assign(objects=objects_of(rows[rows["stage"] == "total"]))
    return rows.groupby("objects")["median_ms"].mean().sort_index()


def stage_lines(ax, rows, linestyle, suffix):
    """Each stage's own median (and the total, black) over the object counts."""
    table = common.stage_table(rows.assign(objects=objects_of(rows)), "objects").sort_index()
    colours = presentation.stage_colours([s for s in table.columns if s != "total"])
    for stage in table.columns:
        colour = "black" if stage == "total" else colours[stage]
        ax.plot(table.index, table[stage].to_numpy(), linestyle=linestyle, marker="o", markersize=2.5,
                color=colour, label=f"{stage}{suffix}")


def draw(runs, args=None):
    quads = figure_notes.quiet_runs(common.select(runs, scene="quads"))
    brute = common.select(quads, TECHNIQUE, params={"buckets": "off"})
    merge = common.select(quads, TECHNIQUE, params={"neighbor_search": "merge"})
    bucketed = quads[(quads["technique"] == TECHNIQUE) & ~quads.index.isin(brute.index) & ~quads.index.isin(merge.index)]
    if bucketed.empty:
        raise common.NoData(f"no {TECHNIQUE} rows on the quads scene")
    table = common.stage_table(bucketed.assign(objects=objects_of(bucketed)), "objects").sort_index()
    fig, (ax, own) = plt.subplots(1, 2, figsize=(12, 4.8))
    # A stage outside the paper's groups still gets an area (before compose),
    # so the stack always adds up to the technique's stages.
    grouped = {stage for _, members in GROUPS for stage in members}
    others = [s for s in table.columns if s not in grouped and s != "total"]
    groups = GROUPS[:-1] + ([("+".join(others), others)] if others else []) + GROUPS[-1:]
    common.stacked_stages(ax, table.index.to_numpy(), table, groups)
    if not brute.empty:
        line = totals_by_objects(brute)
        ax.plot(line.index, line.to_numpy(), linestyle=":", color="black", linewidth=2,
                label="brute force (buckets=off), total", zorder=3)
    if not merge.empty:
        line = totals_by_objects(merge)
        ax.plot(line.index, line.to_numpy(), linestyle="-.", color="black", linewidth=1.5,
                label="merge search (neighbor_search=merge), total", zorder=3)
    kbuffer = common.select(quads, "kbuffer")
    if not kbuffer.empty:
        line = totals_by_objects(kbuffer)
        ax.plot(line.index, line.to_numpy(), linestyle="--", color="grey", label="kbuffer alone, total", zorder=3)
    for axes in (ax, own):
        axes.set_xscale("log", base=2)
        axes.set_xticks(table.index.to_numpy(), [str(v) for v in table.index])
        axes.set_xlabel("number of objects (32 stacked quads)")
    ax.set_ylabel("cumulative time per frame (ms)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left")
    figure_notes.paper_box(ax, PAPER)
    stage_lines(own, bucketed, "-", "")
    if not brute.empty:
        stage_lines(own, brute, ":", " (brute force)")
    if not merge.empty:
        neighbors = merge[merge["stage"] == "neighbors"]
        line = neighbors.assign(objects=objects_of(neighbors)).groupby("objects")["median_ms"].mean().sort_index()
        own.plot(line.index, line.to_numpy(), linestyle="-.", marker="o", markersize=2.5, color="black",
                 label="neighbors (merge search)")
    own.set_yscale("log")
    own.set_ylabel("time per frame of each stage (ms, log)")
    own.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.01, 0.5))
    own.set_title("each stage on its own: bucketed solid, brute force dotted, merge dash-dotted", fontsize=8)
    return figure_notes.finish(fig, ax, bucketed, "murray2016 Fig. 10: bucketed k-buffer vs number of objects",
                               noisy_rows=quads)


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
