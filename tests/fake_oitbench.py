#!/usr/bin/python3
"""A stand-in for build/harness/oitbench in the reproduce tests: `list` prints
a small catalogue, `bench` appends plausible CSV rows for exactly the runs its
arguments ask for and logs each invocation, `stats` writes a tiny heatmap PNG.
FAKE_OITBENCH_LOG: file receiving one line per invocation.
FAKE_OITBENCH_NO_BKB=1: list without bucketed_kbuffer.
FAKE_OITBENCH_DIE_AT=N: the N-th bench invocation (counted in the log) writes
its rows for the first technique only and exits 1, as an interrupted run.
`render` writes a tiny PNG; a mesh file path is a scene without parameters."""
import argparse
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import analysis_fixtures  # noqa: E402

TECHNIQUES = {
    "reference": ({"initial_nodes_per_pixel": "8"}, ["fill", "sort", "compose"], "[exact, reference]"),
    "depth_peeling": ({"max_passes": "64"}, ["peel", "compose"], "[exact]"),
    "linked_list": ({"sort": "insertion"}, ["clear", "fill", "sort", "compose"], "[exact]"),
    "kbuffer": ({"k": "8"}, ["clear", "fill", "compose"], "[approximate]"),
    "illustration_buffer": ({"neighbors": "heuristic", "modulation": "silhouette_halo", "iterations": "20"},
                            ["clear", "fill", "sort", "neighbors", "stylize", "compose"], "[exact]"),
    "bucketed_kbuffer": ({"buckets": "on", "k": "8", "neighbor_search": "merge"},
                         ["clear", "fill", "bucket", "neighbors", "stylize", "compose"], "[approximate]"),
}
SCENE_DEFAULTS = {"quads": {"layers": "32", "objects": "32", "seed": "1"}, "torus": {"slices": "64", "stacks": "32"},
                  "model": {"name": "bunny", "alpha": "0.4"}}
MODELS = ["engine", "bunny", "wuson", "elephant", "bones"]
# What `list` prints as a parameter's allowed values (default: a plain range).
ALLOWED = {("linked_list", "sort"): "one of {insertion, selection, network}",
           ("bucketed_kbuffer", "neighbor_search"): "one of {merge, bucket}",
           ("kbuffer", "k"): "integer in [1, 64] or auto",
           ("illustration_buffer", "modulation"): "one of {none, silhouette_halo}"}


def techniques():
    return {t: v for t, v in TECHNIQUES.items()
            if not (t == "bucketed_kbuffer" and os.environ.get("FAKE_OITBENCH_NO_BKB"))}


def log(argv):
    path = os.environ.get("FAKE_OITBENCH_LOG")
    if path:
        with open(path, "a") as f:
            f.write(" ".join(argv) + "\n")
    if path and os.path.exists(path):
        with open(path) as f:
            return sum(1 for line in f if line.startswith("bench "))
    return 0


def run_list():
    print("Device: fake (4.5, none)\n\nTechniques:")
    for t, (params, stages, kind) in techniques().items():
        print(f"  {t:<20} {t} {kind}\n      paper: none\n      stages: {', '.join(stages)}")
        for key, value in params.items():
            print(f"      {key:<24} default {value:<8} {ALLOWED.get((t, key), 'anything')} — a parameter")
    print("\nScenes (or a .gltf/.glb/.obj/.off/.ply/.stl file path):")
    for scene, params in SCENE_DEFAULTS.items():
        print(f"  {scene:<20} a scene")
        for key, value in params.items():
            allowed = "one of {" + ", ".join(MODELS) + "}" if key == "name" else "integer in [1, 9]"
            print(f"      {key:<24} default {value:<8} {allowed} — a parameter")


def run_bench(args, count):
    known = techniques()
    rows = []
    for n, technique in enumerate(args.technique):
        params = dict(known[technique][0])
        for assignment in args.set:
            name, _, value = assignment.partition("=")
            owner, _, key = name.rpartition(".")
            if owner == technique:
                params[key] = value
        scene_params = dict(SCENE_DEFAULTS.get(args.scene, {}))
        scene_params.update(dict(s.split("=", 1) for s in args.scene_set))
        width, height = (int(v) for v in args.size.split("x"))
        layers = int(scene_params.get("layers", 4))
        common = dict(params=" ".join(f"{k}={v}" for k, v in params.items()), scene=args.scene,
                      scene_params=" ".join(f"{k}={v}" for k, v in scene_params.items()), camera=args.camera,
                      width=width, height=height, fragments=width * height * layers, max_depth_complexity=layers,
                      psi=0.5, extra="scene_triangles=128 scene_vertices=66",
                      bytes_allocated=width * height * (layers + 1) * 16, passes=2)
        stages = known[technique][1]
        for stage in stages:
            rows.append(analysis_fixtures.row(technique, stage, 1.0, **common))
        rows.append(analysis_fixtures.row(technique, "total", len(stages) + 0.5, **common))
        if n == 0 and os.environ.get("FAKE_OITBENCH_DIE_AT") and count == int(os.environ["FAKE_OITBENCH_DIE_AT"]):
            analysis_fixtures.write_csv(args.csv, rows, append=True)
            sys.exit(1)
    analysis_fixtures.write_csv(args.csv, rows, append=True)


def write_png(path):
    # A 2x2 RGB PNG: signature, IHDR, one IDAT, IEND.
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    raw = b"".join(b"\x00" + bytes([255, 0, 0, 0, 0, 255]) for _ in range(2))
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def run_stats(args):
    write_png(args.heatmap)
    print("fragments 4")


def main():
    count = log(sys.argv[1:])
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("list")
    bench = sub.add_parser("bench")
    bench.add_argument("--technique", action="append", default=[])
    bench.add_argument("--set", action="append", default=[])
    bench.add_argument("--scene")
    bench.add_argument("--scene-set", action="append", default=[])
    for option in ("--size", "--camera", "--warmup", "--frames", "--csv"):
        bench.add_argument(option)
    stats = sub.add_parser("stats")
    for option in ("--scene", "--size", "--heatmap"):
        stats.add_argument(option)
    stats.add_argument("--scene-set", action="append", default=[])
    render = sub.add_parser("render")
    for option in ("--technique", "--scene", "--size", "--camera", "--background", "-o"):
        render.add_argument(option)
    render.add_argument("--set", action="append", default=[])
    render.add_argument("--scene-set", action="append", default=[])
    args = parser.parse_args()
    if args.command == "list":
        run_list()
    elif args.command == "bench":
        run_bench(args, count)
    elif args.command == "render":
        write_png(args.o)
    else:
        run_stats(args)


if __name__ == "__main__":
    main()
