"""Run the sweeps behind the papers' figures, then draw every plot.

Usage (from the repository root, after `bash setup.sh build`):
    /usr/bin/python3 -m analysis.reproduce [--quick | --full] [--out results/<date>] [--only NAME ...]
        [--frames N] [--warmup N] [--rerun-noisy] [--oitbench build/harness/oitbench]
        [--dry-run | --list-commands | --plots-only]

One CSV per sweep under --out (murray_fig10, carnecky_fig14, carnecky_fig15,
models, pastyrik_fig7, murray_models, psi_scenes, layers), heatmaps under --out/heatmaps,
the carnecky2013 Figs. 9-13 renders under --out/images, murray2016 Figs. 1 and
5-9 under --out/murray_images, the PNG plots next
to them. Resumable: before starting a bench the driver reads the sweep's CSV
and leaves out every run (technique, its swept parameters, scene, swept scene
parameters, camera, width, height) that the CSV already holds whole (all its
rows) with status ok or skipped; a run that failed with an error, or was cut
short, is tried again; with --rerun-noisy a run flagged `noisy` is run once
more (the plots then keep the quiet repeat). Interrupt it at any point and
start it again with the same --out.

--list-commands prints the sweeps as JSON (bench, stats and render
invocations, plot modules) for other drivers: workflow/Snakefile runs the
benches as cluster jobs. --plots-only draws from the CSVs already in --out;
a CSV holding several (device, platform) pairs is drawn once per pair (file
names get a suffix).

--quick: small sizes, 1 warm-up + 3 timed frames, a few models: software GL
on 2 cores. --full (the default): the papers' resolutions and parameters
(PAPER below; 3 warm-up + 20 timed frames), sized for a GPU; --frames and
--warmup shorten the runs without changing the sizes.
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys
import time
from collections import OrderedDict, namedtuple

from analysis import figure_configs
from analysis.results_io import read_rows, save_figure

# A run: technique parameters and scene parameters are tuples of (key, value)
# holding only what the sweep sets; everything else stays at its default.
Point = namedtuple("Point", "technique tparams scene sparams camera width height")
# One image of `oitbench render` for the stylised-image grids (carnecky2013
# Figs. 9-13): written to <out>/images/<name>.png; `caption` goes under it.
Render = namedtuple("Render", "name caption technique tparams scene sparams camera width height")

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OITBENCH = os.path.join(REPO, "build", "harness", "oitbench")
COMPARISON = ["depth_peeling", "dual_depth_peeling", "linked_list", "illustration_buffer"]
QUICK_MODELS = ["wuson", "elephant", "dragon", "bones", "bunny", "engine", "armadillo"]
# CAD-like meshes of assimp-testmodels loaded as file scenes beside the
# `model` scene's catalogue (pastyrik2016 timed CAD scenes: GPU, Suspension,
# engines): regr01 is a building's floor plan in 275 parts. Left out where
# the file is not installed.
CAD_FILES = ["/usr/share/assimp/models/OBJ/regr01.obj"]
# pastyrik2016 section 4: "each model is tested in two positions - one
# general and one where the length of linked list is maximum possible".
MODEL_CAMERAS = ["default", "max_list:16:1"]
# The papers' sizes and parameters (--full), pinned per figure in
# analysis/figure_configs.py: carnecky2013 section 7, murray2016 section 6,
# pastyrik2016 section 4.
PAPER = dict({name: figure.paper for name, figure in figure_configs.FIGURES.items()},
             carnecky_images="carnecky2013 Figs. 9-13 at 512^2 (Fig. 12(b): 512x512, 20 iterations; Fig. 9: its "
                             "five diffusion configurations)",
             murray_images="murray2016 Figs. 1, 5-9 at 1000x1000 (Fig. 8's bike: 1200x800) with each figure's "
                           "transfer functions")


class Catalogue:
    """What `oitbench list` says this build has: technique ids (with their
    parameter defaults and descriptions, and which is the reference) and
    model names."""

    def __init__(self, text):
        self.techniques = OrderedDict()  # id -> {param: default}
        self.descriptions = {}  # id -> {param: description (its allowed values first), wrapped lines joined}
        self.reference = set()
        self.models = []
        section, current = None, None
        parameters = []  # [section, technique or scene, parameter, default, description]
        for line in text.splitlines():
            wrapped = re.match(r"^ {8}\S", line)
            if wrapped and parameters and parameters[-1] is not None:
                parameters[-1][4] += " " + line.strip()  # a long range or description goes on here
                continue
            if parameters and parameters[-1] is not None:
                parameters.append(None)  # what follows no longer continues that parameter
            if line.startswith("Techniques:"):
                section = "techniques"
            elif line.startswith("Scenes"):
                section = "scenes"
            elif section and re.match(r"^  \S", line):
                current = line.split()[0]
                if section == "techniques":
                    self.techniques[current] = {}
                    self.descriptions[current] = {}
                    if ", reference]" in line:
                        self.reference.add(current)
            elif section and (m := re.match(r"^ {6}(\S+)\s+default (\S*)\s+(.*)", line)):
                parameters[-1:] = [[section, current, m.group(1), m.group(2), m.group(3)]]
        for section, owner, name, default, description in filter(None, parameters):
            if section == "techniques" and owner in self.techniques:
                self.techniques[owner][name] = default
                self.descriptions[owner][name] = description
            elif section == "scenes" and owner == "model" and name == "name":
                choices = re.search(r"one of \{([^}]*)\}", description)
                if choices:
                    self.models = [c.strip() for c in choices.group(1).split(",")]

    def timed(self):
        """Every technique but the exact reference, the paper's four first."""
        ids = [t for t in self.techniques if t not in self.reference]
        return [t for t in COMPARISON if t in ids] + [t for t in ids if t not in COMPARISON]

    def allowed(self, technique, param):
        """What `list` says a parameter allows: its description up to the
        dash before its meaning ("" when it is not there)."""
        return self.descriptions.get(technique, {}).get(param, "").split(" — ")[0]

    def choices(self, technique, param):
        """The values `one of {...}` allows for a parameter ([] when it is not
        a choice or not there)."""
        found = re.search(r"one of \{([^}]*)\}", self.allowed(technique, param))
        return [c.strip() for c in found.group(1).split(",")] if found else []

    def accepts_auto(self, technique, param):
        return "or auto" in self.allowed(technique, param)

    def is_switch(self, technique, param):
        return self.allowed(technique, param).startswith("true or false")


