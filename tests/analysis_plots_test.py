#!/usr/bin/python3
"""The paper plots of analysis/ on fixture CSVs with known numbers: each test
checks the series the figure holds (labels, x and y data, axis scales, title),
not only that a PNG appears."""
import os
import subprocess
import sys
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
import analysis_fixtures as fx  # noqa: E402
from analysis import (carnecky_fig14, carnecky_fig15, carnecky_images, common, figure_configs,  # noqa: E402
                      murray_fig10, oit_comparison, pastyrik_fig8, pastyrik_fig9, pastyrik_fig10, presentation,
                      time_per_fragment)


def stack_tops(ax):
    """Upper edge of each stacked area, bottom to top: at each x, the highest
    vertex of the area's outline."""
    tops = []
    for collection in ax.collections:
        vertices = collection.get_paths()[0].vertices
        xs = sorted(set(vertices[:, 0]))
        tops.append(np.array([vertices[vertices[:, 0] == x, 1].max() for x in xs]))
    return tops


class PlotTest(fx.TempDirTest):
    def tearDown(self):
        plt.close("all")

    def draw(self, module, rows, args=None):
        fx.write_csv(self.csv, rows)
        return module.draw(common.load(self.csv), args)

    def assert_title(self, ax_or_fig, size):
        text = ax_or_fig.get_title() if hasattr(ax_or_fig, "get_title") else ax_or_fig._suptitle.get_text()
        for part in (fx.DEVICE, size, "2026-11-22", "clock wall"):
            self.assertIn(part, text)


class MurrayFig10Test(PlotTest):
    def rows(self, with_brute=True, with_kbuffer=True):
        rows = []
        for objects in (1, 2, 4):
            sp = f"layers=32 objects={objects} seed=1"
            stages = {"clear": 0.5, "fill": 2.0, "bucket": 1.0, "neighbors": 3.0 / objects, "stylize": 1.0,
                      "compose": 0.5}
            for stage, ms in stages.items():
                rows.append(fx.row("bucketed_kbuffer", stage, ms, params="buckets=on k=8", scene_params=sp))
            rows.append(fx.row("bucketed_kbuffer", "total", sum(stages.values()) + 0.1, params="buckets=on k=8",
                               scene_params=sp))
            if with_brute:
                rows.append(fx.row("bucketed_kbuffer", "neighbors", 3.0, params="buckets=off k=8", scene_params=sp))
                rows.append(fx.row("bucketed_kbuffer", "total", 9.0, params="buckets=off k=8", scene_params=sp))
            if with_kbuffer:
                rows.append(fx.row("kbuffer", "total", 2.0 + objects, params="k=8", scene_params=sp))
        rows.append(fx.row("bucketed_kbuffer", "", "", params="k=8", status="skipped", message="x"))
        return rows

    def test_stacked_stage_groups_brute_force_and_kbuffer_lines(self):
        ax = self.draw(murray_fig10, self.rows()).axes[0]
        self.assertEqual([c.get_label() for c in ax.collections],
                         ["clear", "fill/sort/bucket/store", "neighbors", "stylize", "compose"])
        tops = stack_tops(ax)
        np.testing.assert_allclose(tops[1], [3.5, 3.5, 3.5])  # clear + fill + bucket, cumulative
        np.testing.assert_allclose(tops[-1], [8.0, 6.5, 5.75])  # everything: neighbours shrink with objects
        lines = {line.get_label(): line for line in ax.get_lines()}
        self.assertEqual(lines["brute force (buckets=off), total"].get_linestyle(), ":")
        np.testing.assert_allclose(lines["brute force (buckets=off), total"].get_ydata(), [9, 9, 9])
        np.testing.assert_allclose(lines["kbuffer alone, total"].get_xdata(), [1, 2, 4])
        np.testing.assert_allclose(lines["kbuffer alone, total"].get_ydata(), [3, 4, 6])
        self.assertEqual(ax.get_xscale(), "log")
        self.assert_title(ax, "64x64")

    def test_the_merge_search_is_a_line_of_its_own_not_an_area(self):
        rows = self.rows(False, False)
        for objects in (1, 2, 4):
            sp = f"layers=32 objects={objects} seed=1"
            rows.append(fx.row("bucketed_kbuffer", "neighbors", 0.5, params="buckets=on k=8 neighbor_search=merge",
                               scene_params=sp))
            rows.append(fx.row("bucketed_kbuffer", "total", 4.0, params="buckets=on k=8 neighbor_search=merge",
                               scene_params=sp))
        figure = self.draw(murray_fig10, rows)
        ax, own = figure.axes[0], figure.axes[1]
        np.testing.assert_allclose(stack_tops(ax)[-1], [8.0, 6.5, 5.75])  # the areas: the bucket query alone
        lines = {line.get_label(): line for line in ax.get_lines()}
        self.assertEqual(lines["merge search (neighbor_search=merge), total"].get_linestyle(), "-.")
        np.testing.assert_allclose(lines["merge search (neighbor_search=merge), total"].get_ydata(), [4, 4, 4])
        own_lines = {line.get_label(): line for line in own.get_lines()}
        np.testing.assert_allclose(own_lines["neighbors (merge search)"].get_ydata(), [0.5, 0.5, 0.5])

    def test_without_brute_force_or_kbuffer_only_the_areas(self):
        ax = self.draw(murray_fig10, self.rows(False, False)).axes[0]
        self.assertEqual(len(ax.collections), 5)
        self.assertEqual([line.get_label() for line in ax.get_lines()], [])

    def test_a_stage_outside_the_groups_gets_its_own_area_before_compose(self):
        rows = self.rows(False, False)
        rows += [fx.row("bucketed_kbuffer", "peel", 1.0, params="buckets=on k=8",
                        scene_params=f"layers=32 objects={n} seed=1") for n in (1, 2, 4)]
        ax = self.draw(murray_fig10, rows).axes[0]
        self.assertEqual([c.get_label() for c in ax.collections],
                         ["clear", "fill/sort/bucket/store", "neighbors", "stylize", "peel", "compose"])

    def test_no_bucketed_rows_is_no_data(self):
        with self.assertRaises(common.NoData):
            self.draw(murray_fig10, [fx.row("kbuffer", "total", 1.0)])


