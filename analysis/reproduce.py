"""Run the sweeps behind the papers' timing plots, then draw every plot.

Usage (from the repository root, after `bash setup.sh build`):
    /usr/bin/python3 -m analysis.reproduce [--quick] [--out results/<date>] [--only NAME ...]
        [--oitbench build/harness/oitbench] [--dry-run | --list-commands | --plots-only]

One CSV per sweep under --out (murray_fig10.csv, carnecky_fig14.csv,
carnecky_fig15.csv, models.csv, layers.csv), heatmaps under --out/heatmaps,
the PNG plots next to them. Resumable: before starting a bench the driver
reads the sweep's CSV and leaves out every run (technique, its swept
parameters, scene, swept scene parameters, camera, width, height) that the CSV
already holds whole (all its rows) with status ok or skipped; a run that failed
with an error, or was cut short, is tried again. Interrupt it at any point and start it again with the same --out.

--list-commands prints the sweeps as JSON (bench and stats invocations, plot
modules) for other drivers: workflow/Snakefile runs them as cluster jobs.
--plots-only draws from the CSVs already in --out; a CSV holding several
(device, platform) pairs is drawn once per pair (file names get a suffix).

--quick: small sizes, 1 warm-up + 3 timed frames, a few models: minutes on 2
cores with software GL. Without it the sweeps are sized for a real GPU (the
papers' resolutions and tessellations).
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

from analysis.results_io import read_rows, save_figure

# A run: technique parameters and scene parameters are tuples of (key, value)
# holding only what the sweep sets; everything else stays at its default.
Point = namedtuple("Point", "technique tparams scene sparams camera width height")

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OITBENCH = os.path.join(REPO, "build", "harness", "oitbench")
COMPARISON = ["depth_peeling", "dual_depth_peeling", "linked_list", "illustration_buffer"]
QUICK_MODELS = ["wuson", "elephant", "dragon", "bones", "bunny", "engine", "armadillo"]


class Catalogue:
    """What `oitbench list` says this build has: technique ids (with their
    parameter defaults, and which is the reference) and model names."""

    def __init__(self, text):
        self.techniques = OrderedDict()  # id -> {param: default}
        self.reference = set()
        self.models = []
        section, current, scene = None, None, None
        for line in text.splitlines():
            if line.startswith("Techniques:"):
                section = "techniques"
            elif line.startswith("Scenes"):
                section = "scenes"
            elif section and re.match(r"^  \S", line):
                current = line.split()[0]
                if section == "techniques":
                    self.techniques[current] = {}
                    if ", reference]" in line:
                        self.reference.add(current)
                else:
                    scene = current
            elif section and (m := re.match(r"^ {6}(\S+)\s+default (\S+)\s+(.*)", line)):
                if section == "techniques" and current in self.techniques:
                    self.techniques[current][m.group(1)] = m.group(2)
                elif section == "scenes" and scene == "model" and m.group(1) == "name":
                    choices = re.search(r"one of \{([^}]*)\}", m.group(3))
                    if choices:
                        self.models = [c.strip() for c in choices.group(1).split(",")]

    def timed(self):
        """Every technique but the exact reference, the paper's four first."""
        ids = [t for t in self.techniques if t not in self.reference]
        return [t for t in COMPARISON if t in ids] + [t for t in ids if t not in COMPARISON]


class Sweep:
    def __init__(self, name, points, plots, warmup, frames, skip_reason=""):
        self.name, self.points, self.plots = name, points, plots
        self.warmup, self.frames, self.skip_reason = warmup, frames, skip_reason


def cross(techniques, scene, scene_sets, cameras, sizes, tparams=()):
    return [Point(t, tuple(tparams), scene, tuple(s), c, w, h)
            for s in scene_sets for (w, h) in sizes for c in cameras for t in techniques]


def random_views(count, seed):
    """The views of a random camera set one by one, so each is resumable on its own."""
    return [f"random:{count}:{seed}@{i}" for i in range(count)]


