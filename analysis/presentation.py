"""What makes a plot readable and honest, shared by plot_stages and pareto:
labels that name only the parameters a run changed from its technique's
defaults, one facet per scene configuration (runs of different scenes,
sizes, cameras, clocks or devices never share a bar or a point), text of at
least 9 pt at the saved size, and a vector copy (SVG, text kept as text)
beside every PNG.

The defaults are the build's own: `oitbench list --markdown` prints every
technique's parameters with their defaults from the registry, without GL.
The one visual identity of the plots is here too: technique_style gives
every registered technique its own colour, marker and hatch (the same in
every plot), stage_colours every stage of a plot its own colour."""
import collections
import os
import re
import subprocess
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import pandas as pd  # noqa: E402

from analysis.common import tokens  # noqa: E402
from analysis.results_io import save_figure  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OITBENCH = os.path.join(REPO, "build", "harness", "oitbench")

# Every text of a figure at 9 pt or more; figures are saved at their own
# size (no scaling), so these are the sizes a reader sees.
READABLE = {"font.size": 9, "axes.titlesize": 10, "axes.labelsize": 9, "xtick.labelsize": 9,
            "ytick.labelsize": 9, "legend.fontsize": 9, "legend.title_fontsize": 9, "figure.titlesize": 10}
SMALLEST_POINTS = 9
LABEL_WIDTH = 40  # characters of a label line; longer labels wrap at spaces


# Colour-blind-safe colours: Okabe & Ito's eight and seven of Paul Tol's
# "muted" set (its cyan and sand are left out: too close to Okabe-Ito's sky
# blue and yellow). Markers and hatches are unique too, so a technique is
# told apart in grey print and by readers who confuse two of the colours.
OKABE_ITO = {"blue": "#0072B2", "sky_blue": "#56B4E9", "bluish_green": "#009E73", "vermillion": "#D55E00",
             "orange": "#E69F00", "reddish_purple": "#CC79A7", "black": "#000000", "yellow": "#F0E442"}
TOL_MUTED = {"rose": "#CC6677", "indigo": "#332288", "green": "#117733", "wine": "#882255", "teal": "#44AA99",
             "olive": "#999933", "purple": "#AA4499", "cyan": "#88CCEE", "sand": "#DDCC77", "grey": "#BBBBBB"}
TechniqueStyle = collections.namedtuple("TechniqueStyle", "colour marker hatch")
# Every registered technique (algorithms/<id>/, `oitbench list`): the paper's
# four comparison techniques take the most distinct colours. A technique
# added to the build gets its line here (tests/analysis_plots_test.py checks
# that every listed technique has one and that no two share a colour, a
# marker or a hatch).
TECHNIQUE_STYLES = {
    "depth_peeling": TechniqueStyle(OKABE_ITO["blue"], "o", "//"),
    "dual_depth_peeling": TechniqueStyle(OKABE_ITO["sky_blue"], "s", "\\\\"),
    "linked_list": TechniqueStyle(OKABE_ITO["bluish_green"], "^", "xx"),
    "illustration_buffer": TechniqueStyle(OKABE_ITO["vermillion"], "D", ".."),
    "kbuffer": TechniqueStyle(OKABE_ITO["orange"], "v", "++"),
    "bucketed_kbuffer": TechniqueStyle(OKABE_ITO["reddish_purple"], "P", "oo"),
    "reference": TechniqueStyle(OKABE_ITO["black"], "*", ""),
    "unsorted": TechniqueStyle(OKABE_ITO["yellow"], "X", "--"),
    "linearized_fragment_buffer": TechniqueStyle(TOL_MUTED["green"], "h", "||"),
    "multi_layer_alpha_blending": TechniqueStyle(TOL_MUTED["indigo"], "<", "/"),
    "weighted_blended": TechniqueStyle(TOL_MUTED["rose"], ">", "\\\\\\"),
    "moment_oit": TechniqueStyle(TOL_MUTED["wine"], "p", "x"),
    "hybrid_transparency": TechniqueStyle(TOL_MUTED["teal"], "d", "."),
    "stochastic_transparency": TechniqueStyle(TOL_MUTED["olive"], "8", "+"),
    "adaptive_transparency": TechniqueStyle(TOL_MUTED["purple"], "H", "O"),
}
# A technique missing from the table (a build newer than this file): grey,
# its own marker, and stderr says so once.
UNLISTED_STYLE = TechniqueStyle("#777777", "1", "**")


