#!/usr/bin/python3
"""analysis.reproduce against a fake oitbench (tests/fake_oitbench.py): it
starts one bench per missing run group, a second run repeats nothing, an
interrupted run is completed without repeating its finished rows, and a build
without bucketed_kbuffer leaves murray2016 Fig. 10 out with a message."""
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
from analysis import reproduce  # noqa: E402

FAKE = os.path.join(HERE, "fake_oitbench.py")
KEY = ("technique", "params", "scene", "scene_params", "camera", "width", "height", "stage")


def rows_of(out, sweep):
    with open(os.path.join(out, f"{sweep}.csv"), newline="") as f:
        return list(csv.DictReader(f))


class ReproduceTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.tmp.name, "out")
        self.log = os.path.join(self.tmp.name, "calls.log")
        self.env = mock.patch.dict(os.environ, {"FAKE_OITBENCH_LOG": self.log})
        self.env.start()

    def tearDown(self):
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
        # Fig. 10: kbuffer, bucketed (buckets named at its default), brute force, each at 6 object counts.
        fig10 = [c for c in benches if c[c.index("--csv") + 1].endswith("murray_fig10.csv")]
        self.assertEqual(len(fig10), 18)
        self.assertEqual(sum("bucketed_kbuffer.buckets=off" in c for c in fig10), 6)
        self.assertEqual(sum("bucketed_kbuffer.buckets=on" in c for c in fig10), 6)
        # Fig. 14: 5 sizes x 3 views of random:3:1, one view per run.
        fig14 = [c for c in benches if c[c.index("--csv") + 1].endswith("carnecky_fig14.csv")]
        self.assertEqual(sorted(c[c.index("--camera") + 1] for c in fig14), ["random:3:1@0"] * 5 + ["random:3:1@1"] * 5 + ["random:3:1@2"] * 5)
        self.assertTrue(all(c[c.index("--warmup") + 1] == "1" and c[c.index("--frames") + 1] == "3" for c in benches))
        # Techniques without parameters share one process per scene point; the reference is never timed.
        models = [c for c in benches if c[c.index("--csv") + 1].endswith("models.csv")]
        self.assertTrue(all(c.count("--technique") > 1 and "reference" not in c for c in models))

    def test_second_run_repeats_nothing_and_draws_every_plot(self):
        started, printed = self.reproduce()
        first = self.bench_calls()
        self.assertEqual(len(first), len([c for c in started if c[1] == "bench"]))
        for png in ("murray_fig10", "carnecky_fig14", "carnecky_fig15", "pastyrik_fig8", "pastyrik_fig9",
                    "pastyrik_fig10", "oit_comparison", "time_per_fragment"):
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
        self.assertEqual(list(sweeps), ["murray_fig10", "carnecky_fig14", "carnecky_fig15", "models", "layers"])
        # The same invocations as a dry run, without the binary and --csv.
        self.assertEqual(sorted(map(tuple, (b for s in listed["sweeps"] for b in s["benches"]))),
                         sorted(tuple(c[1:c.index("--csv")]) for c in dry if c[1] == "bench"))
        self.assertEqual([h["model"] for h in sweeps["models"]["heatmaps"]],
                         ["wuson", "elephant", "bones", "bunny", "engine"])
        self.assertEqual(sweeps["layers"]["plots"], ["time_per_fragment"])

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
        self.assertEqual(catalogue.techniques["bucketed_kbuffer"], {"buckets": "on", "k": "8"})
        self.assertEqual(catalogue.reference, {"reference"})
        self.assertEqual(catalogue.models, ["engine", "bunny", "wuson", "elephant", "bones"])
        self.assertEqual(catalogue.timed()[:2], ["depth_peeling", "linked_list"])


if __name__ == "__main__":
    unittest.main()
