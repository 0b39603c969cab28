#!/usr/bin/python3
"""analysis/plot_stages.py reads the CSV the harness writes and plots the
median of each stage: checked on a CSV with known numbers, in the exact
column layout of harness/core/results_csv.cpp."""
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
from analysis import common, reproduce, results_io  # noqa: E402

COLUMNS = ("timestamp,git_revision,device,gl_version,platform,technique,params,scene,scene_params,camera,width,height,"
           "clock,stage,median_ms,min_ms,p05_ms,p95_ms,mean_ms,frames,warmup,status,message,fragments,"
           "max_depth_complexity,mean_depth_complexity,psi,bytes_allocated,fragments_stored,fragments_dropped,passes,"
           "overflow_retries,error_max,error_rmse,psnr,ssim,pixels_over_1_255,other_cpu_load,noisy,clock_disagreement,extra")


def row(technique, params, stage, median, status="ok", message=""):
    fields = ["2026-11-22T09:00:00Z", "abc", "\"llvmpipe (LLVM 15.0.6, 256 bits)\"", "4.5", "egl-surfaceless",
              technique, params, "quads", "layers=32", "default", "64", "64", "wall", stage, str(median), "", "", "",
              "", "3", "2", status, message] + [""] * 18
    return ",".join(fields)


class PlotStagesTest(unittest.TestCase):
    def test_medians_per_stage_and_skipped_rows_ignored(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv = os.path.join(tmp, "runs.csv")
            with open(csv, "w") as f:
                f.write(COLUMNS + "\n")
                for stage, ms in [("clear", 1.0), ("fill", 5.0), ("compose", 2.0), ("total", 8.5)]:
                    f.write(row("reference", "initial_nodes_per_pixel=8", stage, ms) + "\n")
                f.write(row("unsorted", "", "fill", 0.5) + "\n" + row("unsorted", "", "total", 0.75) + "\n")
                f.write(row("kbuffer", "k=8", "", "", status="skipped", message="\"needs a, b\"") + "\n")
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
            csv = os.path.join(tmp, "runs.csv")
            with open(csv, "w") as f:
                f.write(COLUMNS + "\n")
                for stage, ms in [("clear", 1.0), ("build_histogram", 3.0), ("fill", 5.0), ("total", 9.0)]:
                    f.write(row("newcomer", "", stage, ms) + "\n")
                for stage, ms in [("fill", 2.0), ("blend_tail", 1.0), ("total", 3.0)]:
                    f.write(row("unsorted", "", stage, ms) + "\n")
            runs = plot_stages.load_runs(csv)
            self.assertEqual(common.stage_order(runs), ["clear", "build_histogram", "fill", "blend_tail"])
            table = common.stage_table(runs, "technique")
            self.assertEqual(list(table.columns), ["clear", "build_histogram", "fill", "blend_tail", "total"])

    def test_no_matching_rows_is_a_clear_error(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv = os.path.join(tmp, "runs.csv")
            with open(csv, "w") as f:
                f.write(COLUMNS + "\n" + row("unsorted", "", "total", 0.75) + "\n")
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
            csv = os.path.join(tmp, "runs.csv")
            with open(csv, "w") as f:
                f.write(COLUMNS + "\n")
                for technique, params, ms, err in [("kbuffer", "k=4", 2.0, 0.1), ("kbuffer", "k=32", 8.0, 0.0),
                                                   ("unsorted", "", 1.0, 0.3)]:
                    fields = row(technique, params, "total", ms).split(",")
                    fields[COLUMNS.split(",").index("error_rmse") + 1] = str(err)  # the device field holds one comma
                    f.write(",".join(fields) + "\n")
            totals = pareto.load_totals(csv, "error_rmse")
            self.assertEqual(len(totals), 3)
            result = subprocess.run([sys.executable, os.path.join(HERE, "..", "analysis", "pareto.py"), csv],
                                    check=True, capture_output=True, text=True)
            self.assertIn("front = unsorted, kbuffer k=4, kbuffer k=32", result.stdout)
            self.assertTrue(os.path.exists(os.path.join(tmp, "runs_quads_64x64.png")))


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
            csv_path = os.path.join(tmp, "runs.csv")
            fx.write_csv(csv_path, [fx.row("unsorted", s, 1.0) for s in ("fill", "compose", "total")] +
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