class Sweep:
    def __init__(self, name, points, plots, warmup, frames, skip_reason="", renders=(), notes=()):
        self.name, self.points, self.plots = name, list(dict.fromkeys(points)), plots
        self.warmup, self.frames, self.skip_reason = warmup, frames, skip_reason
        self.renders = list(renders)
        self.notes = list(dict.fromkeys(notes))  # pins this build lacks, techniques without pins


def pins_for(catalogue, technique, pins, notes):
    """`pins` (figure_configs) as Point tparams for this build: where the
    illustration buffer has `preset=paper`, it stands for the papers' path;
    a pinned parameter the build does not list is left out and named in
    `notes` (an older build: it has no such knob)."""
    pins = dict(pins)
    if technique == "illustration_buffer" and "paper" in catalogue.choices(technique, "preset") and all(
            pins.get(k) == v for k, v in figure_configs.ILLUSTRATION_BUFFER_PAPER.items()):
        pins = {"preset": "paper", **{k: v for k, v in pins.items()
                                      if k not in figure_configs.ILLUSTRATION_BUFFER_PAPER}}
    known = catalogue.techniques.get(technique, {})
    missing = [k for k in pins if k not in known]
    if missing:
        notes.append(f"{technique} has no {', '.join(missing)} in this build (pinned in analysis/figure_configs.py): "
                     f"left out")
    return tuple((k, v) for k, v in pins.items() if k in known)


def series_points(catalogue, series, scene, scene_sets, cameras, sizes, notes):
    """Points of the figure_configs series whose technique the build has."""
    return [p for s in series if s.technique in catalogue.techniques
            for p in cross([s.technique], scene, scene_sets, cameras, sizes,
                           pins_for(catalogue, s.technique, s.pins, notes))]


def sizes_of(sweep, quick):
    return figure_configs.FIGURES[sweep].sizes["quick" if quick else "full"]


def cross(techniques, scene, scene_sets, cameras, sizes, tparams=()):
    return [Point(t, tuple(tparams), scene, tuple(s), c, w, h)
            for s in scene_sets for (w, h) in sizes for c in cameras for t in techniques]


def random_views(count, seed):
    """The views of a random camera set one by one, so each is resumable on its own."""
    return [f"random:{count}:{seed}@{i}" for i in range(count)]


def murray_fig10(catalogue, quick, warmup, frames):
    """murray2016 Fig. 10: 32 stacked quads, 1..32 objects, k = 32, 512^2:
    the kbuffer alone, the paper's bucket query (buckets on even on one
    object), the brute force (buckets=off) and the merge search (not in
    the paper), each pinned in figure_configs."""
    objects = [1, 2, 4, 8, 16, 32]
    scene_sets = [[("layers", "32"), ("objects", str(n))] for n in objects]
    if "bucketed_kbuffer" not in catalogue.techniques:
        return Sweep("murray_fig10", [], [("murray_fig10", {})], warmup, frames,
                     "bucketed_kbuffer is not in this build (`oitbench list`): murray2016 Fig. 10 left out")
    notes = []
    points = series_points(catalogue, figure_configs.FIGURES["murray_fig10"].series, "quads", scene_sets, ["default"],
                           sizes_of("murray_fig10", quick), notes)
    return Sweep("murray_fig10", points, [("murray_fig10", {})], warmup, frames, notes=notes)


