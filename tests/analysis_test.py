#!/usr/bin/python3
"""analysis/plot_stages.py reads the CSV the harness writes and plots the
median of each stage: checked on a CSV with known numbers, in the exact
column layout of harness/run/results_csv.cpp."""
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "analysis"))
import pareto  # noqa: E402
import plot_stages  # noqa: E402
import pandas as pd  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
import analysis_fixtures as fx  # noqa: E402

OITBENCH = os.path.abspath(sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(HERE, "..", "build", "harness",
                                                                                  "oitbench"))
from analysis import common, presentation, reproduce, results_io  # noqa: E402
import matplotlib.text  # noqa: E402



def runs_csv(tmp, rows):
    """`rows` (analysis_fixtures.row) written as <tmp>/runs.csv; its path."""
    path = os.path.join(tmp, "runs.csv")
    fx.write_csv(path, rows)
    return path


class PlotStagesTest(unittest.TestCase):
    def test_medians_per_stage_and_skipped_rows_ignored(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv = runs_csv(tmp, [fx.row("reference", stage, ms, params="initial_nodes_per_pixel=8")
                                 for stage, ms in [("clear", 1.0), ("fill", 5.0), ("compose", 2.0), ("total", 8.5)]] +
                           [fx.row("unsorted", "fill", 0.5), fx.row("unsorted", "total", 0.75),
                            fx.row("kbuffer", "", "", params="k=8", status="skipped", message="needs a, b")])
            runs = plot_stages.load_runs(csv)
            self.assertEqual(sorted(runs["technique"].unique()), ["reference", "unsorted"])
            medians = runs.pivot_table(index="technique", columns="stage", values="median_ms")
            self.assertEqual(medians.loc["reference", "fill"], 5.0)
            self.assertEqual(medians.loc["unsorted", "total"], 0.75)
            out = os.path.join(tmp, "stages.png")
            subprocess.run([sys.executable, os.path.join(HERE, "..", "analysis", "plot_stages.py"), csv, "--out", out],
                           check=True, capture_output=True)
            with open(out, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_stage_order_comes_from_the_csv_new_stage_names_included(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv = runs_csv(tmp, [fx.row("newcomer", stage, ms) for stage, ms in
                                 [("clear", 1.0), ("build_histogram", 3.0), ("fill", 5.0), ("total", 9.0)]] +
                           [fx.row("unsorted", stage, ms) for stage, ms in
                            [("fill", 2.0), ("blend_tail", 1.0), ("total", 3.0)]])
            runs = plot_stages.load_runs(csv)
            self.assertEqual(common.stage_order(runs), ["clear", "build_histogram", "fill", "blend_tail"])
            table = common.stage_table(runs, "technique")
            self.assertEqual(list(table.columns), ["clear", "build_histogram", "fill", "blend_tail", "total"])

    def test_stage_order_follows_every_runs_pipeline_not_only_the_first_rows(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv = runs_csv(tmp, [fx.row("unsorted", "fill", 1.0)] +
                           [fx.row("linearized_fragment_buffer", s, 1.0) for s in ("count", "fill", "compose")] +
                           [fx.row("linked_list", s, 1.0) for s in ("clear", "fill", "compose")] +
                           [fx.row("disagrees", s, 1.0) for s in ("compose", "fill")])
            runs = plot_stages.load_runs(csv)
            self.assertEqual(common.stage_order(runs), ["count", "clear", "fill", "compose"])
            self.assertEqual(common.stage_order(runs[runs["technique"] != "disagrees"]),
                             ["count", "clear", "fill", "compose"])

    def test_no_matching_rows_is_a_clear_error(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv = runs_csv(tmp, [fx.row("unsorted", "total", 0.75)])
            result = subprocess.run([sys.executable, os.path.join(HERE, "..", "analysis", "plot_stages.py"), csv,
                                     "--scene", "spheres"], capture_output=True, text=True)
            self.assertNotEqual(result.returncode, 0)
            self.assertIn("no successful runs", result.stderr)


class ParetoTest(unittest.TestCase):
    def test_front_keeps_only_undominated_runs(self):
        points = pd.DataFrame({"label": ["fast_bad", "slow_exact", "dominated", "middle", "slower_exact"],
                               "time_ms": [1.0, 10.0, 5.0, 4.0, 20.0],
                               "error": [0.5, 0.0, 0.3, 0.1, 0.0]})
        front = pareto.pareto_front(points)
        self.assertEqual(list(front["label"]), ["fast_bad", "middle", "slow_exact"])

    def test_plots_one_figure_per_scene_from_bench_rows(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv = runs_csv(tmp, [fx.row(technique, "total", ms, params=params, error_rmse=err)
                                 for technique, params, ms, err in [("kbuffer", "k=4", 2.0, 0.1),
                                                                    ("kbuffer", "k=32", 8.0, 0.0),
                                                                    ("unsorted", "", 1.0, 0.3)]])
            totals = pareto.load_totals(csv, "error_rmse")
            self.assertEqual(len(totals), 3)
            result = subprocess.run([sys.executable, os.path.join(HERE, "..", "analysis", "pareto.py"), csv],
                                    check=True, capture_output=True, text=True)
            self.assertIn("front = unsorted, kbuffer k=4, kbuffer k=32", result.stdout)
            self.assertTrue(os.path.exists(os.path.join(tmp, "runs_quads_64x64.png")))


TABLE = """| id | technique | paper | kind | parameters (default, range) | stages |
|---|---|---|---|---|---|
| `kbuffer` | Dual-pass k-buffer | Kubisch 2014 | exact | `k` (16; integer in [1, 64] or auto), `tail` (drop; one of {drop, blend}) | count, fill |
| `bucketed_kbuffer` | Bucketed \\| k-buffer | Murray 2016 | approximate | `color_transfer_file` (empty; path of a readable file without spaces, ',' or '=' (empty: none)), `depth_bits` (16; one of {16, 24}) | fill |
| `unsorted` | Unsorted alpha blending | (baseline) | approximate | - | fill |
"""
DEFAULTS = {"kbuffer": {"k": "16", "tail": "drop"}, "bucketed_kbuffer": {"color_transfer_file": "", "depth_bits": "16"},
            "unsorted": {}}


class PresentationTest(unittest.TestCase):
    def test_defaults_read_from_the_technique_table(self):
        self.assertEqual(presentation.parse_technique_table(TABLE), DEFAULTS)

    def test_defaults_of_the_built_oitbench(self):
        built = presentation.technique_defaults(OITBENCH)
        self.assertEqual(built["kbuffer"], {"k": "16", "tail": "drop", "slot_layout": "full", "auto_k_memory_mb": "1024"})
        self.assertEqual(built["unsorted"], {})

    def test_an_oitbench_that_does_not_answer_is_an_error_naming_it(self):
        with self.assertRaises(RuntimeError) as raised:
            presentation.technique_defaults("/nonexistent/oitbench")
        self.assertIn("'/nonexistent/oitbench list --markdown'", str(raised.exception))

    def test_labels_keep_only_parameters_off_their_defaults(self):
        runs = pd.DataFrame({"technique": ["kbuffer", "kbuffer", "bucketed_kbuffer", "newcomer", "kbuffer"],
                             "params": ["k=16 tail=drop", "k=4 tail=drop", "color_transfer_file= depth_bits=24",
                                        "x=1", "k=16 tail=drop added_later=3"]})
        self.assertEqual(list(presentation.non_default_params(runs, DEFAULTS)),
                         ["", "k=4", "depth_bits=24", "x=1", "added_later=3"])
        self.assertEqual(list(presentation.short_params(runs, None)),
                         ["k=16", "k=4", "", "", "k=16 added_later=3"])  # without defaults: what differs


def stage_rows(technique, params, scene_params, clock="wall", scale=1.0, camera="default"):
    return [fx.row(technique, stage, ms * scale, params=params, scene_params=scene_params, clock=clock,
                   camera=camera, p05_ms=ms * scale * 0.5, p95_ms=ms * scale * 2)
            for stage, ms in (("fill", 2.0), ("compose", 1.0), ("total", 3.5))]


class StageFacetsTest(unittest.TestCase):
    def draw(self, rows, defaults=DEFAULTS):
        with tempfile.TemporaryDirectory() as tmp:
            return plot_stages.draw(plot_stages.load_runs(runs_csv(tmp, rows)), defaults)

    def test_scenes_and_clocks_never_share_a_bar(self):
        fig = self.draw(stage_rows("kbuffer", "k=16 tail=drop", "layers=32") +
                        stage_rows("kbuffer", "k=4 tail=drop", "layers=32", scale=2) +
                        stage_rows("kbuffer", "k=16 tail=drop", "layers=64", scale=3) +
                        stage_rows("kbuffer", "k=16 tail=drop", "layers=64", clock="gl", scale=4))
        facets = [ax for ax in fig.axes if ax.get_title(loc="left")]
        self.assertEqual([ax.get_title(loc="left") for ax in facets],
                         ["quads layers=32 | 64x64 | clock wall", "quads layers=64 | 64x64 | clock gl",
                          "quads layers=64 | 64x64 | clock wall"])
        self.assertEqual([[t.get_text() for t in ax.get_yticklabels()] for ax in facets],
                         [["kbuffer", "kbuffer k=4"], ["kbuffer"], ["kbuffer"]])
        fills = [[round(p.get_width(), 6) for p in ax.patches][:len(ax.get_yticklabels())] for ax in facets]
        self.assertEqual(fills, [[2.0, 4.0], [8.0], [6.0]])
        whisker = [c for c in facets[0].collections if isinstance(c, matplotlib.collections.LineCollection)][0]
        self.assertEqual([tuple(segment[:, 0]) for segment in whisker.get_segments()], [(1.75, 7.0), (3.5, 14.0)])

    def test_every_text_is_at_least_9_points(self):
        fig = self.draw(stage_rows("kbuffer", "k=4 tail=blend", "layers=32") + stage_rows("unsorted", "", "layers=32"))
        fig.canvas.draw()  # tick labels are made when drawn
        texts = [t for t in fig.findobj(matplotlib.text.Text) if t.get_text() and t.get_visible()]
        self.assertGreater(len(texts), 10)
        self.assertGreaterEqual(min(t.get_fontsize() for t in texts), presentation.SMALLEST_POINTS)

    def test_two_configurations_under_one_label_are_an_error_not_one_bar(self):
        with self.assertRaises(ValueError) as raised:
            self.draw(stage_rows("kbuffer", "k=16", "layers=32") + stage_rows("kbuffer", "", "layers=32"))
        self.assertIn("labels kbuffer each name several configurations", str(raised.exception))

    def test_more_configurations_than_a_png_can_hold_are_an_error(self):
        rows = [fx.row("unsorted", s, 1.0, scene_params=f"layers={n}") for n in range(300) for s in ("fill", "total")]
        with self.assertRaises(ValueError) as raised:
            self.draw(rows)
        self.assertIn("300 scene configurations do not fit one figure (436 in high): choose some with --scene or "
                      "--clock", str(raised.exception))

    def test_out_must_be_a_png(self):
        result = subprocess.run([sys.executable, "-m", "analysis.plot_stages", "runs.csv", "--out", "x.jpg"],
                                cwd=os.path.join(HERE, ".."), capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("--out x.jpg: name a .png file (an .svg is written beside it)", result.stderr)


class ParetoNamesTest(unittest.TestCase):
    def totals(self, rows):
        with tempfile.TemporaryDirectory() as tmp:
            return pareto.load_totals(runs_csv(tmp, rows), "error_rmse")

    def test_names_tell_every_configuration_apart(self):
        rows = [fx.row("unsorted", "total", 1.0, scene_params=f"layers={n} seed=1", clock=clock)
                for n in (32, 64) for clock in ("gl", "wall")]
        names = pareto.file_names(self.totals(rows), "sweep_a")
        self.assertEqual(sorted(names.values()),
                         ["sweep_a_quads_layers-32_64x64_gl.png", "sweep_a_quads_layers-32_64x64_wall.png",
                          "sweep_a_quads_layers-64_64x64_gl.png", "sweep_a_quads_layers-64_64x64_wall.png"])

    def test_a_name_two_configurations_would_share_is_an_error(self):
        rows = [fx.row("unsorted", "total", 1.0, scene_params=f"name={n}", scene="model") for n in ("a+b", "a-b")]
        with self.assertRaises(ValueError) as raised:
            pareto.file_names(self.totals(rows), "p")
        self.assertIn("several configurations would be written to p_model_name-a-b_64x64.png", str(raised.exception))

    def test_runs_without_an_error_are_left_out_and_said(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "sweep.csv")
            fx.write_csv(path, [fx.row("unsorted", "total", 1.0, error_rmse=0.1),
                                fx.row("kbuffer", "total", 2.0, params="k=4"),
                                fx.row("kbuffer", "total", 2.0, scene="spheres", scene_params="count=3")])
            result = subprocess.run([sys.executable, "-m", "analysis.pareto", path, "--oitbench", OITBENCH],
                                    cwd=os.path.join(HERE, ".."), capture_output=True, text=True, check=True)
            self.assertEqual(result.stderr, "quads layers=32 | 64x64: 1 run(s) without a time or error_rmse left out\n"
                                            "spheres count=3 | 64x64: 1 run(s) without a time or error_rmse left "
                                            "out\n")
            self.assertEqual(sorted(os.listdir(tmp)), ["sweep.csv", "sweep_quads_64x64.png", "sweep_quads_64x64.svg"])

    def test_every_text_is_at_least_9_points_and_the_front_is_listed(self):
        rows = [fx.row("kbuffer", "total", ms, params=f"k={k} tail=drop", error_rmse=err)
                for k, ms, err in ((4, 1.0, 0.1), (16, 3.0, 0.0), (8, 2.0, 0.2))]
        (name, fig, front), = pareto.figures(self.totals(rows), DEFAULTS, "error_rmse", "p")
        self.assertEqual(name, "p_quads_64x64.png")
        self.assertEqual(list(front["short"]), ["kbuffer k=4", "kbuffer"])
        fig.canvas.draw()
        texts = [t for t in fig.findobj(matplotlib.text.Text) if t.get_text() and t.get_visible()]
        self.assertIn("Pareto front, fastest first:\n1 kbuffer k=4\n2 kbuffer", [t.get_text() for t in texts])
        self.assertGreaterEqual(min(t.get_fontsize() for t in texts), presentation.SMALLEST_POINTS)

    def test_a_replaced_plot_is_said(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "sweep.csv")
            fx.write_csv(path, [fx.row("unsorted", "total", 1.0, error_rmse=0.1)])
            command = [sys.executable, "-m", "analysis.pareto", path, "--oitbench", OITBENCH]
            first = subprocess.run(command, cwd=os.path.join(HERE, ".."), capture_output=True, text=True, check=True)
            second = subprocess.run(command, cwd=os.path.join(HERE, ".."), capture_output=True, text=True, check=True)
            png = os.path.join(tmp, "sweep_quads_64x64.png")
            svg = os.path.join(tmp, "sweep_quads_64x64.svg")
            self.assertIn(f"wrote {png} and {svg}\n", first.stdout)
            self.assertIn(f"wrote {png} and {svg} (replaced {png}, {svg})\n", second.stdout)


class ResultsIoTest(unittest.TestCase):
    """Plots are written whole or not at all; only whole runs are read."""

    def figure(self):
        fig, ax = plt.subplots()
        ax.plot([0, 1], [1, 0])
        return fig

    def test_a_plot_is_written_whole_with_no_temporary_left(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "plots", "fig.png")
            results_io.save_figure(self.figure(), out, dpi=50)
            with open(out, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
            self.assertEqual(os.listdir(os.path.dirname(out)), ["fig.png"])
            self.assertEqual(os.stat(out).st_mode & 0o077, 0o666 & ~self.umask() & 0o077)

    def umask(self):
        mask = os.umask(0)
        os.umask(mask)
        return mask

    def test_a_link_to_a_device_refusing_writes_raises_naming_the_file(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "fig.png")
            os.symlink("/dev/full", out)
            with self.assertRaises(OSError) as raised:
                results_io.save_figure(self.figure(), out)
            self.assertIn(f"cannot write '{out}': it is not a regular file", str(raised.exception))
            self.assertTrue(os.path.islink(out))

    def test_a_full_disk_raises_naming_the_file_and_leaves_nothing(self):
        # A file-size limit on a child process: its writes fail as on a full disk.
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "fig.png")
            code = ("import resource, signal, sys; sys.path.insert(0, sys.argv[2]);"
                    "signal.signal(signal.SIGXFSZ, signal.SIG_IGN);"
                    "resource.setrlimit(resource.RLIMIT_FSIZE, (1000, 1000));"
                    "import matplotlib; matplotlib.use('Agg'); import matplotlib.pyplot as plt;"
                    "from analysis import results_io;"
                    "fig, ax = plt.subplots(); ax.plot([0, 1], [1, 0]); results_io.save_figure(fig, sys.argv[1])")
            result = subprocess.run([sys.executable, "-c", code, out, os.path.join(HERE, "..")], capture_output=True,
                                    text=True)
            self.assertNotEqual(result.returncode, 0)
            self.assertIn(f"cannot write '{out}': [Errno 27] File too large", result.stderr)
            self.assertEqual(os.listdir(tmp), [])

    def test_readers_keep_only_whole_runs(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv_path = runs_csv(tmp, [fx.row("unsorted", s, 1.0) for s in ("fill", "compose", "total")] +
                                [fx.row("kbuffer", s, 2.0, params="k=8") for s in ("fill", "compose", "total")])
            with open(csv_path) as f:
                lines = f.readlines()
            with open(csv_path, "w") as f:  # the kbuffer run cut after 2 of its 3 rows, the second mid-line
                f.writelines(lines[:-2])
                f.write(lines[-2][:40])
            runs = plot_stages.load_runs(csv_path)
            self.assertEqual(sorted(runs["technique"].unique()), ["unsorted"])
            self.assertEqual(len(runs), 3)
            rows = reproduce.read_rows(csv_path)
            self.assertEqual([r["technique"] for r in rows], ["unsorted"] * 3)


if __name__ == "__main__":
    unittest.main()
