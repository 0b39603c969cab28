"""murray2016 Figure 10: bucketed k-buffer stage times versus number of objects.

Scene: 32 stacked full-screen quads (`--scene quads --scene-set
objects=1,2,..,32`): the fragment count is fixed, only the number of distinct
object ids (hence buckets in use) changes. Stacked areas are the cumulative
stage times of `bucketed_kbuffer`; the dotted line is the total of its
brute-force variant (`buckets=off`), whose time should not depend on the
number of objects; the dashed line is a plain `kbuffer` (constant
transparency), the paper's "around 10 ms" reference.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common  # noqa: E402

TECHNIQUE = "bucketed_kbuffer"
# The paper's areas: everything that builds the buckets, then the three
# screen-space passes.
GROUPS = [("clear", ["clear"]), ("fill/sort/bucket/store", ["count", "fill", "sort", "bucket", "store"]),
          ("neighbors", ["neighbors"]), ("stylize", ["stylize"]), ("compose", ["compose"])]


def objects_of(rows):
    return rows["scene_params"].map(lambda p: int(common.tokens(p)["objects"]))


def totals_by_objects(rows):
    rows = rows[rows["stage"] == "total"].assign(objects=objects_of(rows[rows["stage"] == "total"]))
    return rows.groupby("objects")["median_ms"].mean().sort_index()


def draw(runs, args=None):
    quads = common.select(runs, scene="quads")
    brute = common.select(quads, TECHNIQUE, params={"buckets": "off"})
    bucketed = quads[(quads["technique"] == TECHNIQUE) & ~quads.index.isin(brute.index)]
    if bucketed.empty:
        raise common.NoData(f"no {TECHNIQUE} rows on the quads scene")
    table = common.stage_table(bucketed.assign(objects=objects_of(bucketed)), "objects").sort_index()
    fig, ax = plt.subplots(figsize=(7, 4.5))
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
    kbuffer = common.select(quads, "kbuffer")
    if not kbuffer.empty:
        line = totals_by_objects(kbuffer)
        ax.plot(line.index, line.to_numpy(), linestyle="--", color="grey", label="kbuffer alone, total", zorder=3)
    ax.set_xscale("log", base=2)
    ax.set_xticks(table.index.to_numpy(), [str(v) for v in table.index])
    ax.set_xlabel("number of objects (32 stacked quads)")
    ax.set_ylabel("cumulative time per frame (ms)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title(common.title(bucketed, "murray2016 Fig. 10: bucketed k-buffer vs number of objects"), fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