class CarneckyTest(PlotTest):
    STAGES = ["clear", "fill", "sort", "neighbors", "stylize_init", "diffuse", "compose"]

    def rows(self):
        rows = []
        for side in (128, 256):
            for view, fragments in ((0, 1000 * side), (1, 3000 * side)):
                for slices, triangles in ((16, 256), (64, 4096)):
                    common_fields = dict(scene="torus", scene_params=f"slices={slices} stacks={slices // 2}",
                                         camera=f"random:2:1@{view}", width=side, height=side, fragments=fragments,
                                         extra=f"scene_triangles={triangles} scene_vertices={triangles // 2}")
                    for i, stage in enumerate(self.STAGES):
                        ms = (i + 1) * side / 128 * (1 + view) * (2 if stage == "fill" and slices == 64 else 1)
                        rows.append(fx.row("illustration_buffer", stage, ms, **common_fields))
                    rows.append(fx.row("illustration_buffer", "total", 100.0 * side / 128 + view, **common_fields))
        rows.append(fx.row("linked_list", "total", 1.0, scene="torus"))
        return rows

    def test_fig14_fragments_on_x_averaged_over_views(self):
        rows = [r for r in self.rows() if r["scene_params"].startswith("slices=16") or r["technique"] != "illustration_buffer"]
        ax = self.draw(carnecky_fig14, rows).axes[0]
        # The paper's passes (its section 7): connect = the neighbour search (4.4) and the fields' initial
        # values and boundary rules (5.2, 5.3); solve = one diffusion iteration (5.4).
        self.assertEqual([c.get_label() for c in ax.collections],
                         ["clear", "fill", "sort", "connect (neighbors + stylize_init)", "solve (diffuse)", "compose"])
        total = [line for line in ax.get_lines() if line.get_label() == "total"][0]
        np.testing.assert_allclose(total.get_xdata(), [2000 * 128, 2000 * 256])  # mean over the two views
        np.testing.assert_allclose(total.get_ydata(), [100.5, 200.5])
        tops = stack_tops(ax)
        # connect = neighbors (4) + stylize_init (5); solve = diffuse (6); mean over views (x1.5).
        np.testing.assert_allclose(tops[3] - tops[2], [(4 + 5) * 1.5, (4 + 5) * 3.0])
        np.testing.assert_allclose(tops[4] - tops[3], [6 * 1.5, 6 * 3.0])
        # Cumulative: the top of the stack is the sum of the seven stages.
        np.testing.assert_allclose(tops[-1], [28 * 1.5, 56 * 1.5])
        # Each pass has its own colour.
        colours = [tuple(c.get_facecolor()[0][:3]) for c in ax.collections]
        self.assertEqual(len(set(colours)), len(colours))

    def test_fig14_a_csv_with_one_stylize_stage_names_what_it_holds(self):
        rows = [dict(r, stage="stylize") if r["stage"] == "stylize_init" else r for r in self.rows()
                if r["stage"] != "diffuse" and r["scene_params"].startswith("slices=16")]
        ax = self.draw(carnecky_fig14, rows).axes[0]
        self.assertEqual([c.get_label() for c in ax.collections],
                         ["clear", "fill", "sort", "connect (neighbors)",
                          "connect 5.2-5.3 + solve, older CSV (stylize)", "compose"])
        self.assertIn("mean over 2 camera view(s)", ax.get_title())
        self.assert_title(ax, "128x128..256x256")

    def test_fig15_triangles_from_the_extra_column(self):
        rows = [r for r in self.rows() if r["width"] == "256"]
        ax = self.draw(carnecky_fig15, rows).axes[0]
        self.assertEqual(ax.get_xlabel(), "number of triangles")
        total = [line for line in ax.get_lines() if line.get_label() == "total"][0]
        np.testing.assert_allclose(total.get_xdata(), [256, 4096])
        fill_top = stack_tops(ax)[1]  # clear + fill: only fill grows with the triangles
        np.testing.assert_allclose(fill_top, [(2 + 4) * 1.5, (2 + 8) * 1.5])
        self.assert_title(ax, "256x256")


