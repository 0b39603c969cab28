#!/usr/bin/python3
"""tools/gpu_survey.sh in its --quick form with the built binaries (argv[1]:
the build directory): it writes, under --out, a README.md naming every step
with its command, duration and exit status, the device lines of `oitbench
list`, the doctor's verdicts and the bench CSVs; a step that fails is
recorded, the steps after it still run, and the script exits non-zero."""
import csv
import os
import re
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(os.path.dirname(HERE), "tools", "gpu_survey.sh")
BUILD = os.path.abspath(sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(HERE), "build"))


def survey(*arguments):
    return subprocess.run(["bash", SCRIPT, "--build", BUILD, *arguments], capture_output=True, text=True, timeout=500)


def step_rows(readme):
    """step -> (command, seconds, exit status, output file) from the README's table."""
    rows = {}
    for line in readme.splitlines():
        match = re.match(r"^\| (\w+) \| `(.*)` \| ([\d.]+) \| (\d+) \| (\S+) \|$", line)
        if match:
            rows[match.group(1)] = (match.group(2), float(match.group(3)), int(match.group(4)), match.group(5))
    return rows


def total_rows(path):
    with open(path, newline="") as f:
        return [row for row in csv.DictReader(f) if row["stage"] == "total"]


class QuickSurvey(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = os.path.join(cls.tmp.name, "survey")
        cls.result = survey("--quick", "--out", cls.out)
        with open(os.path.join(cls.out, "README.md")) as f:
            cls.readme = f.read()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_every_step_ran_and_passed(self):
        self.assertEqual(self.result.returncode, 0, self.result.stdout + self.result.stderr + self.readme)
        rows = step_rows(self.readme)
        self.assertEqual(list(rows), ["smi_start", "list", "doctor", "ctest", "quads", "quads64", "engine", "dragon", "smi_end"])
        for step, (command, seconds, status, output) in rows.items():
            self.assertEqual(status, 0, step)
            self.assertGreaterEqual(seconds, 0.0, step)
            self.assertTrue(os.path.isfile(os.path.join(self.out, output)), output)
        self.assertIn("$BUILD/harness/oitbench doctor --technique linked_list --technique kbuffer", rows["doctor"][0])
        self.assertIn("- failed steps: none", self.readme)

    def test_readme_records_the_revision_and_the_device(self):
        checkout = subprocess.run(["git", "-C", HERE, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
        with open(os.path.join(BUILD, "generated", "oit_revision.h")) as f:
            built = re.search(r'OIT_GIT_REVISION "(.+)"', f.read()).group(1)
        self.assertRegex(self.readme, rf"(?m)^- build's revision \(what ran; .*\): {re.escape(built)}$")
        self.assertIn(f"- checkout: {checkout} ", self.readme)
        self.assertIn(f"- build: {BUILD}\n", self.readme)
        self.assertRegex(self.readme, r"(?m)^# GPU survey: \S")
        device = self.readme.split("## Device (`oitbench list`)")[1]
        self.assertRegex(device, r"(?m)^Device: .+$")
        self.assertRegex(device, r"(?m)^Limits: largest buffer ")
        self.assertNotIn("Techniques:", device)

    def test_doctor_verdicts_are_kept(self):
        with open(os.path.join(self.out, "doctor.txt")) as f:
            doctor = f.read()
        self.assertRegex(doctor, r"(?m)^  linked_list +exact +exact here ")
        self.assertRegex(doctor, r"(?m)^  kbuffer +exact while storage covers +exact here ")

    def test_bench_csvs_hold_every_run(self):
        expected = {"quads.csv": ("quads", 1), "quads64.csv": ("quads", 1), "engine.csv": ("torus", 1),
                    "dragon.csv": ("nested_spheres", 1)}
        for name, (scene, configurations) in expected.items():
            rows = total_rows(os.path.join(self.out, name))
            self.assertEqual(len(rows), 3 * configurations, name)
            self.assertEqual({row["technique"] for row in rows}, {"unsorted", "linked_list", "kbuffer"}, name)
            for row in rows:
                self.assertEqual((row["status"], row["scene"], row["width"], row["height"]), ("ok", scene, "32", "32"))
                self.assertGreater(float(row["median_ms"]), 0.0)


class FailingStep(unittest.TestCase):
    def test_a_failing_step_is_recorded_and_the_next_steps_still_run(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "survey")
            # linked_list with room for 4 of the doctor's 32 layers: not exact, exit 3.
            result = survey("--quick", "--out", out, "--only", "doctor,list",
                            "--doctor-arg=--set", "--doctor-arg=linked_list.max_per_pixel=4")
            self.assertEqual(result.returncode, 1, result.stderr)
            with open(os.path.join(out, "README.md")) as f:
                readme = f.read()
            rows = step_rows(readme)
            self.assertEqual(list(rows), ["list", "doctor"])
            self.assertEqual(rows["doctor"][2], 3)
            self.assertEqual(rows["list"][2], 0)
            self.assertIn("- failed steps: doctor\n", readme)
            self.assertIn("failed steps: doctor", result.stderr)

    def test_bad_arguments_name_the_problem(self):
        with tempfile.TemporaryDirectory() as tmp:
            for arguments, message in ((["--quick"], "--quick writes to --out DIR"),
                                       (["--only", "nothing"], "--only: unknown step 'nothing'"),
                                       (["--build", tmp], f"no oitbench at {tmp}/harness/oitbench"),
                                       (["--compare-build", tmp, "--out", tmp + "/x"], "has no harness/oitbench")):
                result = subprocess.run(["bash", SCRIPT, *(["--build", BUILD] if "--build" not in arguments else []),
                                         *arguments], capture_output=True, text=True)
                self.assertEqual(result.returncode, 2, arguments)
                self.assertIn(message, result.stderr, arguments)
            with open(os.path.join(tmp, "kept.txt"), "w") as f:
                f.write("an earlier survey")
            result = survey("--out", tmp)
            self.assertEqual(result.returncode, 2)
            self.assertIn("is not empty", result.stderr)


if __name__ == "__main__":
    unittest.main(verbosity=2)