def plan(catalogue, quick):
    """The sweeps and the plots each feeds. Quick: small enough for software
    GL on 2 cores; full: the papers' sizes (fragments grow with the square of
    the resolution: 2048^2 may not fit every device, its run becomes an error
    row and the plot stops where the device stopped)."""
    warmup, frames = (1, 3) if quick else (3, 20)
    sweeps = []

    objects = [1, 2, 4, 8, 16, 32]
    size = [(64, 64)] if quick else [(512, 512)]
    scene_sets = [[("layers", "32"), ("objects", str(n))] for n in objects]
    bkb = catalogue.techniques.get("bucketed_kbuffer")
    points, skip = [], ""
    if bkb is None:
        skip = "bucketed_kbuffer is not in this build (`oitbench list`): murray2016 Fig. 10 left out"
    else:
        # k = 32 covers the 32 layers, as in the paper; buckets=on even on one
        # object (the default `auto` would fall back to brute force there).
        # The figure times the paper's bucket query, not the default merge search.
        k = [("k", "32")] + ([("neighbor_search", "bucket")] if "neighbor_search" in bkb else [])
        points = cross(["kbuffer"], "quads", scene_sets, ["default"], size, k)
        points += cross(["bucketed_kbuffer"], "quads", scene_sets, ["default"], size,
                        k + ([("buckets", "on")] if "buckets" in bkb else []))
        if "buckets" in bkb:
            points += cross(["bucketed_kbuffer"], "quads", scene_sets, ["default"], size, k + [("buckets", "off")])
    sweeps.append(Sweep("murray_fig10", points, [("murray_fig10", {})], warmup, frames, skip))

    # carnecky2013 timed its own neighbour search (Algorithm 2), not pastyrik2016's triangle indices.
    heuristic = [("neighbors", "heuristic")]
    sides = [128, 192, 256, 384, 512] if quick else [128, 256, 512, 1024, 2048]
    views = random_views(3, 1) if quick else random_views(8, 1)
    sweeps.append(Sweep("carnecky_fig14",
                        cross(["illustration_buffer"], "torus", [[]], views, [(s, s) for s in sides], heuristic),
                        [("carnecky_fig14", {})], warmup, frames))

    tessellations = [(8, 4), (16, 8), (32, 16), (64, 32), (128, 64), (256, 128)] if quick else \
        [(16, 8), (32, 16), (64, 32), (128, 64), (256, 128), (512, 256), (1024, 512)]
    side = 256 if quick else 1024
    sweeps.append(Sweep("carnecky_fig15",
                        cross(["illustration_buffer"], "torus",
                              [[("slices", str(a)), ("stacks", str(b))] for a, b in tessellations], views,
                              [(side, side)], heuristic),
                        [("carnecky_fig15", {})], warmup, frames))

    models = [m for m in QUICK_MODELS if m in catalogue.models] if quick else catalogue.models
    side = 256 if quick else 600  # pastyrik2016 section 4.3 quotes 600x600
    sweeps.append(Sweep("models",
                        cross(catalogue.timed(), "model", [[("name", m)] for m in models], ["default"],
                              [(side, side)]),
                        [("pastyrik_fig8", {}), ("pastyrik_fig9", {}), ("pastyrik_fig10", {"heatmaps": True}),
                         ("oit_comparison", {})], warmup, frames))

    layers = [4, 8, 16, 32, 64]
    side = 128 if quick else 512
    sweeps.append(Sweep("layers",
                        cross(catalogue.timed(), "quads", [[("layers", str(n))] for n in layers], ["default"],
                              [(side, side)]),
                        [("time_per_fragment", {})], warmup, frames))
    return sweeps


def tokens(text):
    return dict(item.partition("=")[::2] for item in text.split())


def finished(point, rows):
    """Whether the CSV rows already hold this run (ok or skipped; an error is retried).
    The key of `oitbench bench --resume`; filtering here as well means a group
    whose runs are all finished starts no process (context, scene, reference)."""
    for row in rows:
        if (row.get("status") in ("ok", "skipped") and row.get("technique") == point.technique
                and row.get("scene") == point.scene and row.get("camera") == point.camera
                and row.get("width") == str(point.width) and row.get("height") == str(point.height)):
            params, scene_params = tokens(row.get("params", "")), tokens(row.get("scene_params", ""))
            if all(params.get(k) == v for k, v in point.tparams) and \
                    all(scene_params.get(k) == v for k, v in point.sparams):
                return True
    return False


def batches(points):
    """Missing runs grouped into bench invocations: runs that differ only by
    technique share one process (one GL context, one reference image); runs
    with technique parameters go alone, since --set would apply to every one."""
    groups = OrderedDict()
    for p in points:
        key = (p.tparams and p.technique, p.tparams, p.scene, p.sparams, p.camera, p.width, p.height)
        groups.setdefault(key, []).append(p)
    return list(groups.values())


