"""carnecky2013 Figure 15: illustration buffer stage times versus number of triangles.

A tessellation sweep of one parametric surface at a fixed resolution (the
paper: a toroid at 1024^2, up to 500k triangles), averaged over a random
camera set, one diffusion iteration. x is the scene's triangle count, which
oitbench records in the `extra` column (scene_triangles). The paper: only
the fill pass grows (linearly, with a non-zero intercept); the other passes
do not depend on the geometry.
"""
from analysis import common
from analysis.carnecky_fig14 import PAPER_FIG15, scaling_figure


def draw(runs, args=None):
    return scaling_figure(runs, lambda r: r["scene_params"], "extra_scene_triangles", "number of triangles",
                          "carnecky2013 Fig. 15: illustration buffer vs triangles (tessellation sweep)", PAPER_FIG15)


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