class CarneckyImagesTest(PlotTest):
    def test_fig9_row_holds_the_papers_five_columns_in_order_at_readable_sizes(self):
        import json

        images = self.path("images")
        os.makedirs(images)
        captions = {name: caption for name, caption, _ in figure_configs.CARNECKY_FIG9}
        captions.update({"fig10_constant": "constant transparency", "fig10_ours": "illustration buffer",
                         "fig09_stale": "an image of an older grid"})
        for name in captions:
            if name != "fig09_stale":  # listed without its image: left out
                plt.imsave(os.path.join(images, f"{name}.png"), np.full((8, 8, 3), 0.5))
        with open(os.path.join(images, "captions.json"), "w") as f:
            json.dump(captions, f)
        fig = carnecky_images.draw_directory(images)
        titled = [ax for ax in fig.axes if ax.get_title()]
        self.assertEqual([ax.get_title().replace("\n", " ") for ax in titled[:5]],
                         [caption for _, caption, _ in figure_configs.CARNECKY_FIG9])
        self.assertEqual(len(titled), 7)
        self.assertEqual(len(fig.axes), 10)  # two rows of five
        sizes = [t.get_fontsize() for t in fig.findobj(matplotlib.text.Text) if t.get_text()]
        self.assertGreaterEqual(min(sizes), presentation.SMALLEST_POINTS)
        plt.close(fig)


