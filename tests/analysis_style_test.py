#!/usr/bin/python3
"""The plots' one visual identity (analysis/presentation.py): every
registered technique has its own colour, marker and hatch from the
colour-blind-safe palettes, and the plots draw with them; the stages of a
plot have distinct colours; the Pareto plot carries confidence intervals and
rings the points it cannot tell from the front; pastyrik2016 Figs. 11-14 as
parallel coordinates. Argument: the built oitbench (its `list --markdown`
names the registered techniques)."""
import csv
import os
import re
import subprocess
import sys
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, REPO)
sys.path.insert(0, HERE)
import analysis_fixtures as fx  # noqa: E402
from analysis import (approximate_oit, common, oit_comparison, pareto, pastyrik_fig11_14,  # noqa: E402
                      peeling_stages, plot_stages, presentation)

OITBENCH = sys.argv.pop(1) if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else None


def registered_techniques():
    """Technique ids: the folders under algorithms/ that register one, and
    (with the built oitbench) every id `oitbench list --markdown` prints."""
    ids = set()
    for folder in os.listdir(os.path.join(REPO, "algorithms")):
        path = os.path.join(REPO, "algorithms", folder)
        if os.path.isdir(path):
            for name in os.listdir(path):
                if name.endswith(".cpp"):
                    with open(os.path.join(path, name)) as f:
                        ids.update(re.findall(r'\.id = "([a-z_0-9]+)"', f.read()))
    if OITBENCH:
        listing = subprocess.run([OITBENCH, "list", "--markdown"], capture_output=True, text=True, check=True).stdout
        ids.update(presentation.parse_technique_table(listing))
    return ids


class TechniqueStyleTest(unittest.TestCase):
    def test_every_registered_technique_has_a_style_of_its_own(self):
        ids = registered_techniques()
        self.assertGreaterEqual(len(ids), 15)
        self.assertEqual(sorted(ids - set(presentation.TECHNIQUE_STYLES)), [])
        styles = [presentation.technique_style(t) for t in sorted(ids)]
        for part in ("colour", "marker", "hatch"):
            values = [getattr(s, part) for s in styles]
            self.assertEqual(len(set(values)), len(values), f"two techniques share a {part}")

    def test_colours_come_from_the_colour_blind_safe_palettes(self):
        safe = set(presentation.OKABE_ITO.values()) | set(presentation.TOL_MUTED.values())
        self.assertLessEqual({s.colour for s in presentation.TECHNIQUE_STYLES.values()}, safe)
        self.assertLessEqual(set(presentation.STAGE_COLOURS.values()), safe)

    def test_an_unlisted_technique_is_drawn_grey_and_said(self):
        self.assertEqual(presentation.technique_style("brand_new"), presentation.UNLISTED_STYLE)


class StageColoursTest(unittest.TestCase):
    def test_every_stage_of_a_plot_has_its_own_colour(self):
        stages = list(presentation.STAGE_COLOURS) + ["blend_tail", "build_histogram"]
        colours = presentation.stage_colours(stages)
        self.assertEqual(set(colours), set(stages))
        self.assertEqual(len(set(colours.values())), len(stages))

    def test_a_stage_keeps_its_colour_from_plot_to_plot(self):
        self.assertEqual(presentation.stage_colours(["fill", "compose"])["fill"],
                         presentation.stage_colours(["count", "clear", "fill"])["fill"])

    def test_too_many_unknown_stages_are_an_error_naming_them(self):
        with self.assertRaises(ValueError) as raised:
            presentation.stage_colours([f"stage{i}" for i in range(20)])
        self.assertIn("stage19", str(raised.exception))

    def test_plot_stages_draws_count_fill_clear_and_peel_apart(self):
        # Before: tab10 in stage order gave count and fill two oranges, clear and peel two blues.
        rows = [fx.row("linked_list", stage, ms, params="sort=network") for stage, ms in
                (("count", 1.0), ("clear", 1.0), ("fill", 2.0), ("compose", 1.0), ("total", 5.5))]
        rows += [fx.row("depth_peeling", stage, ms) for stage, ms in (("clear", 1.0), ("peel", 3.0), ("total", 4.5))]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "runs.csv")
            fx.write_csv(path, rows)
            fig = plot_stages.draw(plot_stages.load_runs(path), None)
        legend = fig.axes[-1].get_legend()
        handles = getattr(legend, "legend_handles", None) or legend.legendHandles  # the name before matplotlib 3.7
        colours = {t.get_text(): mcolors.to_hex(h.get_facecolor()) for t, h in zip(legend.get_texts(), handles)
                   if t.get_text() != "total (whisker: p05..p95)"}
        self.assertEqual(sorted(colours), ["clear", "compose", "count", "fill", "peel"])
        self.assertEqual(len(set(colours.values())), 5)
        self.assertEqual(colours["fill"], presentation.STAGE_COLOURS["fill"].lower())
        plt.close(fig)