def technique_style(technique):
    """The colour, marker and hatch of `technique` in every plot."""
    style = TECHNIQUE_STYLES.get(technique)
    if style is None:
        if technique not in _unlisted_told:
            _unlisted_told.add(technique)
            print(f"presentation: no style for technique '{technique}' (add it to TECHNIQUE_STYLES in "
                  f"analysis/presentation.py); drawn grey", file=sys.stderr)
        return UNLISTED_STYLE
    return style


_unlisted_told = set()

# Stage colours: each stage name has its own (so a stage reads the same in
# every plot); a stage the table does not know takes the first spare colour
# no other stage of the plot has. Tol's muted set and three of Okabe-Ito's.
STAGE_COLOURS = {"count": TOL_MUTED["cyan"], "clear": TOL_MUTED["grey"], "fill": TOL_MUTED["sand"],
                 "sort": TOL_MUTED["green"], "bucket": TOL_MUTED["olive"], "store": TOL_MUTED["teal"],
                 "neighbors": TOL_MUTED["rose"], "stylize_init": TOL_MUTED["purple"], "diffuse": TOL_MUTED["wine"],
                 "stylize": OKABE_ITO["vermillion"], "peel": OKABE_ITO["orange"], "compose": TOL_MUTED["indigo"]}
SPARE_STAGE_COLOURS = [OKABE_ITO["blue"], OKABE_ITO["sky_blue"], OKABE_ITO["bluish_green"], OKABE_ITO["reddish_purple"],
                       OKABE_ITO["yellow"], OKABE_ITO["black"], "#777777", "#DDDDDD"]


def stage_colours(stages):
    """{stage: colour} for the stages of one plot, no two alike; a plot with
    more unknown stages than spare colours is an error naming them."""
    colours = {s: STAGE_COLOURS[s] for s in stages if s in STAGE_COLOURS}
    spare = [c for c in SPARE_STAGE_COLOURS if c not in colours.values()]
    unknown = [s for s in dict.fromkeys(stages) if s not in colours]
    if len(unknown) > len(spare):
        raise ValueError(f"stages {', '.join(unknown)}: more stages without a colour than spare colours; add them "
                         f"to STAGE_COLOURS in analysis/presentation.py")
    colours.update(zip(unknown, spare))
    return colours


def parse_technique_table(markdown):
    """{technique: {parameter: default}} from the table `oitbench list
    --markdown` prints (its column `parameters (default, range)`: entries
    "`name` (default; range)", the default `empty` for an empty one)."""
    defaults, column = {}, None
    for line in markdown.splitlines():
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]
        if column is None:
            column = next((i for i, c in enumerate(cells) if c.startswith("parameters (default")), None)
            continue
        technique = re.fullmatch(r"`([^`]+)`", cells[0]) if len(cells) > column else None
        if technique:
            defaults[technique.group(1)] = {name: "" if value == "empty" else value
                                            for name, value in re.findall(r"`([^`]+)` \(([^;]*);", cells[column])}
    if column is None:
        raise ValueError("no 'parameters (default, range)' column in the technique table")
    return defaults


def technique_defaults(oitbench=None):
    """Every technique's parameter defaults as the build at `oitbench`
    declares them. None where no oitbench is given and none is built at
    build/harness/oitbench (stderr says that labels then omit only what all
    runs of a technique share); an oitbench given that does not answer is an
    error naming it."""
    path = oitbench or DEFAULT_OITBENCH
    if oitbench is None and not os.access(path, os.X_OK):
        print(f"no {path} to read parameter defaults from: labels show the parameters that differ between runs "
              f"of a technique (--oitbench names a build)", file=sys.stderr)
        return None
    try:
        listing = subprocess.run([path, "list", "--markdown"], capture_output=True, text=True, check=True,
                                 timeout=120).stdout
    except (OSError, subprocess.SubprocessError) as e:
        raise RuntimeError(f"cannot read parameter defaults from '{path} list --markdown': {e}") from e
    return parse_technique_table(listing)


def varying_params(runs):
    """Per row of `runs` (columns technique, params): its params reduced to
    the keys whose value differs between the rows of its technique."""
    parsed = runs["params"].map(tokens)
    reduced = {}
    for _, rows in parsed.groupby(runs["technique"]):
        values = list(rows)
        varying = {key for v in values for key in v if len({u.get(key) for u in values}) > 1}
        for index, v in zip(rows.index, values):
            reduced[index] = " ".join(f"{k}={v[k]}" for k in v if k in varying)
    return pd.Series(reduced, dtype=object).reindex(runs.index)