class PastyrikTest(PlotTest):
    MODELS = {"bunny": 30.0, "engine": 10.0, "bones": 20.0}

    def rows(self):
        rows = []
        for model, total in self.MODELS.items():
            fields = dict(scene="model", scene_params=f"name={model} alpha=0.4", width=128, height=128,
                          fragments=int(total * 1000), max_depth_complexity=int(total), psi=total / 100,
                          extra=f"scene_triangles={int(total * 10)} scene_vertices={int(total * 5)}")
            for stage, share in (("clear", 0.1), ("fill", 0.3), ("sort", 0.2), ("neighbors", 0.3),
                                 ("stylize", 0.05), ("compose", 0.05)):
                rows.append(fx.row("illustration_buffer", stage, total * share, **fields))
            rows.append(fx.row("illustration_buffer", "total", total, **fields))
            for technique, scale in (("depth_peeling", 2.0), ("linked_list", 0.5), ("dual_depth_peeling", 3.0),
                                     ("kbuffer", 0.25), ("reference", 9.0)):
                rows.append(fx.row(technique, "total", total * scale + (5 if model == "bunny" else 0), **fields))
        return rows

    def test_fig8_cumulative_lines_models_sorted_by_total(self):
        ax = self.draw(pastyrik_fig8, self.rows()).axes[0]
        self.assertEqual([t.get_text() for t in ax.get_xticklabels()], ["engine", "bones", "bunny"])
        lines = {line.get_label(): line for line in ax.get_lines()}
        self.assertEqual(list(lines), ["clear", "fill", "sort", "neighbors", "stylize", "compose", "total"])
        np.testing.assert_allclose(lines["fill"].get_ydata(), [4.0, 8.0, 12.0])  # clear + fill
        np.testing.assert_allclose(lines["compose"].get_ydata(), [10.0, 20.0, 30.0])
        self.assert_title(ax, "128x128")

    def test_fig9_log_axis_and_psi_on_a_second_axis(self):
        fig = self.draw(pastyrik_fig9, self.rows())
        ax, time_ax, psi_ax = fig.axes  # counts, time on its own axis below, Psi twin of the counts
        self.assertEqual(ax.get_yscale(), "log")
        lines = {line.get_label(): line for line in ax.get_lines()}
        self.assertEqual(list(lines), ["vertices", "fragments", "max list length"])
        self.assertEqual(time_ax.get_yscale(), "linear")
        times = {line.get_label(): line for line in time_ax.get_lines()}
        np.testing.assert_allclose(times["total time (ms)"].get_ydata(), [10, 20, 30])
        np.testing.assert_allclose(times["neighbour stage time (ms)"].get_ydata(), [3, 6, 9])
        np.testing.assert_allclose(lines["vertices"].get_ydata(), [50, 100, 150])
        np.testing.assert_allclose(lines["max list length"].get_ydata(), [10, 20, 30])
        (psi,) = psi_ax.get_lines()
        self.assertEqual(psi.get_label(), "Psi")
        self.assertEqual(psi.get_linestyle(), "--")
        np.testing.assert_allclose(psi.get_ydata(), [0.1, 0.2, 0.3])
        self.assertEqual([t.get_text() for t in ax.get_legend().get_texts()][-1], "Psi")

    def test_fig10_one_panel_per_heatmap_in_total_order(self):
        heatmaps = self.path("heatmaps")
        os.makedirs(heatmaps)
        for model in ("bunny", "engine"):  # bones has none: left out, not an error
            plt.imsave(os.path.join(heatmaps, f"heatmap_{model}.png"), np.zeros((4, 4, 3)))
        import argparse
        fig = self.draw(pastyrik_fig10, self.rows(), argparse.Namespace(heatmaps=heatmaps))
        titles = [ax.get_title() for ax in fig.axes if ax.images]
        self.assertEqual(titles, ["engine\nlongest 10, Psi 0.100", "bunny\nlongest 30, Psi 0.300"])
        self.assert_title(fig, "128x128")

    def test_comparison_grouped_bars_coloured_by_thirds(self):
        ax = self.draw(oit_comparison, self.rows()).axes[0]
        self.assertEqual(ax.get_yscale(), "log")
        bars = {c.get_label(): c for c in ax.containers}
        # The paper's four first, then the rest; the reference is not a contender.
        self.assertEqual(list(bars), ["depth_peeling", "dual_depth_peeling", "linked_list", "illustration_buffer",
                                      "kbuffer"])
        self.assertEqual([t.get_text() for t in ax.get_xticklabels()], ["engine", "bones", "bunny"])
        green, blue, red = (matplotlib.colors.to_rgba(c) for c in oit_comparison.THIRD_COLOURS)
        # illustration_buffer 10, 20, 30: lowest, middle, highest third of its own range.
        self.assertEqual([p.get_facecolor() for p in bars["illustration_buffer"]], [green, blue, red])
        # depth_peeling 20, 40, 65: 40 is in the middle third [35, 50) of [20, 65].
        self.assertEqual([p.get_facecolor() for p in bars["depth_peeling"]], [green, blue, red])
        np.testing.assert_allclose([p.get_height() for p in bars["linked_list"]], [5, 10, 20])
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        self.assertIn("slowest third of its range", legend)

    def test_thirds_of_a_range(self):
        self.assertEqual(list(oit_comparison.thirds(np.array([0.0, 1.0, 1.5, 2.0, 3.0]))), [0, 1, 1, 2, 2])
        self.assertEqual(list(oit_comparison.thirds(np.array([4.0, 4.0]))), [0, 0])


