#!/usr/bin/python3
"""analysis/figure_configs.py against the built oitbench and against what
analysis.reproduce plans: every technique a figure times has every
parameter the build lists pinned (or named in UNPINNED with its reason),
each pinned value is one the build accepts, and every bench that
`analysis.reproduce --list-commands` prints for --quick and --full sets
exactly the pins of one of its figure's series, at the figure's sizes.
Argument: the built oitbench (only `oitbench list` runs: no GL)."""
import contextlib
import io
import json
import os
import subprocess
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from analysis import figure_configs, reproduce  # noqa: E402

OITBENCH = sys.argv.pop(1) if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else None


def catalogue():
    listing = subprocess.run([OITBENCH, "list"], capture_output=True, text=True, check=True).stdout
    return reproduce.Catalogue(listing)


def every_series():
    return [(name, s) for name, figure in figure_configs.FIGURES.items() for s in figure.series] + [
        ("carnecky_images", figure_configs.Series("illustration_buffer", figure_configs.CARNECKY_IMAGES, ""))] + [
        (f"carnecky_images {column}",
         figure_configs.Series("illustration_buffer", {**figure_configs.CARNECKY_IMAGES, **knobs}, caption))
        for column, caption, knobs in figure_configs.CARNECKY_FIG9]


def as_sent(cat, series):
    """The pins as reproduce sends them to this build (preset=paper where it has one)."""
    return dict(reproduce.pins_for(cat, series.technique, series.pins, []))


class PapersPathsTest(unittest.TestCase):
    """The papers' variants, as the brief of each figure states them."""

    def test_illustration_buffer_on_the_papers_path(self):
        for pins in (figure_configs.CARNECKY, figure_configs.PASTYRIK, figure_configs.CARNECKY_IMAGES):
            for key, value in {"storage": "linked", "diffusion": "steps", "skip_converged": "false",
                               "flat_color_records": "false", "diffusion_tolerance": "0"}.items():
                self.assertEqual(pins[key], value, key)
        self.assertEqual((figure_configs.CARNECKY["iterations"], figure_configs.CARNECKY["neighbors"]),
                         ("1", "heuristic"))
        self.assertEqual(figure_configs.PASTYRIK["neighbors"], "triangle_index")
        # Fig. 7: the paper's static arrays (3 x 64 entries), not sort=array's
        # array sized to the frame's longest list, against its dynamic sort.
        fig7 = {s.pins["sort"]: s.label for s in figure_configs.FIGURES["pastyrik_fig7"].series}
        self.assertEqual(set(fig7), {"static_arrays", "dynamic"})
        self.assertIn("3 static arrays of 64", fig7["static_arrays"])

    def test_carnecky_fig9_columns_follow_the_papers_table(self):
        # carnecky2013 Fig. 9: Diff., Mod. (p), n, lambda_beta per column; lambda_gamma = 0.1 in all.
        table = [("nonphysical", "none", "20", "0.05"), ("nonphysical", "exponential", "20", "0.05"),
                 ("homogeneous", "none", "20", "1"), ("homogeneous", "power", "20", "1"),
                 ("homogeneous", "none", "100", "1")]
        columns = figure_configs.CARNECKY_FIG9
        self.assertEqual([(k["field_diffusion"], k["profile"], k["iterations"], k["lambda_beta"])
                          for _, _, k in columns], table)
        self.assertEqual({k["lambda_gamma"] for _, _, k in columns}, {"0.1"})
        self.assertEqual((columns[1][2]["exponential_p"], columns[3][2]["power_p"]), ("3", "0.3"))
        for (_, caption, knobs), equation in zip(columns, ["eq. 9", "eq. 9", "eq. 8", "eq. 8", "eq. 8"]):
            self.assertTrue(caption.startswith(equation), caption)
            self.assertEqual(("eq. 10" in caption, "eq. 11" in caption),
                             (knobs["profile"] == "exponential", knobs["profile"] == "power"), caption)

    def test_peelings_canonical_first_and_both_variants_labelled(self):
        models = [s for s in figure_configs.FIGURES["models"].series if "peeling" in s.technique]
        self.assertEqual([(s.technique, s.pins["tie_break"]) for s in models],
                         [("depth_peeling", "submission"), ("depth_peeling", "triangle_id"),
                          ("dual_depth_peeling", "submission"), ("dual_depth_peeling", "triangle_id")])
        self.assertTrue(all(s.pins["tie_break"] in s.label for s in models))

    def test_murray_times_the_papers_bucket_query_and_fig8_at_1200x800(self):
        for name in ("murray_models", "murray_fig10"):
            bucketed = [s for s in figure_configs.FIGURES[name].series if s.technique == "bucketed_kbuffer"]
            self.assertEqual((bucketed[0].pins["neighbor_search"], bucketed[0].pins["buckets"]), ("bucket", "on"))
        self.assertIn((1200, 800), figure_configs.FIGURES["murray_models"].sizes["full"])


