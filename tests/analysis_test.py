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
import plot_stages  # noqa: E402

COLUMNS = ("timestamp,git_revision,device,gl_version,platform,technique,params,scene,scene_params,width,height,"
           "clock,stage,median_ms,min_ms,p05_ms,p95_ms,mean_ms,frames,warmup,status,message,fragments,"
           "max_depth_complexity,mean_depth_complexity,bytes_allocated,fragments_stored,fragments_dropped,passes,"
           "overflow_retries,error_max,error_rmse,psnr,other_cpu_load,noisy,clock_disagreement,extra")


def row(technique, params, stage, median, status="ok", message=""):
    fields = ["2026-11-22T09:00:00Z", "abc", "\"llvmpipe (LLVM 15.0.6, 256 bits)\"", "4.5", "egl-surfaceless",
              technique, params, "quads", "layers=32", "64", "64", "wall", stage, str(median), "", "", "", "", "3",
              "2", status, message] + [""] * 15
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

    def test_no_matching_rows_is_a_clear_error(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv = os.path.join(tmp, "runs.csv")
            with open(csv, "w") as f:
                f.write(COLUMNS + "\n" + row("unsorted", "", "total", 0.75) + "\n")
            result = subprocess.run([sys.executable, os.path.join(HERE, "..", "analysis", "plot_stages.py"), csv,
                                     "--scene", "spheres"], capture_output=True, text=True)
            self.assertNotEqual(result.returncode, 0)
            self.assertIn("no successful runs", result.stderr)


if __name__ == "__main__":
    unittest.main()