def carnecky_sweeps(catalogue, quick, warmup, frames, views=None):
    """carnecky2013 Figs. 14 and 15: the toroid under random cameras, its
    stages on the paper's path (figure_configs.CARNECKY: linked lists, every
    fragment diffused every step, ONE diffusion iteration: the paper's solve
    pass is one iteration, its own neighbour search, Algorithm 2); without
    the accuracy bookkeeping (surface id and uv per fragment), which the
    paper's buffer does not hold. `views`: random views per point instead of the
    mode's (3 quick; 32 and 16 full)."""
    notes = []
    ib = pins_for(catalogue, "illustration_buffer", figure_configs.CARNECKY, notes)
    views14 = random_views(views or (3 if quick else 32), 1)
    fig14 = Sweep("carnecky_fig14", cross(["illustration_buffer"], "torus", [[]], views14,
                                          sizes_of("carnecky_fig14", quick), ib),
                  [("carnecky_fig14", {})], warmup, frames, notes=notes)
    # slices x stacks x 2 triangles: 64 .. 65k (quick), 256 .. 1M (full; the
    # paper's axis ends at 500k).
    tessellations = [(8, 4), (16, 8), (32, 16), (64, 32), (128, 64), (256, 128)] if quick else \
        [(16, 8), (64, 32), (128, 64), (256, 128), (512, 256), (512, 512), (1024, 512)]
    views15 = random_views(views or (3 if quick else 16), 1)
    fig15 = Sweep("carnecky_fig15",
                  cross(["illustration_buffer"], "torus", [[("slices", str(a)), ("stacks", str(b))]
                                                           for a, b in tessellations], views15,
                        sizes_of("carnecky_fig15", quick), ib),
                  [("carnecky_fig15", {})], warmup, frames, notes=notes)
    return [fig14, fig15]


def model_scenes(catalogue, quick):
    """(scene, scene parameters) of every model the pastyrik2016 sweeps time:
    the `model` catalogue (a quick subset) and the CAD files installed."""
    names = [m for m in QUICK_MODELS if m in catalogue.models] if quick else catalogue.models
    return ([("model", (("name", m),)) for m in names]
            + [(path, ()) for path in CAD_FILES if os.path.exists(path)])


def model_points(catalogue, series, scenes, cameras, sizes, notes):
    return [p for scene, sparams in scenes
            for p in series_points(catalogue, series, scene, [sparams], cameras, sizes, notes)]


def comparison(catalogue, series, notes):
    """`series` (figure_configs) of the techniques the build times, and a
    series at its defaults, named in `notes`, for a technique the table
    does not pin yet."""
    pinned = {s.technique for s in series}
    extra = [t for t in catalogue.timed() if t not in pinned]
    notes += [f"{t}: no pins in analysis/figure_configs.py, run at this build's defaults" for t in extra]
    return ([s for s in series if s.technique in catalogue.timed()]
            + [figure_configs.Series(t, {}, t) for t in extra])


def pastyrik_fig7(catalogue, scenes, quick, warmup, frames):
    """pastyrik2016 Fig. 7: the illustration buffer's dynamic sort of the
    list against its static arrays (figure_configs); a build whose buffer has
    no `sort` times the same sorts in the linked lists the buffer is built
    on (every linked_list `sort` choice, the rest at its defaults)."""
    notes = []
    sizes = sizes_of("pastyrik_fig7", quick)
    if catalogue.choices("illustration_buffer", "sort"):
        points = model_points(catalogue, figure_configs.FIGURES["pastyrik_fig7"].series, scenes, MODEL_CAMERAS, sizes,
                              notes)
        return Sweep("pastyrik_fig7", points, [("pastyrik_fig7", {})], warmup, frames, notes=notes)
    variants = catalogue.choices("linked_list", "sort")
    if variants:
        series = [figure_configs.Series("linked_list", {"sort": v}, f"linked_list sort={v}") for v in variants]
        notes.append("illustration_buffer has no `sort` in this build: linked_list's sorts instead")
        return Sweep("pastyrik_fig7", model_points(catalogue, series, scenes, MODEL_CAMERAS, sizes, notes),
                     [("pastyrik_fig7", {})], warmup, frames, notes=notes)
    return Sweep("pastyrik_fig7", [], [("pastyrik_fig7", {})], warmup, frames,
                 "neither illustration_buffer nor linked_list has a `sort` choice in this build")


def murray_models(catalogue, scenes, quick, warmup, frames):
    """murray2016 Figs. 1, 8, 9: frame rate of OIT (dual-pass k-buffer,
    constant transparency) against mean curvature transparency (bucketed
    k-buffer with the paper's bucket query), 16 layers, 1000x1000 and (full)
    Fig. 8's 1200x800."""
    if "bucketed_kbuffer" not in catalogue.techniques or "kbuffer" not in catalogue.techniques:
        return Sweep("murray_models", [], [("murray_fps_ratio", {})], warmup, frames,
                     "kbuffer or bucketed_kbuffer is not in this build: murray2016 Figs. 1/8/9 left out")
    notes = []
    points = model_points(catalogue, figure_configs.FIGURES["murray_models"].series, scenes, ["default"],
                          sizes_of("murray_models", quick), notes)
    return Sweep("murray_models", points, [("murray_fps_ratio", {})], warmup, frames, notes=notes)


# Synthetic scenes whose complexity coverage Psi spans 0..1 at similar
# fragment counts: pastyrik2016 finds that Psi drives the illustration
# buffer's time (its FindNeighbours stage) and no other technique's.
PSI_SCENES = [("quads", (("layers", "8"), ("objects", "8"))), ("nested_spheres", (("count", "4"),)),
              ("cylinders", ()), ("torus", ()), ("spheres", ()), ("particles", ()), ("random_quads", ())]