def non_default_params(runs, defaults):
    """Per row of `runs`: its params less those at their technique's default
    (`defaults` as technique_defaults returns it; a parameter the build does
    not know is kept)."""
    missing = object()
    return pd.Series([" ".join(f"{k}={v}" for k, v in tokens(p).items()
                               if defaults.get(t, {}).get(k, missing) != v)
                      for t, p in zip(runs["technique"], runs["params"])], index=runs.index, dtype=object)


def short_params(runs, defaults):
    """non_default_params where the defaults are known, else varying_params."""
    return varying_params(runs) if defaults is None else non_default_params(runs, defaults)


def run_labels(runs, defaults):
    """Per row of `runs`: its technique and every parameter off the
    technique's default ("kbuffer k=16 tail=blend"), the one label of a run
    in every plot (short_params: the parameters that differ between a
    technique's runs where no defaults are known)."""
    short = short_params(runs, defaults)
    return runs["technique"] + short.map(lambda s: f" {s}" if s else "")


def label_note(defaults):
    """What a figure's labels leave out, for its caption."""
    return ("labels: parameters off their defaults" if defaults is not None
            else "labels: parameters that differ between a technique's runs")


def wrap(label):
    """A label over several lines of at most LABEL_WIDTH characters."""
    return "\n".join(textwrap.wrap(label, LABEL_WIDTH, break_on_hyphens=False)) or label


def camera_set(camera):
    """The view set a camera belongs to: `random:8:1@3` -> `random:8:1`;
    other cameras are their own set."""
    return str(camera).split("@", 1)[0]


FACET_COLUMNS = ["device", "platform", "scene", "scene_params", "size", "camera_set", "clock"]


def with_facets(runs):
    """`runs` with the columns that name a facet: size (WxH) and
    camera_set, beside device, platform, scene, scene_params and clock."""
    runs = runs.copy()
    runs["size"] = runs["width"].astype(str) + "x" + runs["height"].astype(str)
    runs["camera_set"] = runs["camera"].map(camera_set)
    return runs


def facet_title(key, runs):
    """One line naming a facet: scene and all its parameters, size, the
    camera unless `default`, and the clock and device where the plot holds
    several of them."""
    values = dict(zip(FACET_COLUMNS, key))
    parts = [f"{values['scene']} {values['scene_params']}".strip(), values["size"]]
    if values["camera_set"] != "default":
        parts.append(f"camera {values['camera_set']}")
    if runs["clock"].nunique() > 1:
        parts.append(f"clock {values['clock']}")
    if runs[["device", "platform"]].drop_duplicates().shape[0] > 1:
        parts.append(f"{values['device']} ({values['platform']})")
    return " | ".join(parts)


def caption(runs, what, defaults):
    """Two lines: `what` with the device(s), clock(s) and date(s) the rows
    come from; then what the labels leave out."""
    devices = ", ".join(sorted(runs["device"].unique()))
    clocks = ", ".join(sorted(runs["clock"].unique()))
    dates = sorted(runs["timestamp"].astype(str).str.slice(0, 10).unique())
    date_text = dates[0] if len(dates) == 1 else f"{dates[0]}..{dates[-1]}"
    return f"{what} on {devices}, clock {clocks}, {date_text}\n{label_note(defaults)}"


def vector_path(png):
    return os.path.splitext(png)[0] + ".svg"


def save_png_and_svg(fig, png, dpi):
    """`png` and, beside it, the same figure as SVG, each written whole
    (results_io.save_figure). Returns the paths; a file replaced is named in
    the note printed, so no plot is overwritten silently."""
    if os.path.splitext(png)[1].lower() != ".png":
        raise ValueError(f"'{png}': the plot is written as PNG (and SVG beside it); name a .png file")
    paths = [png, vector_path(png)]
    replaced = [p for p in paths if os.path.exists(p)]
    save_figure(fig, png, dpi=dpi)
    with matplotlib.rc_context({"svg.fonttype": "none"}):  # text stays text: searchable, checkable
        save_figure(fig, paths[1])
    note = f" (replaced {', '.join(replaced)})" if replaced else ""
    print(f"wrote {paths[0]} and {paths[1]}{note}")
    return paths
