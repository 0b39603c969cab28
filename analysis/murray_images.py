"""murray2016 Figures 1 and 5-9 as image grids of our renders.

The renders are `oitbench render` images that `analysis.reproduce --only
murray_images` writes to <out>/murray_images/<name>.png (white background),
at the paper's sizes, with their captions in captions.json; names start with
the paper's figure (fig01_..., fig09_...). One row per figure, the panels in
the paper's order: OIT with constant transparency (kbuffer) against the
bucketed k-buffer with the transfer functions each figure shows, on the
packaged models closest to the paper's (results/reference/reproduce/README.md
says which stands in for which). Usage:
python3 -m analysis.murray_images IMAGES_DIR -o grid.png
"""
import json
import os

import matplotlib

matplotlib.use("Agg")
from analysis import common  # noqa: E402

# Figure prefix -> the row's label: the paper's figure and our stand-in model.
ROWS = {"fig01": "Fig. 1 (engine)", "fig05": "Fig. 5: reverse check (cylinders)",
        "fig06": "Fig. 6: colour TFs (armadillo)", "fig07": "Fig. 7: opacity TFs (armadillo)",
        "fig08": "Fig. 8: bike (engine), powerplant (regr01)", "fig09": "Fig. 9 (bones)"}


def panels(directory):
    """{figure prefix: [(name, caption)]} of the rendered images, in order."""
    with open(os.path.join(directory, "captions.json")) as f:
        captions = json.load(f)
    found = {}
    for name, caption in captions.items():
        if os.path.exists(os.path.join(directory, f"{name}.png")):
            found.setdefault(name.split("_")[0], []).append((name, caption))
    if not found:
        raise common.NoData(f"no rendered image of captions.json in {directory}")
    return {prefix: found[prefix] for prefix in ROWS if prefix in found}


def draw_directory(directory):
    return common.image_grid(directory, [(ROWS[prefix], items) for prefix, items in panels(directory).items()],
                             "murray2016 Figs. 1, 5-9 with our k-buffers (oitbench render at the paper's sizes; "
                             "kbuffer = OIT, the rest bucketed_kbuffer)", panel=(2.6, 2.4))


if __name__ == "__main__":
    common.images_cli(__doc__.splitlines()[0], draw_directory)