def psi_scenes(catalogue, quick, warmup, frames):
    series = figure_configs.FIGURES["psi_scenes"].series
    notes = []
    points = model_points(catalogue, series, PSI_SCENES, ["default"], sizes_of("psi_scenes", quick), notes)
    return Sweep("psi_scenes", points, [("pastyrik_psi", {})], warmup, frames,
                 "" if points else "neither illustration_buffer nor linked_list is in this build", notes=notes)


def layers_sweep(catalogue, quick, warmup, frames):
    """Time per fragment against depth complexity; the k-buffers at k=auto
    (k = the view's depth complexity: no fragment dropped) where they accept it."""
    layers = [4, 8, 16, 32, 64]
    sets = [[("layers", str(n))] for n in layers]
    notes = []
    series = comparison(catalogue, figure_configs.FIGURES["layers"].series, notes)
    # A build whose k-buffer takes no k=auto keeps the pinned fixed k.
    series = [s._replace(pins={**s.pins, "k": figure_configs.KBUFFER["k"]})
              if s.pins.get("k") == "auto" and not catalogue.accepts_auto(s.technique, "k") else s for s in series]
    points = series_points(catalogue, series, "quads", sets, ["default"], sizes_of("layers", quick), notes)
    return Sweep("layers", points, [("time_per_fragment", {})], warmup, frames, notes=notes)


def carnecky_images(catalogue, quick):
    """carnecky2013 Figs. 9-13 as renders of comparable scenes: Fig. 9's
    five diffusion configurations (figure_configs.CARNECKY_FIG9), constant
    transparency against the method (Figs. 10, 12, 13) and the transparency
    assignments of Fig. 11 this build offers (angle / normal variation
    modes where `modulation` lists them)."""
    if "illustration_buffer" not in catalogue.techniques:
        return []
    side = 256 if quick else 512
    ib, modes = "illustration_buffer", catalogue.choices("illustration_buffer", "modulation")
    extra_modes = [m for m in modes if re.search(r"angle|normal", m)]
    torus = ("torus", ())
    # A random view frames the whole bounding sphere: the engine's own camera crops it.
    engine = ("model", (("name", "engine"),), "random:8:2@0") if "engine" in catalogue.models else torus
    flow = ("cylinders", ())
    close = ("spheres", ())
    # Fig. 9's eq. 8 columns need field_diffusion (an older build has only eq. 9: they are left out).
    # A view where the torus's inner side passes over its far side: halos as well as silhouettes.
    eq8 = "homogeneous" in catalogue.choices(ib, "field_diffusion")
    folded_torus = ("torus", (), "random:8:2@2")
    grid = [(name, caption, ib, list(knobs.items()), folded_torus)
            for name, caption, knobs in figure_configs.CARNECKY_FIG9 if eq8 or knobs["field_diffusion"] != "homogeneous"]
    grid += [
        ("fig10_constant", "constant transparency", ib, [("modulation", "none")], close),
        ("fig10_ours", "illustration buffer", ib, [], close),
        ("fig11_constant", "(b) constant", ib, [("modulation", "none")], ("nested_spheres", ())),
        ("fig11_ours", "(e) silhouettes + halos", ib, [], ("nested_spheres", ())),
        ("fig12_constant", "flow surface, constant", ib, [("modulation", "none")], flow),
        ("fig12_ours", "flow surface, ours", ib, [], flow),
        ("fig13_constant", "(a) engine, constant", ib, [("modulation", "none")], engine),
        ("fig13_ours", "(c) engine, ours", ib, [], engine),
    ]
    grid += [(f"fig11_{m}", f"{m} transparency", ib, [("modulation", m)], ("nested_spheres", ())) for m in extra_modes]
    grid += [(f"fig13_{m}", f"(b) engine, {m}", ib, [("modulation", m)], engine)
             for m in extra_modes if "normal" in m]
    # Every image on the paper's path (figure_configs.CARNECKY_IMAGES), its own knobs on top.
    return [Render(name, caption, t, pins_for(catalogue, t, {**figure_configs.CARNECKY_IMAGES, **dict(tp)}, []),
                   where[0], where[1], where[2] if len(where) > 2 else "default", side, side)
            for name, caption, t, tp, where in grid]


