"""What the papers' figures add to a plot beyond the data: the paper's own
numbers beside ours, and which runs were measured on a busy machine."""
import textwrap

import pandas as pd

from analysis import common

# Columns that tell one run configuration from another (camera and size
# included): the runs of one key are repeats of one measurement.
RUN_KEY = ["technique", "params", "scene", "scene_params", "camera", "width", "height"]


def quiet_runs(rows):
    """`rows` without the noisy runs of a configuration that also has a quiet
    run (`analysis.reproduce --rerun-noisy` ran it again): a configuration
    measured only on a busy machine keeps its noisy rows (and the plot says
    so, noisy_note)."""
    if "noisy" not in rows or rows.empty:
        return rows
    noisy = rows["noisy"].astype(str) == "true"
    quiet_keys = set(map(tuple, rows.loc[~noisy, RUN_KEY].astype(str).to_numpy()))
    keys = pd.Series(list(map(tuple, rows[RUN_KEY].astype(str).to_numpy())), index=rows.index)
    return rows[~(noisy & keys.isin(quiet_keys))]


def noisy_note(rows):
    """'' or ', N of M runs noisy (other processes > 25% of the cores)'."""
    if "noisy" not in rows or rows.empty:
        return ""
    runs = rows.drop_duplicates(subset=RUN_KEY + (["run_id"] if "run_id" in rows else []))
    noisy = int((runs["noisy"].astype(str) == "true").sum())
    return f", {noisy} of {len(runs)} runs noisy (other load > 25%)" if noisy else ""


def tie_break(params):
    """A peeling run's tie_break ('' where its params do not say)."""
    return common.tokens(params).get("tie_break", "")


def canonical_peels(rows):
    """`rows` with each peeling technique's runs at tie_break=submission
    only (the canonical peel, figure_configs.PEELING_CANONICAL), where the
    rows hold that variant; other techniques' rows untouched. Figures that
    show one bar or line per technique compare the canonical peels."""
    variant = rows["params"].map(tie_break)
    canonical = set(rows.loc[variant == "submission", "technique"])
    return rows[~rows["technique"].isin(canonical) | (variant == "submission")]


def paper_box(ax, lines, loc="lower right"):
    """The paper's claims as a small text box inside the axes."""
    corners = {"lower right": (0.98, 0.02, "right", "bottom"), "upper right": (0.98, 0.98, "right", "top"),
               "upper left": (0.02, 0.98, "left", "top"), "lower left": (0.02, 0.02, "left", "bottom")}
    x, y, ha, va = corners[loc]
    ax.text(x, y, "\n".join(lines), transform=ax.transAxes, ha=ha, va=va, fontsize=6,
            bbox=dict(boxstyle="round", facecolor="lightyellow", alpha=0.9))


def finish(fig, ax, rows, what, noisy_rows=None, paper=None, paper_loc="lower right"):
    """Titles `ax` (common.title of `rows`, `what` followed by the noisy_note
    of `noisy_rows`, by default `rows`), puts the `paper` lines in a box at
    `paper_loc` of `ax` when given, lays `fig` out and returns it: how every
    paper figure ends."""
    if paper is not None:
        paper_box(ax, paper, loc=paper_loc)
    noisy = noisy_note(rows if noisy_rows is None else noisy_rows)
    # Wrapped to the figure's width: an 8 pt character is about a fifteenth
    # of an inch, and a title longer than the figure is cut off at both ends.
    width = max(40, int(fig.get_figwidth() * 15))
    text = "\n".join(textwrap.fill(line, width) for line in common.title(rows, what + noisy).split("\n"))
    ax.set_title(text, fontsize=8)
    fig.tight_layout()
    return fig


def finish_panels(fig, panels, rows, what, legend_loc="upper left", **finish_options):
    """`finish` for a figure of panels that share its runs: a legend in each
    of `panels` at `legend_loc`, the title (and paper box) on the first."""
    for ax in panels:
        ax.legend(fontsize=7, loc=legend_loc)
    return finish(fig, panels[0], rows, what, **finish_options)
