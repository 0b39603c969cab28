"""pastyrik2016 section 4.3: memory against fragments per technique.

Every technique's `bytes_allocated` (GPU memory it owns) against the
fragments of the view, one point per model and camera position, with the
paper's illustration buffer formula: 208 bytes per fragment plus 96 bits per
pixel (its Suspension 2: 1,900,548 fragments at 600x600, about 397 MB).
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from analysis import common, figure_notes, presentation  # noqa: E402
from analysis.pastyrik_fig8 import model_rows  # noqa: E402

BYTES_PER_FRAGMENT, BYTES_PER_PIXEL = 208, 12
PAPER = ["pastyrik2016: 208 B per fragment + 96 bits per pixel;",
         "Suspension 2, 1.9 M fragments at 600x600: ~397 MB"]
SHOWN = ["illustration_buffer", "linked_list", "reference", "kbuffer", "bucketed_kbuffer", "depth_peeling",
         "dual_depth_peeling"]


def paper_bytes(fragments, pixels):
    return BYTES_PER_FRAGMENT * np.asarray(fragments, dtype=float) + BYTES_PER_PIXEL * np.asarray(pixels, dtype=float)


def draw(runs, args=None):
    rows = model_rows(runs, None)
    rows = rows[(rows["stage"] == "total") & (rows["bytes_allocated"] > 0) & (rows["fragments"] > 0)]
    if rows.empty:
        raise common.NoData("no total rows with bytes_allocated and fragments on the models")
    fig, ax = plt.subplots(figsize=(8, 5))
    for technique in [t for t in SHOWN if t in set(rows["technique"])]:
        part = rows[rows["technique"] == technique].sort_values("fragments")
        style = presentation.technique_style(technique)
        ax.plot(part["fragments"], part["bytes_allocated"] / 2**20, marker=style.marker, markersize=4, linestyle="",
                color=style.colour, label=technique)
    fragments = np.array(sorted(rows["fragments"]))
    pixels = int(rows["width"].iloc[0]) * int(rows["height"].iloc[0])
    ax.plot(fragments, paper_bytes(fragments, pixels) / 2**20, color="black", linestyle="--",
            label=f"paper's illustration buffer: 208 B/fragment + 12 B/pixel ({pixels} pixels)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("fragments of the view")
    ax.set_ylabel("GPU memory the technique owns (MiB, log)")
    ax.legend(fontsize=7, loc="upper left")
    figure_notes.paper_box(ax, PAPER)
    ax.set_title(common.title(rows, "pastyrik2016 section 4.3: memory against fragments"), fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
