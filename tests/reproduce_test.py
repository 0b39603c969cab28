#!/usr/bin/python3
"""analysis.reproduce against a fake oitbench (tests/fake_oitbench.py): it
starts one bench per missing run group, a second run repeats nothing, an
interrupted run is completed without repeating its finished rows, and a build
without bucketed_kbuffer leaves murray2016 Fig. 10 out with a message; the
--full plan holds the papers' sizes and parameters; the new figures' plots
draw what their rows say; the reproduction README's tables quote the
papers' numbers."""
import contextlib
import csv
import io
import json
import os
import sys
import tempfile
import unittest
from collections import Counter
from unittest import mock

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from analysis import figure_configs, reproduce, results_io  # noqa: E402

FAKE = os.path.join(HERE, "fake_oitbench.py")
KEY = ("technique", "params", "scene", "scene_params", "camera", "width", "height", "stage")


def rows_of(out, sweep):
    """Every row of the sweep's CSV, or (committed, over 1 MiB) of its .csv.gz."""
    return list(csv.DictReader(io.StringIO(results_io.read_text(os.path.join(out, f"{sweep}.csv")))))


class ReproduceTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.tmp.name, "out")
        self.log = os.path.join(self.tmp.name, "calls.log")
        self.env = mock.patch.dict(os.environ, {"FAKE_OITBENCH_LOG": self.log})
        self.env.start()
        # One CAD-like mesh file beside the catalogue's models, whatever this machine has installed.
        self.cad = os.path.join(self.tmp.name, "cad_part.obj")
        open(self.cad, "w").close()
        self.cad_files = mock.patch.object(reproduce, "CAD_FILES", [self.cad])
        self.cad_files.start()

    def tearDown(self):
        self.cad_files.stop()
        self.env.stop()
        self.tmp.cleanup()

    def reproduce(self, *extra):
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            started = reproduce.main(["--quick", "--out", self.out, "--oitbench", FAKE, *extra])
        return started, printed.getvalue()

    def bench_calls(self):
        with open(self.log) as f:
            return [line.split() for line in f if line.startswith("bench ")]

    def test_dry_run_lists_every_group_and_starts_nothing(self):
        started, printed = self.reproduce("--dry-run")
        self.assertEqual(self.bench_calls(), [])
        self.assertIn("would run:", printed)
        benches = [c for c in started if c[1] == "bench"]
        # Fig. 10: kbuffer with the paper's bucketed query in one process,
        # then the brute force and the merge search (bucketed_kbuffer again:
        # a process each), at 6 object counts.
        fig10 = [c for c in benches if c[c.index("--csv") + 1].endswith("murray_fig10.csv")]
        self.assertEqual(len(fig10), 18)
        self.assertEqual(sum("kbuffer.k=32" in c for c in fig10), 6)
        self.assertEqual(sum("bucketed_kbuffer.buckets=off" in c for c in fig10), 6)
        self.assertEqual(sum("bucketed_kbuffer.buckets=on" in c for c in fig10), 12)
        self.assertEqual(sum("bucketed_kbuffer.neighbor_search=merge" in c for c in fig10), 6)
        self.assertEqual(sum("bucketed_kbuffer.neighbor_search=bucket" in c for c in fig10), 12)
        # Fig. 14: 5 sizes x 3 views of random:3:1, one view per run.
        fig14 = [c for c in benches if c[c.index("--csv") + 1].endswith("carnecky_fig14.csv")]
        self.assertEqual(sorted(c[c.index("--camera") + 1] for c in fig14), ["random:3:1@0"] * 5 + ["random:3:1@1"] * 5 + ["random:3:1@2"] * 5)
        self.assertTrue(all(c[c.index("--warmup") + 1] == "1" and c[c.index("--frames") + 1] == "3" for c in benches))
        # The techniques of a scene point share one process, each with its own
        # pinned parameters (`--set technique.key=value`); the reference is never timed.
        models = [c for c in benches if os.path.basename(c[c.index("--csv") + 1]) == "models.csv"]
        self.assertTrue(all(c.count("--technique") > 1 and "reference" not in c for c in models))
        first = models[0]
        self.assertIn("linked_list.sort=network", first)
        self.assertIn("illustration_buffer.neighbors=triangle_index", first)

    def test_second_run_repeats_nothing_and_draws_every_plot(self):
        started, printed = self.reproduce()
        first = self.bench_calls()
        self.assertEqual(len(first), len([c for c in started if c[1] == "bench"]))
        for png in ("murray_fig10", "carnecky_fig14", "carnecky_fig15", "pastyrik_fig8", "pastyrik_fig9",
                    "pastyrik_fig10", "oit_comparison", "time_per_fragment", "pastyrik_fig7", "pastyrik_memory",
                    "peeling_stages", "murray_fps_ratio", "carnecky_images", "pastyrik_psi", "pastyrik_fig11_14"):
            self.assertTrue(os.path.exists(os.path.join(self.out, f"{png}.png")), png)
        started, printed = self.reproduce()
        self.assertEqual(started, [])
        self.assertEqual(len(self.bench_calls()), len(first))
        self.assertIn("18 runs, 18 already in", printed)

    def test_interrupted_run_resumes_without_duplicate_rows(self):
        # The 3rd bench of the models sweep dies after its first technique.
        with mock.patch.dict(os.environ, {"FAKE_OITBENCH_DIE_AT": "3"}):
            _, printed = self.reproduce("--only", "models", "--no-plots")
        self.assertIn("exit status 1", printed)
        calls_before = len(self.bench_calls())
        partial = rows_of(self.out, "models")
        started, _ = self.reproduce("--only", "models", "--no-plots")
        resumed = [c for c in started if c[1] == "bench"]
        # Only the interrupted group's other techniques run again, the finished first one not.
        self.assertEqual(len(resumed), 1)
        self.assertNotIn("depth_peeling", resumed[0])
        self.assertIn("linked_list", resumed[0])
        self.assertEqual(len(self.bench_calls()), calls_before + 1)
        complete = rows_of(self.out, "models")
        self.assertGreater(len(complete), len(partial))
        duplicates = [k for k, n in Counter(tuple(r[c] for c in KEY) for r in complete).items() if n > 1]
        self.assertEqual(duplicates, [])

    def test_list_commands_prints_the_dry_run_benches_as_json(self):
        dry, _ = self.reproduce("--dry-run", "--no-plots")
        _, printed = self.reproduce("--list-commands")
        listed = json.loads(printed)
        sweeps = {s["name"]: s for s in listed["sweeps"]}
        self.assertEqual(list(sweeps), ["murray_fig10", "carnecky_fig14", "carnecky_fig15", "models", "pastyrik_fig7",
                                        "murray_models", "psi_scenes", "layers", "carnecky_images", "murray_images"])
        # The same invocations as a dry run, without the binary and --csv.
        self.assertEqual(sorted(map(tuple, (b for s in listed["sweeps"] for b in s["benches"]))),
                         sorted(tuple(c[1:c.index("--csv")]) for c in dry if c[1] == "bench"))
        self.assertEqual([h["model"] for h in sweeps["models"]["heatmaps"]],
                         ["wuson", "elephant", "bones", "bunny", "engine", "cad_part"])
        self.assertEqual(sweeps["models"]["heatmaps"][-1]["arguments"][:3], ["stats", "--scene", self.cad])
        # The image grid is no bench: the workflow is told to leave it to analysis.reproduce.
        self.assertEqual(sweeps["carnecky_images"]["benches"], [])
        self.assertIn("renders only", sweeps["carnecky_images"]["skipped"])
        self.assertIn(["--set", "modulation=none"], [r["arguments"][3:5] for r in sweeps["carnecky_images"]["renders"]])
        self.assertEqual(sweeps["layers"]["plots"], ["time_per_fragment"])
        # murray2016's images at the paper's sizes in either mode, Fig. 8's bike at 1200x800.
        murray = {r["name"]: r["arguments"] for r in sweeps["murray_images"]["renders"]}
        self.assertIn("renders only", sweeps["murray_images"]["skipped"])
        self.assertIn("1200x800", murray["fig08_b"])
        self.assertIn("1000x1000", murray["fig01_ours"])
        self.assertEqual(murray["fig01_oit"][:3], ["render", "--technique", "kbuffer"])

    def test_plots_only_draws_each_device_of_a_merged_csv_apart(self):
        self.reproduce("--only", "layers", "--no-plots")
        rows = rows_of(self.out, "layers")
        with open(os.path.join(self.out, "layers.csv"), "a", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
            # Another machine's recording: its own run ids.
            writer.writerows(dict(r, device="Other GPU", platform="egl-device", run_id=r["run_id"] + "-other")
                             for r in rows)
        calls = len(self.bench_calls())
        _, printed = self.reproduce("--only", "layers", "--plots-only")
        self.assertEqual(len(self.bench_calls()), calls)
        drawn = sorted(f for f in os.listdir(self.out) if f.endswith(".png"))
        self.assertEqual(len(drawn), 2, printed)
        self.assertTrue(any(f.startswith("time_per_fragment_Other-GPU-egl-device") for f in drawn), drawn)

    def test_without_bucketed_kbuffer_fig10_is_skipped_with_a_message(self):
        with mock.patch.dict(os.environ, {"FAKE_OITBENCH_NO_BKB": "1"}):
            started, printed = self.reproduce("--dry-run")
        self.assertIn("murray_fig10: skipped: bucketed_kbuffer is not in this build", printed)
        self.assertFalse(any("murray_fig10.csv" in " ".join(c) for c in started))
        self.assertTrue(any("carnecky_fig14.csv" in " ".join(c) for c in started))


class PlanTest(unittest.TestCase):
    """The plans `oitbench list` of the fake build gives: --full at the papers' sizes and parameters."""

    @classmethod
    def setUpClass(cls):
        import subprocess
        listing = subprocess.run([FAKE, "list"], capture_output=True, text=True, check=True).stdout
        cls.catalogue = reproduce.Catalogue(listing)
        with mock.patch.object(reproduce, "CAD_FILES", [FAKE]):  # an existing file stands for a CAD mesh
            cls.full = {s.name: s for s in reproduce.plan(cls.catalogue, quick=False)}
            cls.quick = {s.name: s for s in reproduce.plan(cls.catalogue, quick=True)}

    def sizes(self, sweep):
        return sorted({(p.width, p.height) for p in sweep.points})

    def test_murray_fig10_at_512_with_32_layers_and_k_32(self):
        sweep = self.full["murray_fig10"]
        self.assertEqual(self.sizes(sweep), [(512, 512)])
        self.assertEqual({dict(p.sparams)["layers"] for p in sweep.points}, {"32"})
        self.assertEqual(sorted({int(dict(p.sparams)["objects"]) for p in sweep.points}), [1, 2, 4, 8, 16, 32])
        self.assertEqual({dict(p.tparams)["k"] for p in sweep.points}, {"32"})
        self.assertEqual(sorted({dict(p.tparams).get("buckets", "-") for p in sweep.points}), ["-", "off", "on"])

    def test_carnecky_one_iteration_tens_of_views_2048_and_500k_triangles(self):
        fig14, fig15 = self.full["carnecky_fig14"], self.full["carnecky_fig15"]
        for sweep in (fig14, fig15):  # the pins the fake build lists (figure_configs.CARNECKY)
            self.assertEqual({p.tparams for p in sweep.points},
                             {(("modulation", "silhouette_halo"), ("iterations", "1"), ("neighbors", "heuristic"))})
            self.assertTrue(any("storage, diffusion, skip_converged" in n for n in sweep.notes), sweep.notes)
        self.assertEqual(self.sizes(fig14), [(s, s) for s in (128, 256, 512, 1024, 2048)])
        self.assertGreaterEqual(len({p.camera for p in fig14.points}), 30)
        self.assertEqual(self.sizes(fig15), [(1024, 1024)])
        triangles = sorted({2 * int(dict(p.sparams)["slices"]) * int(dict(p.sparams)["stacks"]) for p in fig15.points})
        self.assertTrue(any(450_000 <= t <= 600_000 for t in triangles), triangles)
        self.assertGreaterEqual(len({p.camera for p in fig15.points}), 16)

    def test_views_override_and_accuracy_bookkeeping_off_where_listed(self):
        text = ("Techniques:\n  illustration_buffer  IB [approximate]\n"
                "      measure_accuracy         default true     true or false — bookkeeping\n")
        fig14, fig15 = reproduce.carnecky_sweeps(reproduce.Catalogue(text), False, 3, 20, views=2)
        self.assertEqual(sorted({p.camera for p in fig14.points}), ["random:2:1@0", "random:2:1@1"])
        self.assertEqual({dict(p.tparams)["measure_accuracy"] for p in fig15.points}, {"false"})
        self.assertEqual({(p.width, p.height) for p in fig15.points}, {(1024, 1024)})

    def test_models_at_600_in_two_positions_with_a_cad_file(self):
        sweep = self.full["models"]
        self.assertEqual(self.sizes(sweep), [(600, 600)])
        self.assertEqual(sorted({p.camera for p in sweep.points}), ["default", "max_list:16:1"])
        self.assertEqual(sorted({p.scene for p in sweep.points}), sorted(["model", FAKE]))
        self.assertEqual(len({p.sparams for p in sweep.points if p.scene == "model"}), 5)  # every catalogue model

    def test_murray_models_at_1000_and_fig8s_1200x800_with_16_layers(self):
        sweep = self.full["murray_models"]
        self.assertEqual(self.sizes(sweep), [(1000, 1000), (1200, 800)])
        self.assertEqual({(p.technique, p.tparams) for p in sweep.points},
                         {("kbuffer", (("k", "16"),)),
                          ("bucketed_kbuffer", (("k", "16"), ("buckets", "on"), ("neighbor_search", "bucket")))})

    def test_psi_scenes_time_both_techniques_at_600(self):
        sweep = self.full["psi_scenes"]
        self.assertEqual(self.sizes(sweep), [(600, 600)])
        self.assertEqual({p.technique for p in sweep.points}, {"illustration_buffer", "linked_list"})
        self.assertIn(("quads", (("layers", "8"), ("objects", "8"))), {(p.scene, p.sparams) for p in sweep.points})

    def test_fig7_sweeps_the_sort_choices_the_build_lists(self):
        sweep = self.full["pastyrik_fig7"]  # the fake's illustration_buffer has no sort: linked_list's
        self.assertEqual(sorted({dict(p.tparams)["sort"] for p in sweep.points}), ["insertion", "network", "selection"])
        self.assertEqual({p.technique for p in sweep.points}, {"linked_list"})

    def test_k_buffers_run_at_k_auto_where_the_build_accepts_it(self):
        kbuffer = [p for p in self.full["layers"].points if p.technique == "kbuffer"]
        self.assertEqual({p.tparams for p in kbuffer}, {(("k", "auto"),)})
        # The fake's bucketed_kbuffer takes no k=auto: its pinned k.
        self.assertEqual({dict(p.tparams)["k"] for p in self.full["layers"].points
                          if p.technique == "bucketed_kbuffer"}, {"16"})
        self.assertEqual({p.tparams for p in self.full["layers"].points if p.technique == "depth_peeling"},
                         {(("max_passes", "64"),)})

    def test_images_take_the_modes_list_offers_and_the_quick_plan_stays_small(self):
        names = [r.name for r in self.full["carnecky_images"].renders]
        self.assertIn("fig13_constant", names)
        self.assertFalse(any("angle" in n for n in names))  # the fake lists no angle mode
        self.assertEqual({(p.width, p.height) for p in self.quick["carnecky_fig14"].points},
                         {(s, s) for s in (128, 192, 256, 384, 512)})
        self.assertEqual(self.sizes(self.quick["murray_fig10"]), [(64, 64)])

    def test_angle_and_normal_modes_join_fig11_and_fig13_when_listed(self):
        catalogue = reproduce.Catalogue(self.catalogue_text_with_modes())
        names = [r.name for r in reproduce.carnecky_images(catalogue, quick=True)]
        self.assertIn("fig11_angle", names)
        self.assertIn("fig11_normal_variation", names)
        self.assertIn("fig13_normal_variation", names)
        self.assertNotIn("fig13_angle", names)

    def test_fig9_has_the_papers_five_columns_where_the_build_has_eq8(self):
        fig9 = figure_configs.CARNECKY_FIG9
        with_eq8 = reproduce.Catalogue(self.catalogue_text_with_modes() + (
            "      field_diffusion          default nonphysical one of {nonphysical, homogeneous} — eq. 9 or 8\n"
            + "".join(f"      {knob:<24} default 1 anything — a knob of Fig. 9\n"
                      for knob in ("iterations", "lambda_beta", "lambda_gamma", "profile", "exponential_p", "power_p"))))
        renders = [r for r in reproduce.carnecky_images(with_eq8, quick=True) if r.name.startswith("fig09_")]
        self.assertEqual([(r.name, r.caption) for r in renders], [(name, caption) for name, caption, _ in fig9])
        for render, (_, _, knobs) in zip(renders, fig9):
            self.assertEqual({k: v for k, v in render.tparams if k in knobs}, knobs, render.name)
        # A build without eq. 8 renders the eq. 9 columns only (none mislabelled).
        older = [r.name for r in reproduce.carnecky_images(reproduce.Catalogue(self.catalogue_text_with_modes()),
                                                           quick=True) if r.name.startswith("fig09_")]
        self.assertEqual(older, ["fig09_1_eq9", "fig09_2_eq9_eq10"])

    def test_wrapped_ranges_and_model_names_are_read_whole(self):
        # `oitbench list` wraps a long range onto lines indented by 8; a
        # technique's own lines (paper, stages) wrap too and are no parameter's.
        text = ("Techniques:\n  illustration_buffer  IB [approximate]\n"
                "      paper: one of {a,\n        b}\n"
                "      modulation default none one of {none, angle,\n        ray_distance} — modes, not\n"
                "        one of {x} or auto\n"
                "      sort default auto one of {auto, array} — sorts\n"
                "Scenes (--scene NAME):\n  model  real models\n"
                "      name default bunny one of {engine, bunny,\n        dragon} — which model\n")
        catalogue = reproduce.Catalogue(text)
        self.assertEqual(catalogue.choices("illustration_buffer", "modulation"), ["none", "angle", "ray_distance"])
        self.assertFalse(catalogue.accepts_auto("illustration_buffer", "modulation"))  # "or auto" in its meaning only
        self.assertEqual(catalogue.choices("illustration_buffer", "sort"), ["auto", "array"])
        self.assertEqual(list(catalogue.techniques["illustration_buffer"]), ["modulation", "sort"])
        self.assertEqual(catalogue.models, ["engine", "bunny", "dragon"])

    def catalogue_text_with_modes(self):
        return ("Techniques:\n  illustration_buffer  IB [approximate]\n"
                "      modulation               default silhouette_halo one of {none, angle, normal_variation, "
                "silhouette_halo} — modes\n")


class QuickRowsTest(unittest.TestCase):
    """What a quick run against the fake build leaves in the CSVs."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        out = os.path.join(cls.tmp.name, "out")
        with mock.patch.object(reproduce, "CAD_FILES", []), contextlib.redirect_stdout(io.StringIO()):
            reproduce.main(["--quick", "--out", out, "--oitbench", FAKE, "--no-plots"])
        cls.rows = {name: rows_of(out, name) for name in ("carnecky_fig14", "models", "layers", "pastyrik_fig7",
                                                          "murray_models")}
        cls.out = out

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_fig14_rows_hold_one_iteration_and_three_views_per_size(self):
        rows = [r for r in self.rows["carnecky_fig14"] if r["stage"] == "total"]
        self.assertEqual(len(rows), 15)
        self.assertTrue(all(reproduce.tokens(r["params"])["iterations"] == "1" for r in rows))

    def test_models_rows_in_both_positions(self):
        totals = Counter((reproduce.tokens(r["scene_params"])["name"], r["camera"])
                         for r in self.rows["models"] if r["stage"] == "total" and r["technique"] == "linked_list")
        self.assertEqual(totals[("engine", "default")], 1, totals)
        self.assertEqual(totals[("engine", "max_list:16:1")], 1)
        self.assertEqual(len(totals), 10)

    def test_layers_kbuffer_rows_at_k_auto_and_images_rendered(self):
        ks = {reproduce.tokens(r["params"])["k"] for r in self.rows["layers"] if r["technique"] == "kbuffer"}
        self.assertEqual(ks, {"auto"})
        with open(os.path.join(self.out, "images", "captions.json")) as f:
            captions = json.load(f)
        self.assertEqual(captions["fig09_1_eq9"], "eq. 9, n=20, λβ=0.05")  # the fake build has no eq. 8
        self.assertTrue(all(os.path.exists(os.path.join(self.out, "images", f"{n}.png")) for n in captions))


class NoisyTest(unittest.TestCase):
    def row(self, run_id, noisy):
        return {"technique": "kbuffer", "params": "k=32", "scene": "quads", "scene_params": "layers=32", "camera":
                "default", "width": "64", "height": "64", "status": "ok", "noisy": noisy, "run_id": run_id}

    def test_a_noisy_run_is_run_again_until_quiet_or_tried_twice(self):
        point = reproduce.Point("kbuffer", (("k", "32"),), "quads", (), "default", 64, 64)
        self.assertTrue(reproduce.finished(point, [self.row("a", "true")]))  # without --rerun-noisy
        self.assertFalse(reproduce.finished(point, [self.row("a", "true")], rerun_noisy=True))
        self.assertTrue(reproduce.finished(point, [self.row("a", "true"), self.row("b", "true")], rerun_noisy=True))
        self.assertTrue(reproduce.finished(point, [self.row("a", "true"), self.row("b", "false")], rerun_noisy=True))

    def test_plots_drop_a_noisy_run_that_has_a_quiet_repeat_and_count_the_rest(self):
        import pandas as pd
        from analysis import figure_notes
        rows = pd.DataFrame([dict(self.row("a", "true"), median_ms=9.0), dict(self.row("b", "false"), median_ms=1.0),
                             dict(self.row("c", "true"), median_ms=5.0, camera="random:2:1@1")])
        kept = figure_notes.quiet_runs(rows)
        self.assertEqual(sorted(kept["run_id"]), ["b", "c"])
        self.assertEqual(figure_notes.noisy_note(kept), ", 1 of 2 runs noisy (other load > 25%)")


class CommittedReproductionTest(unittest.TestCase):
    """results/reference/reproduce: its README compares every figure with the
    paper's numbers, and its CSVs hold the runs the README describes."""
    FOLDER = os.path.join(os.path.dirname(HERE), "results", "reference", "reproduce")

    @classmethod
    def setUpClass(cls):
        with open(os.path.join(cls.FOLDER, "README.md")) as f:
            cls.readme = f.read()

    def section(self, heading):
        start = self.readme.index(heading)
        end = self.readme.find("\n## ", start + 1)
        return self.readme[start:end if end > 0 else None]

    def test_one_table_per_figure_with_the_papers_numbers(self):
        expected = {"murray2016 Fig. 10": ["~10 ms", "a fifth", "> 5 buckets"],
                    "carnecky2013 Fig. 14": ["20x", "~15 fps", "linear"],
                    "carnecky2013 Fig. 15": ["8.94", "non-zero intercept"],
                    "pastyrik2016 Figs. 8-10": ["Suspension 2", "FindNeighbours"],
                    "pastyrik2016 Fig. 7": ["dynamic", "no performance difference"],
                    "pastyrik2016 section 4.3": ["208", "~397 MB"],
                    "pastyrik2016 Figs. 11-14": ["much slower", "linked lists"],
                    "murray2016 Figs. 1, 8, 9": ["64 / 24 = 2.67", "120 / 45 = 2.67", "20 / 10 = 2.0", "50 / 20 = 2.5"]}
        for heading, numbers in expected.items():
            text = self.section("## " + heading)
            self.assertRegex(text, r"\| (quantity|figure) \| paper", heading)
            for number in numbers:
                self.assertIn(number, text, heading)

    def test_the_corrected_explanations(self):
        self.assertIn("favours **dual** peeling", self.readme)
        self.assertIn("one** diffusion iteration", self.readme)
        self.assertNotIn("unlike the paper, the neighbour stage dominates everything", self.readme)
        with open(os.path.join(os.path.dirname(HERE), "results", "reference", "MEASURED.md")) as f:
            self.assertNotIn("which favours the single-layer peel", f.read())

    def test_every_plot_the_readme_names_is_committed(self):
        import re
        for png in set(re.findall(r"`((?:full/)?[a-z0-9_]+\.png)`", self.readme)):
            self.assertTrue(os.path.exists(os.path.join(self.FOLDER, png)), png)

    def test_the_committed_runs_are_the_ones_described(self):
        fig14 = [r for r in rows_of(self.FOLDER, "carnecky_fig14") if r["stage"] == "total"]
        self.assertTrue(fig14 and all(reproduce.tokens(r["params"])["iterations"] == "1" for r in fig14))
        full14 = [r for r in rows_of(os.path.join(self.FOLDER, "full"), "carnecky_fig14") if r["stage"] == "total"]
        self.assertEqual(sorted({int(r["width"]) for r in full14}), [128, 256, 512, 1024, 2048])
        murray = [r for r in rows_of(os.path.join(self.FOLDER, "full"), "murray_fig10") if r["stage"] == "total"]
        self.assertEqual({(r["width"], reproduce.tokens(r["params"])["k"]) for r in murray}, {("512", "32")})
        self.assertEqual(len(murray), 18)
        cameras = {r["camera"] for r in rows_of(self.FOLDER, "models")}
        self.assertEqual(cameras, {"default", "max_list:16:1"})


class FinishedTest(unittest.TestCase):
    def point(self, tparams=(), camera="default"):
        return reproduce.Point("bucketed_kbuffer", tparams, "quads", (("objects", "4"),), camera, 64, 64)

    def row(self, params, status="ok", objects="4", camera="default"):
        return {"technique": "bucketed_kbuffer", "params": params, "scene": "quads",
                "scene_params": f"layers=32 objects={objects} seed=1", "camera": camera, "width": "64",
                "height": "64", "status": status}

    def test_swept_parameters_tell_runs_apart(self):
        rows = [self.row("buckets=off k=8")]
        self.assertTrue(reproduce.finished(self.point((("buckets", "off"),)), rows))
        self.assertFalse(reproduce.finished(self.point((("buckets", "on"),)), rows))
        self.assertFalse(reproduce.finished(self.point((("buckets", "off"),)), [self.row("buckets=off", objects="8")]))
        self.assertFalse(reproduce.finished(self.point(camera="random:2:1@1"), [self.row("k=8", camera="random:2:1@0")]))

    def test_error_rows_are_retried_skipped_rows_are_not(self):
        self.assertFalse(reproduce.finished(self.point(), [self.row("k=8", status="error")]))
        self.assertTrue(reproduce.finished(self.point(), [self.row("k=8", status="skipped")]))


class CatalogueTest(unittest.TestCase):
    def test_parses_techniques_defaults_reference_and_models(self):
        import subprocess
        listing = subprocess.run([FAKE, "list"], capture_output=True, text=True, check=True).stdout
        catalogue = reproduce.Catalogue(listing)
        self.assertEqual(catalogue.techniques["bucketed_kbuffer"], {"buckets": "on", "k": "8", "neighbor_search": "merge"})
        self.assertEqual(catalogue.reference, {"reference"})
        self.assertEqual(catalogue.models, ["engine", "bunny", "wuson", "elephant", "bones"])
        self.assertEqual(catalogue.timed()[:2], ["depth_peeling", "linked_list"])


if __name__ == "__main__":
    unittest.main()