class TimePerFragmentTest(PlotTest):
    def test_one_line_per_technique_in_ns_per_fragment(self):
        rows = []
        for layers in (4, 16):
            fields = dict(scene_params=f"layers={layers}", fragments=64 * 64 * layers, max_depth_complexity=layers)
            rows.append(fx.row("linked_list", "total", 0.004096 * layers * layers, **fields))
            rows.append(fx.row("kbuffer", "total", 0.004096 * layers, params="k=8", **fields))
            rows.append(fx.row("kbuffer", "fill", 0.001, params="k=8", **fields))
            rows.append(fx.row("reference", "total", 99.0, **fields))
        ax = self.draw(time_per_fragment, rows).axes[0]
        lines = {line.get_label(): line for line in ax.get_lines()}
        self.assertEqual(sorted(lines), ["kbuffer", "linked_list"])
        np.testing.assert_allclose(lines["linked_list"].get_xdata(), [4, 16])
        np.testing.assert_allclose(lines["linked_list"].get_ydata(), [4.0, 16.0])  # ms*1e6/(4096*layers)
        np.testing.assert_allclose(lines["kbuffer"].get_ydata(), [1.0, 1.0])
        self.assertEqual((ax.get_xscale(), ax.get_yscale()), ("log", "log"))


class CommandLineTest(PlotTest):
    def run_module(self, module, *args):
        return subprocess.run([sys.executable, "-m", f"analysis.{module}", *args], cwd=os.path.dirname(HERE),
                              capture_output=True, text=True)

    def test_every_module_runs_as_a_command(self):
        fx.write_csv(self.csv, PastyrikTest.rows(PastyrikTest()))
        for module in ("pastyrik_fig8", "pastyrik_fig9", "oit_comparison"):
            out = self.path(f"{module}.png")
            result = self.run_module(module, self.csv, "-o", out)
            self.assertEqual(result.returncode, 0, result.stderr)
            with open(out, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_missing_data_is_a_clear_error(self):
        fx.write_csv(self.csv, [fx.row("kbuffer", "total", 1.0)])
        result = self.run_module("carnecky_fig14", self.csv, "-o", self.path("x.png"))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("no illustration_buffer rows", result.stderr)


if __name__ == "__main__":
    unittest.main()