def murray_images(catalogue):
    """murray2016 Figs. 1 and 5-9 as renders of the closest packaged models,
    at the paper's sizes in both modes (a few renders), each with the
    transfer functions the figure shows: OIT with constant transparency
    (kbuffer) against the bucketed k-buffer's stylisations."""
    if "bucketed_kbuffer" not in catalogue.techniques or "kbuffer" not in catalogue.techniques:
        return []
    bkb, kb = "bucketed_kbuffer", "kbuffer"
    examples = os.path.join(REPO, "algorithms", "bucketed_kbuffer", "examples")
    opaque = [("opacity_transfer_file", os.path.join(examples, "opacity_opaque.txt"))]
    front_opaque = [("opacity_transfer_file", os.path.join(examples, "opacity_front_opaque_3x3.txt"))]
    # A random view frames the whole bounding sphere: the engine's own camera crops it.
    engine = ("model", (("name", "engine"),), "random:8:2@0")
    cad = next((path for path in CAD_FILES if os.path.exists(path)), None)
    plant = (cad, (), "random:8:2@0") if cad else ("model", (("name", "spider"),))
    bones, creature = ("model", (("name", "bones"), ("alpha", "0.6"))), ("model", (("name", "armadillo"),))
    big, bike, small = (1000, 1000), (1200, 800), (512, 512)
    grid = [
        ("fig01_oit", "(left) OIT, constant transparency", kb, [], engine, big),
        ("fig01_opaque", "(centre) shading on opaque surfaces", bkb, opaque, engine, big),
        ("fig01_ours", "(right) ours, Fig. 7(a)", bkb, [], engine, big),
        ("fig05_simple", "(a) simple check", bkb, [("reverse_check", "false")], ("cylinders", ()), small),
        ("fig05_reverse", "(b) reverse check", bkb, [], ("cylinders", ()), small),
        # Fig. 6 shows colour functions: constant opacity, so that only the colour changes.
        ("fig06_a", "(a) mean curvature shading", bkb, [("opacity_transfer", "identity")], creature, small),
        ("fig06_b", "(b) bright curved, dark flat", bkb,
         [("color_transfer", "curved_bright"), ("opacity_transfer", "identity")], creature, small),
        ("fig07_a", "(a) front focus", bkb, [], creature, small),
        ("fig07_b", "(b) depth range", bkb, [("opacity_transfer", "depth_range")], creature, small),
        ("fig08_a", "(a) bike: Fig. 7(a)", bkb, [], engine, bike),
        ("fig08_b", "(b) bike: Fig. 7(b)", bkb, [("opacity_transfer", "depth_range")], engine, bike),
        ("fig08_c", "(c) powerplant: Fig. 7(a)", bkb, [], plant, big),
        ("fig08_d", "(d) powerplant: front opaque", bkb, front_opaque, plant, big),
        ("fig09_a", "(a) OIT, opacity 0.6", kb, [], bones, big),
        ("fig09_b", "(b) mean curvature shading only", bkb, [("opacity_transfer", "identity")], bones, big),
        ("fig09_c", "(c) mean curvature transparency", bkb, [], bones, big),
    ]
    pins = {bkb: figure_configs.BUCKETED_KBUFFER_PAPER_SLOTS, kb: figure_configs.KBUFFER_PAPER_SLOTS}
    # A model this build does not package is left out (its figure loses that panel).
    grid = [g for g in grid if g[4][0] != "model" or dict(g[4][1])["name"] in catalogue.models]
    return [Render(name, caption, t, pins_for(catalogue, t, {**pins[t], **dict(tp)}, []), where[0], where[1],
                   where[2] if len(where) > 2 else "default", size[0], size[1])
            for name, caption, t, tp, where, size in grid]


def render_directory(out, sweep):
    """Where a render sweep's images go: carnecky2013's in <out>/images (as
    committed), every other's in <out>/<sweep name>."""
    return os.path.join(out, "images" if sweep.name == "carnecky_images" else sweep.name)


def plan(catalogue, quick, views=None):
    """The sweeps and the plots each feeds. Quick: small enough for software
    GL on 2 cores; full: the papers' sizes and parameters (PAPER; fragments
    grow with the square of the resolution: 2048^2 may not fit every device,
    its run becomes an error row and the plot stops where the device
    stopped)."""
    warmup, frames = (1, 3) if quick else (3, 20)
    scenes = model_scenes(catalogue, quick)
    notes = []
    series = comparison(catalogue, figure_configs.FIGURES["models"].series, notes)
    models = Sweep("models", model_points(catalogue, series, scenes, MODEL_CAMERAS, sizes_of("models", quick), notes),
                   [(module, {"heatmaps": True} if module == "pastyrik_fig10" else {})
                    for module in figure_configs.FIGURES["models"].plots], warmup, frames, notes=notes)
    images, murray = carnecky_images(catalogue, quick), murray_images(catalogue)
    return ([murray_fig10(catalogue, quick, warmup, frames)] + carnecky_sweeps(catalogue, quick, warmup, frames, views)
            + [models, pastyrik_fig7(catalogue, scenes, quick, warmup, frames),
               murray_models(catalogue, scenes, quick, warmup, frames),
               psi_scenes(catalogue, quick, warmup, frames),
               layers_sweep(catalogue, quick, warmup, frames),
               Sweep("carnecky_images", [], [("carnecky_images", {"images": True})], 0, 0,
                     "" if images else "illustration_buffer is not in this build", images),
               Sweep("murray_images", [], [("murray_images", {"images": True})], 0, 0,
                     "" if murray else "kbuffer or bucketed_kbuffer is not in this build", murray)])


def tokens(text):
    return dict(item.partition("=")[::2] for item in text.split())


