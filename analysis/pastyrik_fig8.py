"""pastyrik2016 Figure 8: illustration buffer stage times per model, models sorted by total.

One line per stage, each including the stages before it (the paper's
cumulative reading), over the models (`--scene model --scene-set name=...`
and mesh files, named by their stem) ordered by the total time per frame;
one panel per camera position: the paper times each model in a general
position (`default`) and where its lists are longest (`max_list`).
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from analysis import common, figure_notes, presentation  # noqa: E402

TECHNIQUE = "illustration_buffer"
MESH_EXTENSIONS = (".obj", ".off", ".ply", ".stl", ".gltf", ".glb")
PAPER = ["pastyrik2016 (GTX 660, 600x600, 12 CAD/scanned models):",
         "FindNeighbours is the stage that grows most; Psi, not",
         "fragments or vertices, explains GPU 2 > Suspension 2"]


def is_model_scene(scene):
    return scene == "model" or str(scene).lower().endswith(MESH_EXTENSIONS)


def view_of(camera):
    """'general' for the default camera, 'max_list' for the longest-list view."""
    return "general" if camera == "default" else str(camera).split(":")[0]


def model_rows(runs, technique=TECHNIQUE):
    rows = runs[runs["scene"].map(is_model_scene)]
    if technique is not None:
        rows = rows[rows["technique"] == technique]
    rows = figure_notes.quiet_runs(rows)
    if rows.empty:
        raise common.NoData(f"no {technique or 'technique'} rows on the model scene or a mesh file")
    names = [common.tokens(p).get("name") or os.path.splitext(os.path.basename(s))[0]
             for s, p in zip(rows["scene"], rows["scene_params"])]
    return rows.assign(model=names, view=rows["camera"].map(view_of))


def views(rows):
    """The camera positions present, general first."""
    return sorted(rows["view"].unique(), key=lambda v: (v != "general", v))


def models_by_total(rows):
    """Model names, fastest total first (the paper's horizontal axis)."""
    totals = rows[rows["stage"] == "total"].groupby("model")["median_ms"].mean()
    return list(totals.sort_values().index)


def draw(runs, args=None):
    rows = model_rows(runs)
    panels = views(rows)
    fig, axes = plt.subplots(1, len(panels), figsize=(7.5 * len(panels), 4.5), squeeze=False)
    for ax, view in zip(axes[0], panels):
        part = rows[rows["view"] == view]
        order = models_by_total(part)
        table = common.stage_table(part, "model").loc[order]
        positions = range(len(order))
        cumulative = 0.0
        stages = [s for s in table.columns if s != "total"]
        colours = presentation.stage_colours(stages)
        for stage in stages:
            cumulative = cumulative + table[stage].fillna(0.0)
            ax.plot(positions, cumulative.to_numpy(), marker="o", markersize=3, color=colours[stage], label=stage)
        if "total" in table:
            ax.plot(positions, table["total"].to_numpy(), color="black", linestyle="--", marker="s", markersize=3,
                    label="total")
        ax.set_xticks(list(positions), order, rotation=30, ha="right")
        ax.set_xlabel(f"model (sorted by total time), camera: {view}")
        ax.set_ylabel("cumulative time per frame (ms)")
        ax.set_ylim(bottom=0)
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title(common.title(part, f"pastyrik2016 Fig. 8: illustration buffer stages per model ({view} "
                                        f"camera{figure_notes.noisy_note(part)})"), fontsize=8)
    figure_notes.paper_box(axes[0][0], PAPER, loc="upper right")
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    common.cli(__doc__.splitlines()[0], draw)
