"""What every paper plot shares: reading an oitbench CSV, choosing one clock,
the `extra` counters as columns, and a title naming device, resolution and
date (times are only comparable within one device)."""
import argparse
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import pandas as pd  # noqa: E402

from analysis.results_io import ResultsError, read_results, save_figure  # noqa: E402

NUMERIC = ["width", "height", "median_ms", "fragments", "max_depth_complexity", "mean_depth_complexity", "psi",
           "bytes_allocated", "fragments_stored", "passes"]


class NoData(Exception):
    """The CSV holds no row the plot can use; the message says which."""


def tokens(text):
    """'a=1 b=2' -> {'a': '1', 'b': '2'} (params, scene_params and extra are written this way)."""
    out = {}
    for item in str(text).split():
        key, _, value = item.partition("=")
        out[key] = value
    return out


def load(path, clock=None):
    """Successful rows of one CSV (or several, concatenated), numeric columns
    parsed, `extra` counters as extra_<name> columns, restricted to one clock
    (the given one, else the one most rows use: mixing clocks mixes devices'
    notions of time)."""
    paths = [path] if isinstance(path, str) else list(path)
    frames = [read_results(p, columns=["clock", "timestamp", "median_ms"]) for p in paths]
    runs = pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()
    if runs.empty or "status" not in runs:
        raise NoData(f"{', '.join(paths)}: no rows")
    runs = runs[runs["status"] == "ok"].copy()
    if runs.empty:
        raise NoData(f"{', '.join(paths)}: no successful runs")
    for column in NUMERIC:  # a column older CSVs lack is empty
        runs[column] = pd.to_numeric(runs[column], errors="coerce") if column in runs else float("nan")
    extra = runs["extra"].map(tokens) if "extra" in runs else pd.Series([{}] * len(runs), index=runs.index)
    for name in sorted({key for counters in extra for key in counters}):
        runs[f"extra_{name}"] = pd.to_numeric(extra.map(lambda c, n=name: c.get(n, "")), errors="coerce")
    if clock is None:
        clock = runs["clock"].value_counts().idxmax()
    runs = runs[runs["clock"] == clock]
    if runs.empty:
        raise NoData(f"{', '.join(paths)}: no successful runs with clock {clock}")
    runs["date"] = runs["timestamp"].str.slice(0, 10)
    return runs


def select(runs, technique=None, scene=None, params=None):
    """Rows of one technique/scene whose params contain every key=value of `params`."""
    keep = pd.Series(True, index=runs.index)
    if technique is not None:
        keep &= runs["technique"] == technique
    if scene is not None:
        keep &= runs["scene"] == scene
    for key, value in (params or {}).items():
        keep &= runs["params"].map(lambda p: tokens(p).get(key) == value)
    return runs[keep]


def title(runs, what):
    """`what` on a first line; device, resolution(s), clock and date(s) on the second."""
    sizes = sorted({(int(w), int(h)) for w, h in zip(runs["width"], runs["height"])})
    size_text = (f"{sizes[0][0]}x{sizes[0][1]}" if len(sizes) == 1
                 else f"{sizes[0][0]}x{sizes[0][1]}..{sizes[-1][0]}x{sizes[-1][1]}")
    dates = sorted(runs["date"].unique())
    date_text = dates[0] if len(dates) == 1 else f"{dates[0]}..{dates[-1]}"
    devices = ", ".join(sorted(runs["device"].unique()))
    # `what` wrapped at 110 characters: the narrowest figures (7.5 in at 8 pt)
    # hold about that many, and a longer title is cut off at both ends.
    what = "\n".join(textwrap.fill(line, 110) for line in what.split("\n"))
    return f"{what}\n{devices} | {size_text} | clock {', '.join(sorted(runs['clock'].unique()))} | {date_text}"


