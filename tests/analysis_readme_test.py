#!/usr/bin/python3
"""The README's analysis examples run as written and draw what it promises.

Every `python3 -m analysis.*` command of README.md's code blocks and code
spans is run, from a directory holding the CSVs it names (small fixtures in
the harness's column layout), except analysis.reproduce (it runs oitbench
sweeps: tests/reproduce_test.py). The labels' parameter defaults come from
the built oitbench (argv[1]). The files written are then read back: PNG and
SVG beside it, the facets and their titles, labels without default
parameters, every text at least 9 pt at the saved size.

Also: every analysis module with a command line answers `python3 -m
analysis.NAME --help`, pyproject.toml names every library they import, and
the documents analysis/ cites exist."""
import ast
import csv
import os
import re
import shlex
import struct
import subprocess
import sys
import tempfile
import tomllib
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import analysis_fixtures as fx  # noqa: E402

OITBENCH = os.path.abspath(sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(REPO, "build", "harness", "oitbench"))
QUADS = "layers=32 objects=32 seed=1 alpha=0.3"
SPHERES = "count=3 slices=32 stacks=16 alpha=0.4"
NOT_RUN = {"reproduce"}


def run_rows(technique, params, scene, scene_params, stages, error, camera="default"):
    """The rows of one run: its stages, then total = their sum + 10 %; p05
    and p95 at 0.9 and 1.3 times each median."""
    total = round(sum(ms for _, ms in stages) * 1.1, 6)
    return [fx.row(technique, stage, ms, params=params, scene=scene, scene_params=scene_params, camera=camera,
                   p05_ms=round(ms * 0.9, 6), p95_ms=round(ms * 1.3, 6), error_rmse=error, error_max=error)
            for stage, ms in stages + [("total", total)]]


def stage_fixture():
    """Two quads configurations and one spheres camera set; kbuffer at its
    defaults and off them (its full params as the harness writes them)."""
    rows = []
    for layers in (32, 64):
        quads = QUADS.replace("layers=32", f"layers={layers}")
        rows += run_rows("kbuffer", "k=16 tail=drop auto_k_memory_mb=1024", "quads", quads,
                         [("count", 1.0), ("fill", 3.0), ("compose", 0.5)], 0.0)
        rows += run_rows("kbuffer", "k=4 tail=blend auto_k_memory_mb=1024", "quads", quads,
                         [("count", 1.0), ("fill", 2.0), ("compose", 0.5)], 0.05)
        rows += run_rows("unsorted", "", "quads", quads, [("fill", 0.4)], 0.2)
    for view in range(3):
        rows += run_rows("depth_peeling", "max_passes=2 early_exit=true tie_break=triangle_id", "spheres", SPHERES,
                         [("peel", 2.0), ("compose", 0.3)], 0.02, camera=f"random:3:1@{view}")
    return rows


def pareto_fixture():
    rows = []
    for scene, scene_params in (("quads", QUADS), ("spheres", SPHERES)):
        rows += run_rows("kbuffer", "k=16 tail=drop auto_k_memory_mb=1024", scene, scene_params, [("fill", 8.0)], 0.0)
        rows += run_rows("kbuffer", "k=4 tail=drop auto_k_memory_mb=1024", scene, scene_params, [("fill", 2.0)],
                         0.1)
        rows += run_rows("kbuffer", "k=8 tail=blend auto_k_memory_mb=1024", scene, scene_params, [("fill", 4.0)],
                         0.3)  # slower and worse than k=4: off the front
        rows += run_rows("unsorted", "", scene, scene_params, [("fill", 1.0)], 0.5)
    return rows


def readme_commands():
    """(module, argument list) of each `python3 -m analysis.*` command in
    README.md's fenced code blocks and code spans (comments dropped)."""
    with open(os.path.join(REPO, "README.md")) as f:
        text = f.read()
    blocks = re.findall(r"^```[^\n]*\n(.*?)^```", text, re.S | re.M)
    lines = [line for block in blocks for line in block.splitlines()]
    spans = [" ".join(span.split()) for span in re.findall(r"(?<!`)`([^`]+)`(?!`)", re.sub(r"^```.*?^```", "", text,
                                                                                         flags=re.S | re.M))]
    commands = []
    for line in lines + spans:
        if "python3 -m analysis." not in line:
            continue
        words = shlex.split(line, comments=True)
        if len(words) > 2 and words[0].endswith("python3") and words[1] == "-m" and words[2].startswith("analysis."):
            commands.append((words[2].split(".", 1)[1], words[3:]))
    return commands