def write_csv_with(path, rows, extra_columns):
    """A CSV in the harness's layout plus `extra_columns` (columns the harness
    is adding, e.g. ci_low_ms)."""
    columns = fx.csv_columns() + [c for c in extra_columns if c not in fx.csv_columns()]
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, restval="", lineterminator="\n")
        writer.writeheader()
        writer.writerows(fx.with_run_columns(rows))


class ParetoIntervalsTest(unittest.TestCase):
    # (technique, params, median, ci_low, ci_high, p05, p95, error)
    RUNS = [("unsorted", "", 1.0, 0.9, 1.1, 0.5, 3.0, 0.3),
            ("kbuffer", "k=4", 2.0, 1.8, 2.2, 1.0, 4.0, 0.1),
            ("kbuffer", "k=8", 2.1, 1.9, 2.4, 1.0, 4.0, 0.15),  # off the front, its CI overlaps k=4's
            ("weighted_blended", "", 5.0, 4.8, 5.3, 1.0, 9.0, 0.2),  # beaten for sure by k=4
            ("kbuffer", "k=32", 8.0, 7.5, 8.5, 6.0, 10.0, 0.0)]

    def draw(self, with_ci):
        rows = []
        for technique, params, median, low, high, p05, p95, error in self.RUNS:
            fields = dict(p05_ms=p05, p95_ms=p95, error_rmse=error)
            if with_ci:
                fields.update(ci_low_ms=low, ci_high_ms=high)
            rows.append(fx.row(technique, "total", median, params=params, **fields))
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "pareto.csv")
            write_csv_with(path, rows, ["ci_low_ms", "ci_high_ms"])
            totals = pareto.load_totals(path, "error_rmse")
        ((_, fig, front),) = list(pareto.figures(totals, None, "error_rmse", "p"))
        return fig.axes[0], front

    def whiskers(self, ax):
        """{rounded median: (low, high)} of every error bar drawn."""
        ends = {}
        for collection in ax.collections:
            if isinstance(collection, matplotlib.collections.LineCollection):
                for segment in collection.get_segments():
                    if len(segment):
                        ends[round(float(np.mean(segment[:, 1])), 6), round(float(segment[0, 0]), 6)] = (
                            float(segment[0, 0]), float(segment[1, 0]))
        return {low: (low, high) for (_, low), (low, high) in ends.items()}

    def test_whiskers_are_the_confidence_intervals_and_the_legend_says_so(self):
        ax, front = self.draw(with_ci=True)
        self.assertEqual(list(front["label"]), ["unsorted", "kbuffer k=4", "kbuffer k=32"])
        whiskers = self.whiskers(ax)
        self.assertEqual(sorted(whiskers), [0.9, 1.8, 1.9, 4.8, 7.5])
        self.assertEqual(whiskers[1.9], (1.9, 2.4))
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        self.assertIn("whisker: 95% CI of the median", legend)
        self.assertIn("95% CI", ax.get_xlabel())

    def test_only_the_point_whose_interval_overlaps_the_front_is_ringed(self):
        ax, _ = self.draw(with_ci=True)
        rings = [c for c in ax.collections if c.get_label().startswith("off the front, not distinguishable")]
        self.assertEqual(len(rings), 1)
        np.testing.assert_allclose(rings[0].get_offsets(), [[2.1, 0.15]])

    def test_without_intervals_the_whiskers_are_p05_p95_and_said(self):
        ax, _ = self.draw(with_ci=False)
        self.assertEqual(sorted(self.whiskers(ax)), [0.5, 1.0, 6.0])  # 1.0: three runs share p05
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        self.assertIn("whisker: p05..p95 of the frames (no CI in this CSV)", legend)

    def test_a_point_without_an_interval_is_not_judged(self):
        points = pareto.pd.DataFrame({"time_ms": [1.0, 2.0], "error": [0.0, 0.5]})
        low, high = pareto.pd.Series([0.9, float("nan")]), pareto.pd.Series([1.1, float("nan")])
        self.assertEqual(pareto.indistinguishable_from_front(points, points.iloc[:1], low, high), [])
        # With an interval [1.0, 2.5] overlapping the front point's [0.9, 1.1] it is ringed.
        low, high = pareto.pd.Series([0.9, 1.0]), pareto.pd.Series([1.1, 2.5])
        self.assertEqual(pareto.indistinguishable_from_front(points, points.iloc[:1], low, high), [1])

    def test_points_take_their_technique_colour_and_marker(self):
        ax, _ = self.draw(with_ci=True)
        dots = {c.get_label(): c for c in ax.collections if c.get_label() in ("kbuffer", "unsorted")}
        self.assertEqual(mcolors.to_hex(dots["kbuffer"].get_facecolor()[0]),
                         presentation.technique_style("kbuffer").colour.lower())

    def tearDown(self):
        plt.close("all")