def finished(point, rows, rerun_noisy=False):
    """Whether the CSV rows already hold this run (ok or skipped; an error is retried).
    The key of `oitbench bench --resume`; filtering here as well means a group
    whose runs are all finished starts no process (context, scene, reference).
    With rerun_noisy a run flagged `noisy` (other processes took over a
    quarter of the cores) counts only once it has been tried twice."""
    noisy = set()
    for row in rows:
        if (row.get("status") in ("ok", "skipped") and row.get("technique") == point.technique
                and row.get("scene") == point.scene and row.get("camera") == point.camera
                and row.get("width") == str(point.width) and row.get("height") == str(point.height)):
            params, scene_params = tokens(row.get("params", "")), tokens(row.get("scene_params", ""))
            if all(params.get(k) == v for k, v in point.tparams) and \
                    all(scene_params.get(k) == v for k, v in point.sparams):
                if not rerun_noisy or row.get("noisy") != "true":
                    return True
                noisy.add(row.get("run_id"))
    return len(noisy) >= 2


def batches(points):
    """Missing runs grouped into bench invocations: runs of one scene point
    (scene, its parameters, camera, size) share one process (one GL context,
    one reference image), at most one run per technique in each, since each
    technique's parameters are set for it alone (`--set technique.key=v`)."""
    groups = OrderedDict()
    for p in points:
        where, n = (p.scene, p.sparams, p.camera, p.width, p.height), 0
        while any(q.technique == p.technique for q in groups.get((where, n), [])):
            n += 1  # a second series of the technique (e.g. the other tie_break): a process of its own
        groups.setdefault((where, n), []).append(p)
    return list(groups.values())


def bench_arguments(batch, warmup, frames):
    """The `oitbench bench` arguments of one batch, without the binary and
    --csv (the Snakemake workflow adds its shard's CSV)."""
    first = batch[0]
    command = ["bench"]
    for p in batch:
        command += ["--technique", p.technique]
    for p in batch:
        command += [a for key, value in p.tparams for a in ("--set", f"{p.technique}.{key}={value}")]
    command += ["--scene", first.scene]
    for key, value in first.sparams:
        command += ["--scene-set", f"{key}={value}"]
    command += ["--size", f"{first.width}x{first.height}", "--camera", first.camera, "--warmup", str(warmup),
                "--frames", str(frames)]
    return command


def bench_command(oitbench, batch, csv_path, warmup, frames):
    return [oitbench] + bench_arguments(batch, warmup, frames) + ["--csv", csv_path]


def describe(batch):
    p = batch[0]
    text = "+".join(q.technique for q in batch)
    text += "".join(f" {q.technique}.{k}={v}" for q in batch for k, v in q.tparams) if len(batch) == 1 else ""
    text += f" on {p.scene}" + "".join(f" {k}={v}" for k, v in p.sparams)
    return text + f" {p.width}x{p.height}" + ("" if p.camera == "default" else f" camera {p.camera}")


def run_sweep(sweep, args, env):
    """Runs what the sweep's CSV lacks; returns the bench commands started."""
    csv_path = os.path.join(args.out, f"{sweep.name}.csv")
    rows = read_rows(csv_path)
    missing = [p for p in sweep.points if not finished(p, rows, args.rerun_noisy)]
    todo = batches(missing)
    print(f"== {sweep.name}: {len(sweep.points)} runs, {len(sweep.points) - len(missing)} already in {csv_path}, "
          f"{len(todo)} bench invocation(s) to go", flush=True)
    for note in sweep.notes:
        print(f"  note: {note}", flush=True)
    started = []
    for i, batch in enumerate(todo):
        command = bench_command(args.oitbench, batch, csv_path, sweep.warmup, sweep.frames)
        started.append(command)
        print(f"[{sweep.name} {i + 1}/{len(todo)}] {describe(batch)}", flush=True)
        if args.dry_run:
            print("  would run: " + " ".join(command), flush=True)
            continue
        begin = time.monotonic()
        # Bench's own progress goes to stderr, which stays on the terminal;
        # its summary table (stdout) is left out to keep the log short.
        result = subprocess.run(command, stdout=subprocess.DEVNULL, env=env)
        note = "" if result.returncode == 0 else f" (exit status {result.returncode}: its rows are retried next time)"
        print(f"  {time.monotonic() - begin:.1f} s{note}", flush=True)
    return started


def model_label(scene, sparams):
    """A model's name: the `model` scene's name parameter, a file scene's stem
    (the plots' `model_rows` names them the same way)."""
    name = dict(sparams).get("name")
    return name if name else os.path.splitext(os.path.basename(scene))[0]


def scene_arguments(scene, sparams):
    return ["--scene", scene] + [a for k, v in sparams for a in ("--scene-set", f"{k}={v}")]


def heatmap_arguments(sweep):
    """(model, `oitbench stats` arguments without the binary and --heatmap)
    per model of the models sweep (pastyrik2016 Fig. 10), default camera."""
    seen = OrderedDict((model_label(p.scene, p.sparams), p) for p in sweep.points)
    return [(model, ["stats"] + scene_arguments(p.scene, p.sparams) + ["--size", f"{p.width}x{p.height}"])
            for model, p in seen.items()]