def png_size(path):
    with open(path, "rb") as f:
        header = f.read(24)
    assert header[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is no PNG"
    return struct.unpack(">II", header[16:24])


def svg_texts(path):
    """(font size in pt, text) of every text of an SVG matplotlib wrote with
    its text kept as text (72 units per inch: a unit is a point)."""
    with open(path) as f:
        svg = f.read()
    texts = [(float(size), re.sub(r"<[^>]+>", "", body))
             for size, body in re.findall(r"<text[^>]*style=\"font: ([0-9.]+)px[^\"]*\"[^>]*>(.*?)</text>", svg, re.S)]
    return svg, texts


class ReadmeExamplesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.commands = readme_commands()
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = cls.tmp.name
        fx.write_csv(os.path.join(cls.dir, "runs.csv"), stage_fixture())
        fx.write_csv(os.path.join(cls.dir, "pareto.csv"), pareto_fixture())
        rows = stage_fixture()
        fx.write_csv(os.path.join(cls.dir, "a.csv"), rows[:len(rows) // 2])
        fx.write_csv(os.path.join(cls.dir, "b.csv"), rows[len(rows) // 2:])
        cls.results = {}
        for module, arguments in cls.commands:
            if module in NOT_RUN:
                continue
            if module in ("plot_stages", "pareto"):
                arguments = arguments + ["--oitbench", OITBENCH]
            cls.results[module] = subprocess.run([sys.executable, "-m", f"analysis.{module}"] + arguments,
                                                 cwd=cls.dir, capture_output=True, text=True,
                                                 env=dict(os.environ, PYTHONPATH=REPO))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def path(self, *parts):
        return os.path.join(self.dir, *parts)

    def test_the_readme_shows_the_plot_examples_and_each_runs(self):
        self.assertTrue({"plot_stages", "pareto", "approximate_oit", "merge"} <= set(self.results),
                        f"README examples found: {self.commands}")
        for module, result in self.results.items():
            self.assertEqual(result.returncode, 0, f"analysis.{module}: {result.stderr}")

    def assert_readable(self, png, dpi):
        """The SVG beside `png` keeps its text as text, all of it >= 9 pt,
        and the PNG is the same figure at `dpi` (so >= 9 pt there too)."""
        svg, texts = svg_texts(os.path.splitext(png)[0] + ".svg")
        self.assertGreater(len(texts), 10)
        self.assertGreaterEqual(min(size for size, _ in texts), 9.0, [t for t in texts if t[0] < 9])
        width_pt, height_pt = (float(v) for v in re.search(r'<svg[^>]*width="([0-9.]+)pt" height="([0-9.]+)pt"',
                                                            svg).groups())
        width_px, height_px = png_size(png)
        self.assertAlmostEqual(width_px, width_pt / 72 * dpi, delta=1)
        self.assertAlmostEqual(height_px, height_pt / 72 * dpi, delta=1)
        return svg, [text for _, text in texts]

    def test_stage_plot_one_facet_per_scene_configuration_short_labels(self):
        svg, texts = self.assert_readable(self.path("stages.png"), dpi=120)
        self.assertEqual(len(re.findall(r'<g id="axes_\d+">', svg)), 4)  # the legend and 3 facets
        titles = [f"quads {QUADS} | 64x64", f"quads {QUADS.replace('layers=32', 'layers=64')} | 64x64",
                  f"spheres {SPHERES} | 64x64 | camera random:3:1"]
        for title in titles:
            self.assertIn(title, texts)
        labels = ["kbuffer", "kbuffer k=4 tail=blend", "unsorted", "depth_peeling max_passes=2", "(mean of 3 runs)"]
        for label in labels:
            self.assertIn(label, texts)
        self.assertFalse([t for t in texts if "auto_k_memory_mb" in t or "early_exit" in t], "a default is shown")
        self.assertIn("total (whisker: p05..p95)", texts)

    def test_pareto_one_file_pair_per_scene_front_listed(self):
        self.assertEqual(sorted(os.listdir(self.path("plots"))),
                         ["pareto_quads_64x64.png", "pareto_quads_64x64.svg", "pareto_spheres_64x64.png",
                          "pareto_spheres_64x64.svg"])
        for scene, scene_params in (("quads", QUADS), ("spheres", SPHERES)):
            svg, texts = self.assert_readable(self.path("plots", f"pareto_{scene}_64x64.png"), dpi=120)
            self.assertIn(f"{scene} {scene_params} | 64x64", texts)
            self.assertIn("1 unsorted", texts)
            self.assertIn("2 kbuffer k=4", texts)
            self.assertIn("3 kbuffer", texts)
            self.assertFalse([t for t in texts if "k=8" in t], "k=8 is off the front")
        self.assertIn("front = unsorted, kbuffer k=4, kbuffer", self.results["pareto"].stdout)

    def test_pareto_table_marks_the_front(self):
        with open(self.path("pareto.md")) as f:
            table = f.read()
        self.assertIn(f"### quads {QUADS} | 64x64\n", table)
        self.assertEqual(table.count("| front |"), 6 + 2)  # 3 front runs per scene, one header per scene

    def test_merge_joins_the_shards(self):
        with open(self.path("all.csv"), newline="") as f:
            merged = list(csv.DictReader(f))
        self.assertEqual(len(merged), len(stage_fixture()))


class PackageTest(unittest.TestCase):
    def modules(self):
        return sorted(name[:-3] for name in os.listdir(os.path.join(REPO, "analysis"))
                      if name.endswith(".py") and name != "__init__.py")

    def test_every_module_with_a_main_answers_help_as_python_m(self):
        runnable = []
        for module in self.modules():
            with open(os.path.join(REPO, "analysis", f"{module}.py")) as f:
                if 'if __name__ == "__main__":' not in f.read():
                    continue
            runnable.append(module)
            result = subprocess.run([sys.executable, "-m", f"analysis.{module}", "--help"], cwd=REPO,
                                    capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, f"analysis.{module}: {result.stderr}")
            self.assertTrue(result.stdout.startswith("usage:"), module)
        self.assertIn("plot_stages", runnable)
        self.assertIn("pareto", runnable)

    def test_pyproject_names_the_package_and_every_library_it_imports(self):
        with open(os.path.join(REPO, "pyproject.toml"), "rb") as f:
            project = tomllib.load(f)
        self.assertEqual(project["tool"]["setuptools"]["packages"], ["analysis"])
        declared = {re.split(r"[<>=!~ ]", d)[0] for d in project["project"]["dependencies"]}
        imported = set()
        for module in self.modules():
            with open(os.path.join(REPO, "analysis", f"{module}.py")) as f:
                tree = ast.parse(f.read())
            for node in ast.walk(tree):
                names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                         else [node.module] if isinstance(node, ast.ImportFrom) and node.level == 0 else [])
                imported |= {n.split(".")[0] for n in names}
        third_party = imported - set(sys.stdlib_module_names) - {"analysis"}
        self.assertEqual(third_party, declared)

    def test_documents_cited_by_analysis_exist(self):
        for module in self.modules() + ["__init__"]:
            with open(os.path.join(REPO, "analysis", f"{module}.py")) as f:
                source = f.read()
            for document in re.findall(r"\b(?:\w+/)+[\w.]+\.md\b|\bDESIGN\.md\b", source):
                self.assertTrue(os.path.exists(os.path.join(REPO, document)), f"analysis/{module}.py cites {document}")
            for document, section in re.findall(r"([\w/]+\.md),\s+\"([^\"]+)\"", source):
                with open(os.path.join(REPO, document)) as f:
                    headings = re.findall(r"^#+ (.*)$", f.read(), re.M)
                self.assertIn(section, headings, f"analysis/{module}.py cites {document} \"{section}\"")


if __name__ == "__main__":
    unittest.main()