class ImageGridTest(unittest.TestCase):
    """approximate_oit's grid follows the harness's image conventions."""

    def test_reference_first_srgb_display_and_log_viridis_error_with_a_colour_bar(self):
        reference = np.full((4, 4, 3), 0.2, dtype=np.float32)
        image = reference.copy()
        image[0, 0] = [0.7, 0.2, 0.2]  # error 0.5 in one pixel, 0 elsewhere
        fig, errors = approximate_oit.draw_grid(reference, [image], ["kbuffer:k=4"], "t")
        top, bottom = fig.axes[0], fig.axes[3]  # row by row: reference, image; its cell, the error
        self.assertEqual(top.get_title(), "reference (exact)")
        # Linear 0.2 is shown as sRGB 0.484, as the harness's display PNGs.
        self.assertAlmostEqual(float(top.images[0].get_array()[1, 1, 0]), 0.4845, places=3)
        heat = bottom.images[0]
        self.assertEqual(heat.get_cmap().name, "viridis")
        self.assertIsInstance(heat.norm, matplotlib.colors.LogNorm)
        self.assertEqual((heat.norm.vmin, heat.norm.vmax), (1e-4, 1.0))
        self.assertAlmostEqual(float(errors[0].max()), 0.5)
        self.assertTrue(any("reference|" in ax.get_ylabel() for ax in fig.axes))  # the colour bar
        plt.close(fig)


def model_rows():
    rows = []
    for model, total in {"bunny": 30.0, "engine": 10.0, "bones": 20.0}.items():
        fields = dict(scene="model", scene_params=f"name={model} alpha=0.4", width=128, height=128,
                      fragments=int(total * 1000), max_depth_complexity=int(total), psi=total / 100,
                      extra=f"scene_triangles={int(total * 10)} scene_vertices={int(total * 5)}", passes=4)
        for technique, scale in (("depth_peeling", 2.0), ("linked_list", 0.5), ("dual_depth_peeling", 3.0),
                                 ("illustration_buffer", 1.0), ("kbuffer", 0.25)):
            rows.append(fx.row(technique, "total", total * scale, **fields))
            if "peeling" in technique:
                rows.append(fx.row(technique, "peel", total * scale * 0.9, **fields))
    return rows


