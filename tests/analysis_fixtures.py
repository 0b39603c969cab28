"""CSV fixtures for the analysis tests, in the exact column layout the harness
writes: the column list is read from harness/run/results_csv.cpp itself, so
a new column there cannot leave the fixtures silently out of date."""
import csv
import itertools
import os
import re
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
DEVICE = "llvmpipe (LLVM 15.0.6, 256 bits)"  # holds a comma: the fixtures must quote it like the harness


def csv_columns():
    with open(os.path.join(REPO, "harness", "run", "results_csv.cpp")) as f:
        source = f.read()
    block = re.search(r"csv_columns\(\) \{.*?=\s*\{(.*?)\};", source, re.S).group(1)
    return re.findall(r'"([a-z0-9_]+)"', block)


def row(technique, stage, median_ms, params="", scene="quads", scene_params="layers=32", camera="default",
        width=64, height=64, status="ok", **fields):
    values = {"timestamp": "2026-11-22T09:00:00Z", "git_revision": "abc", "device": DEVICE, "gl_version": "4.5",
              "platform": "egl-surfaceless", "technique": technique, "params": params, "scene": scene,
              "scene_params": scene_params, "camera": camera, "width": str(width), "height": str(height),
              "clock": "wall", "stage": stage, "median_ms": str(median_ms), "frames": "3", "warmup": "1",
              "status": status, "noisy": "false"}
    values.update({k: str(v) for k, v in fields.items()})
    return values


_calls = itertools.count()


def with_run_columns(rows):
    """run_id and run_rows as the harness writes them, where a row lacks them:
    the rows of one configuration in one call are one run."""
    call = next(_calls)
    key = lambda r: tuple(r.get(k) for k in ("technique", "params", "scene", "scene_params", "camera", "width",
                                             "height"))
    groups = list(dict.fromkeys(key(r) for r in rows))
    sizes = {g: sum(1 for r in rows if key(r) == g) for g in groups}
    return [{"run_id": f"fixture{os.getpid()}-{call}-{groups.index(key(r))}", "run_rows": str(sizes[key(r)]), **r}
            for r in rows]


def write_csv(path, rows, append=False):
    columns = csv_columns()
    rows = with_run_columns(rows)
    new = not append or not os.path.exists(path) or os.path.getsize(path) == 0
    with open(path, "a" if append else "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, restval="", lineterminator="\n")
        if new:
            writer.writeheader()
        for r in rows:
            writer.writerow(r)


class TempDirTest(unittest.TestCase):
    """A test with a fresh temporary directory, removed after it: `self.tmp`,
    `self.path(name)` for a file there and `self.csv` for the usual results
    file (runs.csv, not written)."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.csv = self.path("runs.csv")

    def path(self, name):
        return os.path.join(self.tmp.name, name)