def model_heatmaps(sweep, args, env):
    """`oitbench stats --heatmap` per model of the models sweep."""
    directory = os.path.join(args.out, "heatmaps")
    os.makedirs(directory, exist_ok=True)
    started = []
    for model, arguments in heatmap_arguments(sweep):
        png = os.path.join(directory, f"heatmap_{model}.png")
        if os.path.exists(png):
            continue
        command = [args.oitbench] + arguments + ["--heatmap", png]
        started.append(command)
        print(f"[heatmaps] {model}", flush=True)
        if args.dry_run:
            print("  would run: " + " ".join(command), flush=True)
            continue
        with open(os.path.join(directory, f"stats_{model}.txt"), "w") as log:
            result = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=env)
        if result.returncode != 0:
            print(f"  stats failed (exit status {result.returncode}), see stats_{model}.txt", flush=True)
    return started


def render_arguments(render):
    """`oitbench render` arguments of one image, without the binary and -o."""
    command = ["render", "--technique", render.technique]
    for key, value in render.tparams:
        command += ["--set", f"{key}={value}"]
    return command + scene_arguments(render.scene, render.sparams) + [
        "--size", f"{render.width}x{render.height}", "--camera", render.camera, "--background", "1,1,1"]


def run_renders(sweep, args, env):
    """The sweep's images not yet in <out>/images (resumable like the benches)."""
    directory = render_directory(args.out, sweep)
    os.makedirs(directory, exist_ok=True)
    started = []
    for render in sweep.renders:
        png = os.path.join(directory, f"{render.name}.png")
        if os.path.exists(png):
            continue
        command = [args.oitbench] + render_arguments(render) + ["-o", png]
        started.append(command)
        print(f"[images] {render.name}: {render.caption}", flush=True)
        if args.dry_run:
            print("  would run: " + " ".join(command), flush=True)
            continue
        result = subprocess.run(command, stdout=subprocess.DEVNULL, env=env)
        if result.returncode != 0:
            print(f"  render failed (exit status {result.returncode})", flush=True)
    # The captions travel with the images: the grid plot reads them.
    if not args.dry_run:
        with open(os.path.join(directory, "captions.json"), "w") as f:
            json.dump({r.name: r.caption for r in sweep.renders}, f, indent=1)
    return started


def device_groups(runs):
    """The rows of each (device, platform), with a file-name suffix: none when
    the CSV holds one, else a slug of both. Times are only comparable within
    one device, so a CSV merged from several machines is drawn per device."""
    groups = list(runs.groupby(["device", "platform"], sort=True))
    if len(groups) == 1:
        return [("", groups[0][1])]
    return [("_" + re.sub(r"[^A-Za-z0-9]+", "-", f"{device} {platform}").strip("-")[:80], part)
            for (device, platform), part in groups]


def draw_images(sweep, args):
    """The image grids of a render-only sweep."""
    import importlib

    drawn = []
    for module_name, _ in sweep.plots:
        module = importlib.import_module(f"analysis.{module_name}")
        out = os.path.join(args.out, f"{module_name}.png")
        draw_and_save(lambda: module.draw_directory(render_directory(args.out, sweep)), out, module_name, drawn)
    return drawn


def draw_and_save(draw, out, label, drawn):
    """draw() saved to `out` and appended to `drawn`; a plot without data
    (NoData, a missing file) is reported under `label` and left out."""
    import matplotlib.pyplot as plt

    from analysis import common

    try:
        fig = draw()
    except (common.NoData, FileNotFoundError) as e:
        print(f"  {label}: not drawn: {e}", flush=True)
        return
    save_figure(fig, out, dpi=90)
    plt.close(fig)
    drawn.append(out)
    print(f"  wrote {out}", flush=True)


def draw_plots(sweep, args):
    """Each plot module's draw() on the sweep's CSV, once per device and
    platform in it; a plot without data is reported and left out, the others
    are still drawn."""
    import importlib

    from analysis import common

    if sweep.renders:
        return draw_images(sweep, args)
    csv_path = os.path.join(args.out, f"{sweep.name}.csv")
    try:
        groups = device_groups(common.load(csv_path))
    except (common.NoData, FileNotFoundError) as e:
        print(f"  {sweep.name}: no plot drawn: {e}", flush=True)
        return []
    drawn = []
    for module_name, options in sweep.plots:
        module = importlib.import_module(f"analysis.{module_name}")
        # The build's defaults: labels name the parameters a run has off them.
        plot_args = argparse.Namespace(heatmaps=os.path.join(args.out, "heatmaps") if options.get("heatmaps") else None,
                                       defaults=getattr(args, "defaults", None))
        for suffix, runs in groups:
            out = os.path.join(args.out, f"{module_name}{suffix}.png")
            draw_and_save(lambda: module.draw(runs, plot_args), out, f"{module_name}{suffix}", drawn)
    return drawn


def plan_as_data(sweeps):
    """The sweeps as plain data (what --list-commands prints as JSON): per
    sweep its bench invocations and `stats` heatmap invocations as argument
    lists without the binary, --csv and --heatmap, its `render` invocations
    (without -o; the image name beside them), and its plot modules. A sweep
    of renders only is marked skipped for the workflow, which runs benches:
    `analysis.reproduce --only carnecky_images` draws it."""
    return [{"name": s.name,
             "skipped": s.skip_reason or ("renders only: run by analysis.reproduce" if s.renders and not s.points
                                          else ""),
             "runs": len(s.points),
             "benches": [bench_arguments(b, s.warmup, s.frames) for b in batches(s.points)],
             "heatmaps": [{"model": m, "arguments": a} for m, a in heatmap_arguments(s)] if s.name == "models" else [],
             "renders": [{"name": r.name, "arguments": render_arguments(r)} for r in s.renders],
             "paper": PAPER.get(s.name, ""),
             "notes": s.notes,
             "plots": [module for module, _ in s.plots]}
            for s in sweeps]