class FigureStyleTest(fx.TempDirTest):
    def setUp(self):
        super().setUp()
        fx.write_csv(self.csv, model_rows())
        self.runs = common.load(self.csv)

    def tearDown(self):
        plt.close("all")

    def test_comparison_hatches_are_the_techniques_own(self):
        ax = oit_comparison.draw(self.runs).axes[0]
        for container in ax.containers:
            self.assertEqual({p.get_hatch() for p in container},
                             {presentation.technique_style(container.get_label()).hatch})

    def test_peeling_bars_take_their_technique_colour(self):
        top = peeling_stages.draw(self.runs).axes[0]
        for container in top.containers:
            self.assertEqual({mcolors.to_hex(p.get_facecolor()) for p in container},
                             {presentation.technique_style(container.get_label()).colour.lower()})

    def test_parallel_coordinates_one_panel_per_technique_lines_coloured_by_thirds(self):
        fig = pastyrik_fig11_14.draw(self.runs)
        titles = [ax.get_title() for ax in fig.axes]
        self.assertEqual(titles, ["Fig. 11: depth_peeling (3 model positions)",
                                  "Fig. 12: dual_depth_peeling (3 model positions)",
                                  "Fig. 13: linked_list (3 model positions)",
                                  "Fig. 14: illustration_buffer (3 model positions)"])
        ax = fig.axes[3]
        self.assertEqual([t.get_text() for t in ax.get_xticklabels()],
                         ["vertices (log)", "fragments (log)", "longest list", "Psi", "total ms (log)"])
        lines = {line.get_label(): line for line in ax.get_lines() if not line.get_label().startswith("_")}
        self.assertEqual(sorted(lines), ["bones", "bunny", "engine"])
        # Time 10, 20, 30 ms: fastest, middle, slowest third; each axis spans 0..1.
        green, blue, red = (mcolors.to_hex(c) for c in oit_comparison.THIRD_COLOURS)
        self.assertEqual([mcolors.to_hex(lines[m].get_color()) for m in ("engine", "bones", "bunny")],
                         [green, blue, red])
        np.testing.assert_allclose(lines["engine"].get_ydata(), [0, 0, 0, 0, 0])
        np.testing.assert_allclose(lines["bunny"].get_ydata(), [1, 1, 1, 1, 1])
        # Linear Psi axis: bones (0.2) in the middle of 0.1..0.3.
        self.assertAlmostEqual(lines["bones"].get_ydata()[3], 0.5)
        texts = [t.get_text() for t in ax.texts]
        self.assertIn("10", texts)  # the time axis' ends
        self.assertIn("30", texts)

    def test_both_tie_breaks_are_bars_of_their_own_and_the_comparison_takes_the_canonical_one(self):
        rows = [dict(r, params="tie_break=submission") if "peeling" in r["technique"] else r for r in model_rows()]
        rows += [dict(r, params="tie_break=triangle_id", median_ms=str(float(r["median_ms"]) * 10))
                 for r in model_rows() if "peeling" in r["technique"]]
        path = self.path("ties.csv")
        fx.write_csv(path, rows)
        runs = common.load(path)
        top = peeling_stages.draw(runs).axes[0]
        self.assertEqual([c.get_label() for c in top.containers],
                         ["depth_peeling tie_break=submission", "depth_peeling tie_break=triangle_id",
                          "dual_depth_peeling tie_break=submission", "dual_depth_peeling tie_break=triangle_id"])
        exact = top.containers[1]
        self.assertEqual({mcolors.to_hex(p.get_facecolor()) for p in exact}, {"#ffffff"})  # hollow
        np.testing.assert_allclose(sorted(p.get_height() for p in top.containers[0]), [20, 40, 60])
        np.testing.assert_allclose(sorted(p.get_height() for p in exact), [200, 400, 600])
        bars = {c.get_label(): c for c in oit_comparison.draw(runs).axes[0].containers}
        np.testing.assert_allclose(sorted(p.get_height() for p in bars["depth_peeling"]), [20, 40, 60])

    def test_no_peeling_list_or_buffer_rows_is_no_data(self):
        path = self.path("k.csv")
        fx.write_csv(path, [r for r in model_rows() if r["technique"] == "kbuffer"])
        with self.assertRaises(common.NoData):
            pastyrik_fig11_14.draw(common.load(path))


if __name__ == "__main__":
    unittest.main()