@unittest.skipIf(OITBENCH is None, "needs the built oitbench as argument")
class AgainstTheBuildTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.catalogue = catalogue()

    def test_every_parameter_of_every_timed_technique_is_pinned(self):
        for name, series in every_series():
            known = self.catalogue.techniques.get(series.technique)
            self.assertIsNotNone(known, f"{name}: {series.technique} is not in this build")
            unpinned = [p for p in known if p not in series.pins and p != "preset"
                        and (series.technique, p) not in figure_configs.UNPINNED]
            self.assertEqual(unpinned, [], f"{name} {series.label}: pin these in analysis/figure_configs.py (or "
                                           f"list them in UNPINNED with the reason)")

    def test_every_pinned_value_is_one_the_build_accepts(self):
        for name, series in every_series():
            for key, value in as_sent(self.catalogue, series).items():
                self.assertIn(key, self.catalogue.techniques[series.technique], f"{name}: {series.technique}.{key}")
                choices = self.catalogue.choices(series.technique, key)
                if choices:
                    self.assertIn(value, choices, f"{name}: {series.technique}.{key}={value}")
                if self.catalogue.is_switch(series.technique, key):
                    self.assertIn(value, ("true", "false"), f"{name}: {series.technique}.{key}={value}")

    def test_the_driver_reads_the_whole_model_list_that_list_would_wrap(self):
        # `list` wraps to 120 columns in a pipe; the model scene's names take more.
        models = reproduce.catalogue_of(OITBENCH, dict(os.environ)).models
        self.assertIn("engine", models)
        self.assertIn("dragon_vrip_res4", models)

    def test_every_timed_technique_of_the_build_is_in_the_comparison(self):
        pinned = {s.technique for s in figure_configs.FIGURES["models"].series}
        self.assertEqual(sorted(set(self.catalogue.timed()) - pinned), [])

    def test_the_planned_sweeps_hold_exactly_the_tables_series_and_sizes(self):
        for quick in (True, False):
            for sweep in reproduce.plan(self.catalogue, quick):
                if sweep.name not in figure_configs.FIGURES or not sweep.points:
                    continue
                figure = figure_configs.FIGURES[sweep.name]
                self.assertEqual(sweep.notes, [], sweep.name)
                allowed = [(s.technique, as_sent(self.catalogue, s)) for s in figure.series]
                planned = {(p.technique, tuple(p.tparams)) for p in sweep.points}
                self.assertEqual(sorted((t, dict(tp)) in allowed for t, tp in planned), [True] * len(planned),
                                 sweep.name)
                self.assertEqual({(t, tuple(pins.items())) for t, pins in allowed}, planned, sweep.name)
                self.assertEqual(sorted({(p.width, p.height) for p in sweep.points}),
                                 sorted(figure.sizes["quick" if quick else "full"]), sweep.name)


@unittest.skipIf(OITBENCH is None, "needs the built oitbench as argument")
class ListedCommandsTest(unittest.TestCase):
    """What `--list-commands` prints, the input of the Snakemake workflow."""

    def listed(self, mode):
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            reproduce.main([mode, "--oitbench", OITBENCH, "--list-commands"])
        return json.loads(printed.getvalue())["sweeps"]

    def sets_per_technique(self, bench):
        techniques = [bench[i + 1] for i, a in enumerate(bench) if a == "--technique"]
        sets = {t: {} for t in techniques}
        for i, a in enumerate(bench):
            if a == "--set":
                scoped, _, value = bench[i + 1].partition("=")
                technique, _, key = scoped.partition(".")
                sets[technique][key] = value
        return sets

    def test_every_bench_sets_the_pins_of_its_figures_series(self):
        cat = catalogue()
        for mode in ("--quick", "--full"):
            for sweep in self.listed(mode):
                if sweep["name"] not in figure_configs.FIGURES:
                    continue
                figure = figure_configs.FIGURES[sweep["name"]]
                allowed = [(s.technique, as_sent(cat, s)) for s in figure.series]
                sizes = {f"{w}x{h}" for w, h in figure.sizes[mode.strip("-")]}
                for bench in sweep["benches"]:
                    for technique, sets in self.sets_per_technique(bench).items():
                        self.assertIn((technique, sets), allowed, f"{mode} {sweep['name']}: {' '.join(bench)}")
                    self.assertIn(bench[bench.index("--size") + 1], sizes, f"{mode} {sweep['name']}")
                self.assertEqual(sweep["notes"], [], sweep["name"])


if __name__ == "__main__":
    unittest.main()