def oitbench_environment(oitbench):
    """The environment to start oitbench in: Mesa compiles each shader once per
    machine, not once per bench process (build/harness/oitbench ->
    build/mesa_shader_cache, where setup.sh and the tests keep it)."""
    env = dict(os.environ)
    env.setdefault("MESA_SHADER_CACHE_DIR", os.path.join(os.path.dirname(os.path.dirname(
        os.path.abspath(oitbench))), "mesa_shader_cache"))
    return env


def catalogue_of(oitbench, env):
    """What `oitbench list` lists. `list` wraps its lines to COLUMNS (else
    120 columns in a pipe), which would split a `one of {...}` (the models'
    names) over lines the Catalogue reads one by one: the widest it takes."""
    listing = subprocess.run([oitbench, "list"], capture_output=True, text=True, env={**env, "COLUMNS": "10000"},
                             check=True).stdout
    return Catalogue(listing)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    size = parser.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="small sizes, 1 warm-up + 3 frames (software GL)")
    size.add_argument("--full", action="store_true",
                      help="the papers' resolutions and parameters (the default; named for clarity)")
    parser.add_argument("--out", default=os.path.join("results", datetime.date.today().isoformat()))
    parser.add_argument("--oitbench", default=DEFAULT_OITBENCH)
    parser.add_argument("--only", nargs="+", default=None, help="sweep names to run (default: all)")
    parser.add_argument("--frames", type=int, default=None,
                        help="timed frames per run instead of the mode's (3 quick, 20 full): the papers' sizes "
                             "with fewer frames on a slow device")
    parser.add_argument("--warmup", type=int, default=None, help="untimed frames per run instead of the mode's")
    parser.add_argument("--views", type=int, default=None,
                        help="random views per point of carnecky2013 Figs. 14/15 instead of the mode's (3 quick, 32 "
                             "and 16 full)")
    parser.add_argument("--rerun-noisy", action="store_true",
                        help="run again every run whose rows are flagged noisy (at most twice in all)")
    parser.add_argument("--dry-run", action="store_true", help="print the invocations a run would start, run none")
    parser.add_argument("--no-plots", action="store_true")
    parser.add_argument("--plots-only", action="store_true",
                        help="draw the plots from the CSVs already in --out (e.g. merged from several machines), run "
                             "no bench")
    parser.add_argument("--list-commands", action="store_true",
                        help="print every sweep's bench and stats invocations as JSON (the Snakemake workflow's "
                             "input), run nothing")
    args = parser.parse_args(argv)
    if not os.access(args.oitbench, os.X_OK):
        sys.exit(f"reproduce: {args.oitbench} is not an executable (build first: bash setup.sh build)")
    env = oitbench_environment(args.oitbench)
    catalogue = catalogue_of(args.oitbench, env)
    args.defaults = catalogue.techniques
    sweeps = plan(catalogue, args.quick, args.views)
    for sweep in sweeps:
        if sweep.points:
            sweep.frames = args.frames if args.frames is not None else sweep.frames
            sweep.warmup = args.warmup if args.warmup is not None else sweep.warmup
    if args.only:
        unknown = set(args.only) - {s.name for s in sweeps}
        if unknown:
            sys.exit(f"reproduce: unknown sweep(s) {', '.join(sorted(unknown))}: "
                     f"expected {', '.join(s.name for s in sweeps)}")
        sweeps = [s for s in sweeps if s.name in args.only]
    if args.list_commands:
        json.dump({"quick": args.quick, "sweeps": plan_as_data(sweeps)}, sys.stdout)
        print()
        return []
    os.makedirs(args.out, exist_ok=True)
    if args.plots_only:
        drawn = [png for sweep in sweeps if not sweep.skip_reason for png in draw_plots(sweep, args)]
        print(f"reproduce: {len(drawn)} plot(s) in {args.out}", flush=True)
        return []
    started, drawn = [], []
    for sweep in sweeps:
        if sweep.skip_reason:
            print(f"== {sweep.name}: skipped: {sweep.skip_reason}", flush=True)
            continue
        begin = time.monotonic()
        started += run_sweep(sweep, args, env) if sweep.points else []
        if sweep.name == "models":
            started += model_heatmaps(sweep, args, env)
        if sweep.renders:
            started += run_renders(sweep, args, env)
        if not args.dry_run:
            print(f"== {sweep.name}: {time.monotonic() - begin:.0f} s", flush=True)
        if not args.dry_run and not args.no_plots:
            drawn += draw_plots(sweep, args)
    print(f"reproduce: {len(started)} invocation(s) {'listed' if args.dry_run else 'run'}, "
          f"{len(drawn)} plot(s) in {args.out}", flush=True)
    return started


if __name__ == "__main__":
    main()
