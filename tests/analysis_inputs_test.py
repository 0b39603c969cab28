#!/usr/bin/python3
"""What analysis/ does with inputs that are not clean results CSVs: a line
that is no row (a quote left open, a shifted value) is named and every whole
run after it is still read; a byte order mark is accepted; a binary file, a
special file or a missing column is an error naming the file (no
traceback); runs without a positive median are named and left out of
plot_stages and pareto, and nothing left means no plot and a non-zero exit;
a Python without Debian's packages is told what to install before any work;
approximate_oit's default build is the repository's."""
import contextlib
import csv
import io
import os
import re
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, REPO)
sys.path.insert(0, HERE)
import analysis_fixtures as fx  # noqa: E402
from analysis import approximate_oit, pareto, plot_stages, results_io  # noqa: E402


def stage_runs(count):
    """`count` runs of two rows each (fill, total), technique t0, t1, ..."""
    return [fx.row(f"t{i}", stage, ms) for i in range(count) for stage, ms in (("fill", 1.0), ("total", 2.0))]


def analysis(*arguments, cwd=REPO, timeout=120):
    """`python3 -m analysis.<arguments>` from the repository root."""
    return subprocess.run([sys.executable, "-m"] + [f"analysis.{arguments[0]}"] + list(arguments[1:]), cwd=cwd,
                          capture_output=True, text=True, timeout=timeout)


