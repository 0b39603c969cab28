"""pastyrik2016 Figure 8: illustration buffer stage times per model, models sorted by total.

One line per stage, each including the stages before it (the paper's
cumulative reading), over the models of `--scene model --scene-set
name=...` ordered by the total time per frame.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common  # noqa: E402

TECHNIQUE = "illustration_buffer"


def model_rows(runs, technique=TECHNIQUE):
    rows = common.select(runs, technique, scene="model")
    if rows.empty:
        raise common.NoData(f"no {technique} rows on the model scene")
    return rows.assign(model=rows["scene_params"].map(lambda p: common.tokens(p).get("name", p)))


def models_by_total(rows):
    """Model names, fastest total first (the paper's horizontal axis)."""
    totals = rows[rows["stage"] == "total"].groupby("model")["median_ms"].mean()
    return list(totals.sort_values().index)


def draw(runs, args=None):
    rows = model_rows(runs)
    order = models_by_total(rows)
    table = common.stage_table(rows, "model").loc[order]
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    positions = range(len(order))
    cumulative = 0.0
    for stage in [s for s in table.columns if s != "total"]:
        cumulative = cumulative + table[stage].fillna(0.0)
        ax.plot(positions, cumulative.to_numpy(), marker="o", markersize=3, label=stage)
    if "total" in table:
        ax.plot(positions, table["total"].to_numpy(), color="black", linestyle="--", marker="s", markersize=3,
                label="total")
    ax.set_xticks(list(positions), order, rotation=30, ha="right")
    ax.set_xlabel("model (sorted by total time)")
    ax.set_ylabel("cumulative time per frame (ms)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title(common.title(rows, "pastyrik2016 Fig. 8: illustration buffer stages per model"), fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