def bench_arguments(batch, warmup, frames):
    """The `oitbench bench` arguments of one batch, without the binary and
    --csv (the Snakemake workflow adds its shard's CSV)."""
    first = batch[0]
    command = ["bench"]
    for p in batch:
        command += ["--technique", p.technique]
    for key, value in first.tparams:
        command += ["--set", f"{first.technique}.{key}={value}"]
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
    text += "".join(f" {k}={v}" for k, v in p.tparams)
    text += f" on {p.scene}" + "".join(f" {k}={v}" for k, v in p.sparams)
    return text + f" {p.width}x{p.height}" + ("" if p.camera == "default" else f" camera {p.camera}")


def run_sweep(sweep, args, env):
    """Runs what the sweep's CSV lacks; returns the bench commands started."""
    csv_path = os.path.join(args.out, f"{sweep.name}.csv")
    rows = read_rows(csv_path)
    missing = [p for p in sweep.points if not finished(p, rows)]
    todo = batches(missing)
    print(f"== {sweep.name}: {len(sweep.points)} runs, {len(sweep.points) - len(missing)} already in {csv_path}, "
          f"{len(todo)} bench invocation(s) to go", flush=True)
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


def heatmap_arguments(sweep):
    """(model, `oitbench stats` arguments without the binary and --heatmap)
    per model of the models sweep (pastyrik2016 Fig. 10)."""
    seen = OrderedDict((dict(p.sparams)["name"], p) for p in sweep.points)
    return [(model, ["stats", "--scene", p.scene, "--scene-set", f"name={model}", "--size", f"{p.width}x{p.height}"])
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


def device_groups(runs):
    """The rows of each (device, platform), with a file-name suffix: none when
    the CSV holds one, else a slug of both. Times are only comparable within
    one device, so a CSV merged from several machines is drawn per device."""
    groups = list(runs.groupby(["device", "platform"], sort=True))
    if len(groups) == 1:
        return [("", groups[0][1])]
    return [("_" + re.sub(r"[^A-Za-z0-9]+", "-", f"{device} {platform}").strip("-")[:80], part)
            for (device, platform), part in groups]


def draw_plots(sweep, args):
    """Each plot module's draw() on the sweep's CSV, once per device and
    platform in it; a plot without data is reported and left out, the others
    are still drawn."""
    import importlib

    import matplotlib.pyplot as plt

    from analysis import common

    csv_path = os.path.join(args.out, f"{sweep.name}.csv")
    try:
        groups = device_groups(common.load(csv_path))
    except (common.NoData, FileNotFoundError) as e:
        print(f"  {sweep.name}: no plot drawn: {e}", flush=True)
        return []
    drawn = []
    for module_name, options in sweep.plots:
        module = importlib.import_module(f"analysis.{module_name}")
        plot_args = argparse.Namespace(heatmaps=os.path.join(args.out, "heatmaps")) if options.get("heatmaps") else None
        for suffix, runs in groups:
            out = os.path.join(args.out, f"{module_name}{suffix}.png")
            try:
                fig = module.draw(runs, plot_args)
            except (common.NoData, FileNotFoundError) as e:
                print(f"  {module_name}{suffix}: not drawn: {e}", flush=True)
                continue
            save_figure(fig, out, dpi=90)
            plt.close(fig)
            drawn.append(out)
            print(f"  wrote {out}", flush=True)
    return drawn


def plan_as_data(sweeps):
    """The sweeps as plain data (what --list-commands prints as JSON): per
    sweep its bench invocations and `stats` heatmap invocations as argument
    lists without the binary, --csv and --heatmap, and its plot modules."""
    return [{"name": s.name, "skipped": s.skip_reason, "runs": len(s.points),
             "benches": [bench_arguments(b, s.warmup, s.frames) for b in batches(s.points)],
             "heatmaps": [{"model": m, "arguments": a} for m, a in heatmap_arguments(s)] if s.name == "models" else [],
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
    listing = subprocess.run([oitbench, "list"], capture_output=True, text=True, env=env, check=True).stdout
    return Catalogue(listing)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes, 1 warm-up + 3 frames (software GL)")
    parser.add_argument("--out", default=os.path.join("results", datetime.date.today().isoformat()))
    parser.add_argument("--oitbench", default=DEFAULT_OITBENCH)
    parser.add_argument("--only", nargs="+", default=None, help="sweep names to run (default: all)")
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
    sweeps = plan(catalogue_of(args.oitbench, env), args.quick)
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
        started += run_sweep(sweep, args, env)
        if sweep.name == "models":
            started += model_heatmaps(sweep, args, env)
        if not args.dry_run and not args.no_plots:
            drawn += draw_plots(sweep, args)
    print(f"reproduce: {len(started)} invocation(s) {'listed' if args.dry_run else 'run'}, "
          f"{len(drawn)} plot(s) in {args.out}", flush=True)
    return started


if __name__ == "__main__":
    main()