class InputsTest(fx.TempDirTest):
    def edit_line(self, number, edit):
        with open(self.csv, newline="") as f:
            lines = f.readlines()
        lines[number - 1] = edit(lines[number - 1])
        with open(self.csv, "w", newline="") as f:
            f.writelines(lines)

    def test_a_quote_left_open_mid_file_costs_only_its_own_run(self):
        fx.write_csv(self.csv, stage_runs(13))  # 26 rows, lines 2-27
        self.edit_line(5, lambda line: line.replace(",ok,", ',ok,"cut, ', 1))  # t1's total: a quote never closed
        runs = results_io.read_results(self.csv)
        self.assertEqual(len(runs), 24)
        self.assertEqual(sorted(set(runs["technique"])), sorted(f"t{i}" for i in range(13) if i != 1))
        out = self.path("stages.png")
        result = analysis("plot_stages", self.csv, "--out", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn(f"{self.csv}: line 5: a quote left open (the field runs on into line 6: ',' expected after "
                      "'\"'): left out\n", result.stderr)
        self.assertIn(f"{self.csv}: line 4: run fixture", result.stderr)
        self.assertIn("has 1 row(s) of 2 (a run cut short is not a result): left out\n", result.stderr)
        self.assertTrue(os.path.exists(out))

    def test_a_file_appended_to_itself_reads_each_run_once(self):
        fx.write_csv(self.csv, stage_runs(2))
        with open(self.csv) as f:
            text = f.read()
        with open(self.csv, "a") as f:
            f.write(text)
        errors = io.StringIO()
        with contextlib.redirect_stderr(errors):
            self.assertEqual(list(results_io.read_results(self.csv)["technique"]), ["t0", "t0", "t1", "t1"])
        self.assertEqual(errors.getvalue().splitlines(), [
            f"{self.csv}: line 6: the header again (two files joined?): left out",
            f"{self.csv}: line 7: a copy of line 2: left out", f"{self.csv}: line 8: a copy of line 3: left out",
            f"{self.csv}: line 9: a copy of line 4: left out", f"{self.csv}: line 10: a copy of line 5: left out"])

    def test_a_shifted_row_is_named_not_read(self):
        fx.write_csv(self.csv, stage_runs(3))
        self.edit_line(4, lambda line: line.replace("t1,", "4.5 (Core Profile,", 1))
        errors = io.StringIO()
        with contextlib.redirect_stderr(errors):
            runs = results_io.read_results(self.csv)
        self.assertEqual(sorted(set(runs["technique"])), ["t0", "t2"])
        self.assertRegex(errors.getvalue(), re.escape(self.csv) + r": line 4 \(run fixture[0-9-]+\): technique '4\.5 "
                                            r"\(Core Profile' is not a technique id: left out\n")

    def test_the_columns_added_at_the_end_of_the_header_are_read(self):
        added = ["requested_params", "ci_low_ms", "ci_high_ms", "precision_reached", "rounds", "baseline", "ratio",
                 "ratio_ci_low", "ratio_ci_high", "warnings", "frame_overhead_ms", "gpu_sm_mhz_start",
                 "gpu_sm_mhz_end", "gpu_mem_mhz_start", "gpu_mem_mhz_end", "gpu_temp_c_end", "samples_ms"]
        columns = fx.csv_columns() + [c for c in added if c not in fx.csv_columns()]
        rows = fx.with_run_columns([dict(row, samples_ms="1.5 2.5 2", warnings="clock throttled,\nonce", ratio="1.1")
                                    for row in stage_runs(2)])
        with open(self.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=columns, restval="", lineterminator="\n")
            writer.writeheader()
            writer.writerows(rows)
        runs = plot_stages.load_runs(self.csv)
        self.assertEqual(list(runs["samples_ms"]), ["1.5 2.5 2"] * 4)
        self.assertEqual(list(runs["median_ms"]), [1.0, 2.0, 1.0, 2.0])

    def test_a_byte_order_mark_is_accepted(self):
        fx.write_csv(self.csv, stage_runs(2))
        with open(self.csv, "rb") as f:
            text = f.read()
        with open(self.csv, "wb") as f:
            f.write(b"\xef\xbb\xbf" + text)
        runs = results_io.read_results(self.csv)
        self.assertEqual(list(runs.columns), fx.csv_columns())
        self.assertEqual([row.get("timestamp") for row in results_io.read_rows(self.csv)], ["2026-11-22T09:00:00Z"] * 4)
        merged = self.path("merged.csv")
        result = analysis("merge", "--out", merged, self.csv)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(len(results_io.read_rows(merged)), 4)

    def test_a_binary_file_is_an_error_naming_it(self):
        with open(self.csv, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe")
        result = analysis("plot_stages", self.csv, "--out", self.path("x.png"))
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr, f"plot_stages: {self.csv}: not a CSV text file (byte 0x89 at offset 0 is not "
                                        "UTF-8)\n")

    def test_a_special_file_is_refused_not_read(self):
        os.symlink("/dev/zero", self.csv)
        for module in ("plot_stages", "pareto"):
            result = analysis(module, self.csv, timeout=60)
            self.assertEqual((result.returncode, result.stderr), (1, f"{module}: {self.csv} is not a regular file\n"))

    def test_a_missing_column_is_named_with_the_file(self):
        fx.write_csv(self.csv, stage_runs(2))
        self.edit_line(1, lambda line: line.replace("median_ms", "median"))
        for module in ("plot_stages", "pareto"):
            result = analysis(module, self.csv)
            self.assertEqual(result.returncode, 1)
            self.assertEqual(result.stderr, f"{module}: {self.csv}: no column 'median_ms': not an oitbench results "
                                            "CSV (or one too old for this)\n")


BAD_MEDIANS = ["", "nan", "n/a", "0", "-1.5"]


class PlotsFromNothingTest(fx.TempDirTest):
    def write(self, medians):
        fx.write_csv(self.csv, [fx.row(f"t{i}", stage, median if stage == "total" else 1.0, error_rmse=0.1 * i)
                                for i, median in enumerate(medians) for stage in ("fill", "total")])

    def test_runs_without_a_positive_median_are_named_and_left_out(self):
        self.write(["2.0"] + BAD_MEDIANS)
        stages, files = self.path("stages.png"), self.tmp.name
        for module, arguments in (("plot_stages", ["--out", stages]), ("pareto", ["--out-dir", files])):
            result = analysis(module, self.csv, *arguments)
            self.assertEqual(result.returncode, 0, result.stderr)
            for i, median in enumerate(BAD_MEDIANS, start=1):
                self.assertIn(f"{self.csv}: line {2 * i + 3}: t{i} on quads layers=32 64x64 wall total: median_ms "
                              f"{median!r} is not a positive number: run left out\n", result.stderr)
        self.assertEqual(list(plot_stages.load_runs(self.csv)["technique"].unique()), ["t0"])
        self.assertEqual(list(pareto.load_totals(self.csv, "error_rmse")["technique"]), ["t0"])
        self.assertTrue(os.path.exists(stages))
        self.assertTrue(os.path.exists(self.path("runs_quads_64x64.png")))

    def test_nothing_usable_is_no_plot_and_a_failure(self):
        self.write(BAD_MEDIANS)
        stages = self.path("stages.png")
        for module, arguments in (("plot_stages", ["--out", stages]), ("pareto", [])):
            result = analysis(module, self.csv, *arguments)
            self.assertEqual(result.returncode, 1)
            self.assertTrue(result.stderr.endswith(f"{module}: {self.csv}: no run with a positive median_ms (5 left "
                                                   "out, see above): nothing to plot\n"), result.stderr)
        self.assertEqual(os.listdir(self.tmp.name), ["runs.csv"])

    def test_pareto_without_any_error_figure_writes_nothing_and_fails(self):
        fx.write_csv(self.csv, [fx.row("unsorted", "total", 1.0)])  # a bench without --reference
        result = analysis("pareto", self.csv)
        self.assertEqual(result.returncode, 1)
        self.assertTrue(result.stderr.endswith(f"pareto: {self.csv}: no run has both a time and error_rmse (see "
                                               "above): no plot written\n"), result.stderr)
        self.assertEqual(os.listdir(self.tmp.name), ["runs.csv"])

    def test_no_front_from_times_that_are_not_positive(self):
        import pandas as pd
        with self.assertRaisesRegex(ValueError, "a Pareto front needs positive times"):
            pareto.pareto_front(pd.DataFrame({"time_ms": [0.0, 1.0], "error": [0.5, 0.1]}))


class StartupTest(unittest.TestCase):
    def test_a_python_without_debians_packages_is_told_what_to_install(self):
        # -S: no site-packages, so pandas, numpy and matplotlib cannot be imported.
        for module in ("plot_stages", "reproduce", "carnecky_fig14"):
            with tempfile.TemporaryDirectory() as tmp:
                result = subprocess.run([sys.executable, "-S", "-m", f"analysis.{module}", "--out", tmp],
                                        cwd=REPO, capture_output=True, text=True, timeout=60)
                self.assertEqual(result.returncode, 1)
                self.assertEqual(os.listdir(tmp), [])  # reproduce ran no sweep
            self.assertIn(f"analysis.{module}: this Python ({sys.executable}) cannot import numpy, pandas, "
                          "matplotlib: run it with Debian's /usr/bin/python3", result.stderr)
            self.assertIn("apt-get install python3-numpy python3-pandas python3-matplotlib", result.stderr)
            self.assertNotIn("Traceback", result.stderr)

    def test_the_workflows_jobs_need_only_the_standard_library(self):
        result = subprocess.run([sys.executable, "-S", "-m", "analysis.merge", "--help"], cwd=REPO,
                                capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)


class ApproximateOitTest(unittest.TestCase):
    def test_the_default_build_is_the_repositorys_wherever_it_runs(self):
        args = approximate_oit.parse_arguments(["grid", "-o", "grid.png"])
        self.assertEqual(args.oitbench, os.path.join(REPO, "build", "harness", "oitbench"))


if __name__ == "__main__":
    unittest.main()