def stage_order(runs):
    """The stage names of `runs` in pipeline order: a run writes its stages
    in the order they first ran (docs/ARCHITECTURE.md, "Stages and timing"),
    so every stage comes after those that precede it in any run (each
    run_id, or each technique in a CSV without run ids); stages no run
    orders stay in the order they first appear in the CSV, as do stages
    whose runs disagree. `total` and the empty stage of a failed run are
    left out."""
    named = runs[(runs["stage"] != "total") & (runs["stage"].astype(str) != "")]
    first_seen = list(dict.fromkeys(named["stage"]))
    key = named["run_id"] if "run_id" in named and (named["run_id"] != "").all() else named["technique"]
    before = {stage: set() for stage in first_seen}
    for _, stages in named["stage"].groupby(key, sort=False):
        sequence = list(dict.fromkeys(stages))
        for i, stage in enumerate(sequence):
            before[stage].update(sequence[:i])
    order = []
    while len(order) < len(first_seen):
        left = [s for s in first_seen if s not in order]
        ready = [s for s in left if before[s] <= set(order)]
        order.append(ready[0] if ready else left[0])  # no stage ready: the runs disagree, take the CSV's order
    return order


def stage_table(runs, index):
    """Median ms of each stage per value of `index` (a column or list of
    columns), averaged over the rows sharing it (e.g. the views of a random
    camera set); columns in the CSV's stage order, then `total`."""
    table = runs.pivot_table(index=index, columns="stage", values="median_ms", aggfunc="mean")
    ordered = [s for s in stage_order(runs) if s in table.columns] + (["total"] if "total" in table.columns else [])
    return table[ordered]


def cli(description, draw, extra_arguments=None):
    """The shared command line: CSV(s) in, -o PNG out, --clock; `draw(runs,
    args)` returns the figure."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("csv", nargs="+")
    parser.add_argument("-o", "--out", required=True, help="PNG to write")
    parser.add_argument("--clock", default=None, help="gl or wall (default: the clock most rows use)")
    if extra_arguments:
        extra_arguments(parser)
    args = parser.parse_args()
    try:
        fig = draw(load(args.csv, args.clock), args)
        save_figure(fig, args.out, dpi=110)
    except (NoData, ResultsError, OSError) as e:
        sys.exit(f"{description.split(':')[0]}: {e}")
    print(f"wrote {args.out}")


def image_grid(directory, rows, title, panel=(2.4, 2.4)):
    """A figure of rendered PNGs from `directory`: `rows` is [(label,
    [(image name, caption), ...])], one row each, the label on its left;
    `panel`: inches per image (width, height)."""
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    width = max(len(items) for _, items in rows)
    with plt.rc_context({"axes.titlesize": 7, "axes.labelsize": 7}):
        fig, axes = plt.subplots(len(rows), width, figsize=(panel[0] * width, panel[1] * len(rows)), squeeze=False)
        for ax in axes.flat:
            ax.set_visible(False)
        for line, (label, items) in zip(axes, rows):
            for c, (name, caption) in enumerate(items):
                line[c].set_visible(True)
                line[c].imshow(mpimg.imread(os.path.join(directory, f"{name}.png")))
                line[c].set(xticks=[], yticks=[], title=caption, ylabel=label if c == 0 else "")
        fig.suptitle(title, fontsize=8)
        fig.tight_layout()
    return fig


def images_cli(description, draw_directory):
    """The command line of an image grid: a folder of renders (with its
    captions.json) in, -o PNG out; `draw_directory(folder)` returns the figure."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("images", help="folder with captions.json and the PNGs")
    parser.add_argument("-o", "--out", required=True)
    args = parser.parse_args()
    try:
        fig = draw_directory(args.images)
    except (NoData, FileNotFoundError) as e:
        sys.exit(f"{description.split(':')[0]}: {e}")
    save_figure(fig, args.out, dpi=110)
    print(f"wrote {args.out}")


def stacked_stages(ax, x, table, groups=None):
    """Cumulative stage times as stacked areas over x (the papers draw each
    stage's time on top of the preceding ones). `groups` maps an area label to
    the stages summed into it; by default one area per stage. Each area has
    the colour of its first stage. Returns the labels drawn, bottom to top."""
    if groups is None:
        groups = [(s, [s]) for s in table.columns if s != "total"]
    from analysis import presentation  # here: presentation imports this module

    labels, series, firsts = [], [], []
    for label, members in groups:
        present = [m for m in members if m in table.columns]
        if not present:
            continue
        labels.append(label)
        firsts.append(present[0])
        series.append(table[present].fillna(0.0).sum(axis=1).to_numpy())
    if not series:
        raise NoData("no stage rows besides total")
    # An area takes the colour of its first stage (presentation.stage_colours).
    colours = presentation.stage_colours(firsts)
    ax.stackplot(x, *series, labels=labels, colors=[colours[f] for f in firsts], alpha=0.85)
    return labels
