#!/usr/bin/python3
"""analysis/approximate_oit.py: the run-time-against-error table marks exactly
the Pareto front and reduces params to the swept knobs (a CSV with known
numbers), the PFM reader reads what the harness writes, and the grid renders
real images with the built oitbench (argv[1]) and compares them with the
reference on one scale."""
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, REPO)
sys.path.insert(0, HERE)
from analysis import approximate_oit  # noqa: E402
from analysis_fixtures import row, write_csv  # noqa: E402
import numpy as np  # noqa: E402

OITBENCH = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(REPO, "build", "harness", "oitbench")


def total(technique, params, ms, rmse):
    return row(technique, "total", ms, params=params, error_rmse=rmse, error_max=rmse)


class TableTest(unittest.TestCase):
    def table(self, *extra):
        with tempfile.TemporaryDirectory() as tmp:
            csv = os.path.join(tmp, "pareto.csv")
            write_csv(csv, [total("unsorted", "", 1.0, 0.09),
                            total("moment_oit", "moments=power4 precision=float", 3.0, 0.05),
                            total("moment_oit", "moments=power8 precision=float", 6.0, 0.02),
                            total("hybrid_transparency", "k=2", 4.0, 0.08),  # dominated by power4
                            total("reference", "initial_nodes_per_pixel=8", 10.0, 0.0)])
            out = os.path.join(tmp, "table.md")
            approximate_oit.main(["table", csv, "-o", out] + list(extra))
            with open(out) as f:
                return [line for line in f.read().splitlines() if line.startswith("| ") and "---" not in line][1:]

    def test_front_and_params(self):
        rows = [[cell.strip() for cell in line.strip("|").split("|")] for line in self.table()]
        self.assertEqual([r[0] for r in rows],
                         ["unsorted", "moment_oit", "hybrid_transparency", "moment_oit", "reference"])
        fronts = {(r[0], r[1]): r[4] for r in rows}
        self.assertEqual(fronts[("hybrid_transparency", "")], "")
        self.assertEqual(fronts[("moment_oit", "moments=power4")], "front")
        self.assertEqual(fronts[("moment_oit", "moments=power8")], "front")
        self.assertEqual(fronts[("reference", "")], "front")
        self.assertEqual(rows[1][2:4], ["3.00", "0.05"])

    def test_short_keeps_each_techniques_fastest_and_most_accurate(self):
        rows = self.table("--short")
        self.assertEqual(len(rows), 5)  # moment_oit has two ends, the others one run each


class PfmTest(unittest.TestCase):
    def test_reads_rows_top_to_bottom(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "x.pfm")
            with open(path, "wb") as f:
                f.write(b"PF\n2 2\n-1.0\n")
                # Bottom row first, as PFM stores it.
                np.array([0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3], dtype="<f4").tofile(f)
            image = approximate_oit.read_pfm(path)
            self.assertEqual(image.shape, (2, 2, 3))
            self.assertEqual(image[0, 0, 0], 2.0)
            self.assertEqual(image[1, 1, 2], 1.0)


class GridTest(unittest.TestCase):
    def test_grid_of_real_renders(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "grid.png")
            result = subprocess.run(
                [sys.executable, "-m", "analysis.approximate_oit", "grid", "--oitbench", OITBENCH, "--scene", "quads",
                 "--scene-set", "layers=4", "--size", "16x16", "--technique", "reference",
                 "--technique", "unsorted", "-o", out], cwd=REPO, capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertGreater(os.path.getsize(out), 1000)
            # The reference against itself is 0; unsorted on 4 shuffled layers is not.
            self.assertIn("largest error", result.stdout)
            self.assertNotIn("largest error 0\n", result.stdout)

    def test_a_failing_render_names_the_command(self):
        result = subprocess.run(
            [sys.executable, "-m", "analysis.approximate_oit", "grid", "--oitbench", OITBENCH, "--technique",
             "no_such_technique", "--size", "8x8", "-o", "/nonexistent/grid.png"], cwd=REPO, capture_output=True,
            text=True)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("no_such_technique", result.stderr)


if __name__ == "__main__":
    unittest.main()
