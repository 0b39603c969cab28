"""Time per fragment of every technique versus depth complexity.

Stacked quads with a growing number of layers (`--scene quads --scene-set
layers=4,..,64`): every pixel holds exactly `layers` fragments, so the total
time divided by the fragment count shows how each technique's cost per
fragment grows with list length (sorting, peeling passes, k-buffer
overflow). The k-buffers run at k=auto (k = the view's depth complexity,
nothing dropped); a run that still dropped fragments (a fixed k below the
layers) is drawn with an x and named in the legend.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import pandas as pd  # noqa: E402

from analysis import common, presentation  # noqa: E402


def draw(runs, args=None):
    rows = runs[(runs["stage"] == "total") & (runs["technique"] != "reference") & (runs["fragments"] > 0)]
    if rows.empty:
        raise common.NoData("no total rows with fragments")
    # Labels name the parameters off the defaults (args.defaults, as
    # analysis.reproduce passes them), else those that differ between a
    # technique's runs.
    rows = rows.assign(label=presentation.run_labels(rows, getattr(args, "defaults", None)),
                       ns_per_fragment=rows["median_ms"] * 1e6 / rows["fragments"])
    fig, ax = plt.subplots(figsize=(8.5, 4.8))
    dropped = pd.to_numeric(rows.get("fragments_dropped", pd.Series(0, index=rows.index)), errors="coerce").fillna(0)
    rows = rows.assign(dropped=dropped > 0)
    dashes = ["-", "--", ":", "-."]
    seen = {}
    for label, series in rows.groupby("label"):
        technique = series["technique"].iloc[0]
        style = presentation.technique_style(technique)
        linestyle = dashes[seen.setdefault(technique, 0) % len(dashes)]  # a technique's second run config: dashed
        seen[technique] += 1
        line = series.groupby("max_depth_complexity")["ns_per_fragment"].mean().sort_index()
        drops = series.groupby("max_depth_complexity")["dropped"].any().sort_index()
        suffix = " (x: fragments dropped)" if drops.any() else ""
        (drawn,) = ax.plot(line.index, line.to_numpy(), marker=style.marker, markersize=4, color=style.colour,
                           linestyle=linestyle, label=presentation.wrap(label + suffix))
        if drops.any():
            ax.plot(line.index[drops.to_numpy()], line.to_numpy()[drops.to_numpy()], linestyle="", marker="x",
                    markersize=8, color=drawn.get_color())
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("depth complexity (fragments per pixel, longest list)")
    ax.set_ylabel("total time per fragment (ns, log)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # lines fill the whole axes
    scenes = ", ".join(sorted(rows["scene"].unique()))
    ax.set_title(common.title(rows, f"time per fragment vs depth complexity ({scenes})"), fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
