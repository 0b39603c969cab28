"""carnecky2013 Figures 9-13 as image grids of our renders.

The renders are `oitbench render` images that `analysis.reproduce` writes
to <out>/images/<name>.png (white background) with their captions in
captions.json; names start with the paper's figure (fig09_..., fig13_...).
One row per figure: Fig. 9's five diffusion configurations (eq. 9; eq. 9
with eq. 10; eq. 8; eq. 8 with eq. 11; eq. 8 with n = 100: its table,
analysis/figure_configs.py CARNECKY_FIG9), Figs. 10-13 constant
transparency against the illustration buffer's silhouettes and halos (and
the angle / normal variation modes of Fig. 11 and 13(b) where the build has
them). Text at presentation.READABLE sizes. Usage:
python3 -m analysis.carnecky_images IMAGES_DIR -o grid.png
"""
import argparse
import json
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common, presentation  # noqa: E402
from analysis.results_io import save_figure  # noqa: E402

FIGURES = {"fig09": "Fig. 9: diffusion (torus, a folded view)", "fig10": "Fig. 10: constant vs ours (spheres)",
           "fig11": "Fig. 11: transparency assignments (nested spheres)",
           "fig12": "Fig. 12: flow-like surface (concentric cylinders)", "fig13": "Fig. 13: jet engine"}


def draw_directory(directory):
    with open(os.path.join(directory, "captions.json")) as f:
        captions = json.load(f)
    present = {n: c for n, c in captions.items() if os.path.exists(os.path.join(directory, f"{n}.png"))}
    if not present:
        raise common.NoData(f"no rendered image of captions.json in {directory}")
    rows = [(figure, [n for n in present if n.startswith(figure + "_")]) for figure in FIGURES]
    rows = [(figure, names) for figure, names in rows if names]
    columns = max(len(names) for _, names in rows)
    with plt.rc_context(presentation.READABLE):
        fig, axes = plt.subplots(len(rows), columns, figsize=(2.6 * columns, 2.9 * len(rows)), squeeze=False)
        for line, (figure, names) in zip(axes, rows):
            for ax in line:
                ax.axis("off")
            for ax, name in zip(line, names):
                ax.imshow(mpimg.imread(os.path.join(directory, f"{name}.png")))
                ax.set_title(presentation.wrap(present[name]), fontsize=presentation.SMALLEST_POINTS)
            line[0].text(-0.05, 0.5, "\n".join(textwrap.wrap(FIGURES[figure], 30)), transform=line[0].transAxes,
                         rotation=90, ha="right", va="center", ma="center", fontsize=presentation.SMALLEST_POINTS)
        fig.suptitle("carnecky2013 Figs. 9-13 with our illustration buffer (oitbench render; 20 iterations, "
                     "silhouette + halo;\nFig. 9: its five columns, λγ = 0.1 in each)")
        fig.tight_layout(rect=(0, 0, 1, 1 - 0.45 / fig.get_figheight()))  # room for the two-line title
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("images", help="folder with captions.json and the PNGs")
    parser.add_argument("-o", "--out", required=True)
    args = parser.parse_args()
    try:
        fig = draw_directory(args.images)
    except (common.NoData, FileNotFoundError) as e:
        sys.exit(f"carnecky_images: {e}")
    save_figure(fig, args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
