"""oitbench compare on real bench runs: a known difference is found with its
direction and significance, the same build against itself is `same`, the
regression gate sets the exit status, and a CSV without per-frame samples
says so. Run: /usr/bin/python3 tests/compare_test.py BUILD_DIR"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
BUILD = os.path.abspath(sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(HERE, "..", "build"))
OITBENCH = os.path.join(BUILD, "harness", "oitbench")
SMALL = ["-s", "quads", "--scene-set", "layers=4", "--size", "48x48"]


def run(arguments, check=True):
    result = subprocess.run([OITBENCH, *arguments], capture_output=True, text=True, timeout=600)
    if check and result.returncode != 0:
        raise AssertionError(f"oitbench {' '.join(arguments)} exited {result.returncode}:\n{result.stdout}\n"
                             f"{result.stderr}")
    return result


def verdicts(output):
    """{(configuration, stage): (ratio text, p, verdict)} from the plain table."""
    found = {}
    lines = output.splitlines()
    header = next(i for i, line in enumerate(lines) if line.startswith("configuration"))
    columns = [lines[header].index(name) for name in ["configuration", "stage", "base ms", "new ms",
                                                       "new/base [95%]", "p", "verdict"]]
    for line in lines[header + 1:]:
        if not line.strip():
            break
        cells = [line[start:end].strip() for start, end in zip(columns, columns[1:] + [None])]
        found[(cells[0], cells[1])] = (cells[4], cells[5], cells[6])
    return found


class CompareTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="compare_test_")
        cls.base = os.path.join(cls.dir, "early_exit.csv")
        cls.new = os.path.join(cls.dir, "no_early_exit.csv")
        frames = ["--frames", "24", "--warmup", "2"]
        run(["bench", "-t", "depth_peeling", "--set", "early_exit=true", *SMALL, *frames, "--csv", cls.base])
        run(["bench", "-t", "depth_peeling", "--set", "early_exit=false", *SMALL, *frames, "--csv", cls.new])

    def test_a_known_difference_is_found_with_its_direction(self):
        # Without early exit the peeler runs all 64 passes for 4 layers.
        result = run(["compare", self.base, self.new, "--ignore-param", "early_exit"])
        rows = verdicts(result.stdout)
        total = [v for (configuration, stage), v in rows.items() if stage == "total"]
        self.assertEqual(len(total), 1, result.stdout)
        ratio, p, verdict = total[0]
        self.assertEqual(verdict, "slower", result.stdout)
        self.assertLess(float(p), 0.01)
        self.assertGreater(float(ratio.split()[0]), 1.5)
        backwards = verdicts(run(["compare", self.new, self.base, "--ignore-param", "early_exit"]).stdout)
        self.assertEqual([v[2] for (c, s), v in backwards.items() if s == "total"], ["faster"])

    def test_the_regression_gate_and_markdown(self):
        gate = run(["compare", self.base, self.new, "--ignore-param", "early_exit", "--fail-if-slower", "10"],
                   check=False)
        self.assertEqual(gate.returncode, 1, gate.stdout + gate.stderr)
        self.assertIn("slower by more than 10%", gate.stderr)
        self.assertEqual(run(["compare", self.new, self.base, "--ignore-param", "early_exit",
                              "--fail-if-slower", "10"], check=False).returncode, 0)
        table = run(["compare", self.base, self.new, "--ignore-param", "early_exit", "--markdown"]).stdout
        self.assertIn("| configuration | stage | base ms | new ms | new/base [95%] | p | verdict |", table)

    def test_without_the_ignored_parameter_nothing_matches(self):
        result = run(["compare", self.base, self.new], check=False)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("no configuration is in both files", result.stdout + result.stderr)

    def test_a_csv_without_samples_says_so(self):
        stripped = os.path.join(self.dir, "no_samples.csv")
        with open(self.base, newline="") as source, open(stripped, "w", newline="") as target:
            rows = list(csv.DictReader(source))
            writer = csv.DictWriter(target, fieldnames=list(rows[0].keys()))
            writer.writeheader()
            for row in rows:
                row["samples_ms"] = ""
                writer.writerow(row)
        rows = verdicts(run(["compare", stripped, self.base]).stdout)
        self.assertTrue(rows)
        self.assertEqual({v[2] for v in rows.values()}, {"no samples"})

    def test_the_same_build_against_itself_is_the_same(self):
        out = os.path.join(self.dir, "builds")
        result = run(["compare", "--builds", BUILD, BUILD, "--build-rounds", "8", "--out", out, "--",
                      "-t", "unsorted", "-t", "weighted_blended", *SMALL, "--frames", "12", "--warmup", "2"])
        rows = verdicts(result.stdout)
        totals = [v[2] for (c, s), v in rows.items() if s == "total"]
        self.assertEqual(len(totals), 2, result.stdout)
        self.assertTrue(all(v == "same" for v in totals), result.stdout + result.stderr)
        for build in "ab":
            self.assertEqual(sorted(os.listdir(os.path.join(out, build))),
                             [f"round_{index:02d}.csv" for index in range(1, 9)])
        self.assertIn("Wilcoxon signed-rank", result.stdout)

    def test_too_few_build_rounds_is_refused_with_the_reason(self):
        result = run(["compare", "--builds", BUILD, BUILD, "--build-rounds", "4", "--", "-t", "unsorted"],
                     check=False)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("--build-rounds 4: give at least 8", result.stderr)


if __name__ == "__main__":
    unittest.main()
