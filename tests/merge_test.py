#!/usr/bin/python3
"""analysis.merge and analysis.shards without a GPU or a cluster: the merge
keeps one recording per run and machine (an ok one over an error one, never
two), keeps the same configuration measured on two devices as two runs,
matches columns by name across headers that differ, keeps --out's rows and
rejects a file that is not an oitbench CSV by name; a sweep file line
becomes bench arguments without --csv, a bad line names file and line, and
a shard job runs every bench with --resume but writes no .done when one fails."""
import csv
import json
import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from analysis import merge, shards  # noqa: E402

HEADER = ["timestamp", "device", "gl_version", "platform", "technique", "params", "scene", "scene_params", "camera",
          "width", "height", "clock", "stage", "median_ms", "status", "message"]


def row(technique="linked_list", stage="total", status="ok", timestamp="2026-01-01T00:00:00Z", device="GPU A",
        median="1.0", width="64"):
    return {"timestamp": timestamp, "device": device, "gl_version": "4.5", "platform": "egl-device",
            "technique": technique, "params": "sort=insertion", "scene": "quads", "scene_params": "layers=4",
            "camera": "default", "width": width, "height": "64", "clock": "wall", "stage": stage,
            "median_ms": median if status == "ok" else "", "status": status, "message": ""}


class MergeTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, name, rows, header=HEADER):
        path = os.path.join(self.tmp.name, name)
        with open(path, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=header, lineterminator="\n", extrasaction="ignore")
            writer.writeheader()
            writer.writerows(rows)
        return path

    def read(self, path):
        with open(path, newline="") as f:
            return list(csv.DictReader(f))

    def test_an_ok_recording_replaces_the_error_one_and_nothing_is_doubled(self):
        # Shard 1: run A failed, then --resume ran it again (ok, two stages); run B ok.
        shard1 = self.write("s1.csv", [row(status="error", timestamp="t1"),
                                       row(stage="fill", timestamp="t2"), row(timestamp="t2"),
                                       row(technique="kbuffer", timestamp="t1")])
        shard2 = self.write("s2.csv", [row(technique="unsorted", timestamp="t3")])
        out = os.path.join(self.tmp.name, "merged.csv")
        counts = merge.merge(out, [shard1, shard2, shard1])  # shard1 twice: its rows once
        rows = self.read(out)
        self.assertEqual([(r["technique"], r["stage"], r["status"], r["timestamp"]) for r in rows],
                         [("linked_list", "fill", "ok", "t2"), ("linked_list", "total", "ok", "t2"),
                          ("kbuffer", "total", "ok", "t1"), ("unsorted", "total", "ok", "t3")])
        self.assertEqual(counts["runs"], 3)
        self.assertEqual(counts["recordings_left_out"], 1)  # the error recording
        self.assertEqual(counts["duplicate_rows"], 3)  # shard1's second copy

    def test_the_last_error_stays_when_no_attempt_succeeded(self):
        shard = self.write("s.csv", [row(status="error", timestamp="t1"), row(status="error", timestamp="t2")])
        out = os.path.join(self.tmp.name, "merged.csv")
        merge.merge(out, [shard])
        self.assertEqual([(r["status"], r["timestamp"]) for r in self.read(out)], [("error", "t2")])

    def test_two_devices_are_two_runs_with_their_own_device_and_platform(self):
        a = self.write("a.csv", [row(device="GPU A", median="1.0")])
        b = self.write("b.csv", [dict(row(device="GPU B", median="2.0"), platform="egl-device, 4k")])
        out = os.path.join(self.tmp.name, "merged.csv")
        merge.merge(out, [a, b])
        self.assertEqual([(r["device"], r["platform"], r["median_ms"]) for r in self.read(out)],
                         [("GPU A", "egl-device", "1.0"), ("GPU B", "egl-device, 4k", "2.0")])

    def test_columns_are_matched_by_name_and_the_header_is_their_union(self):
        old = self.write("old.csv", [row()])
        newer_header = HEADER[:5] + ["tiles"] + HEADER[5:]
        new = self.write("new.csv", [dict(row(technique="kbuffer"), tiles="4")], header=list(reversed(newer_header)))
        out = os.path.join(self.tmp.name, "merged.csv")
        merge.merge(out, [old, new])
        with open(out, newline="") as f:
            header = next(csv.reader(f))
        self.assertEqual(header, HEADER + ["tiles"])
        rows = self.read(out)
        self.assertEqual([(r["technique"], r["tiles"], r["median_ms"]) for r in rows],
                         [("linked_list", "", "1.0"), ("kbuffer", "4", "1.0")])

    def test_rows_already_in_out_are_kept_and_merging_again_changes_nothing(self):
        out = self.write("merged.csv", [row(technique="kbuffer", timestamp="t0")])
        shard = self.write("s.csv", [row(timestamp="t1"), row(technique="kbuffer", timestamp="t9")])
        merge.merge(out, [shard])
        first = self.read(out)
        self.assertEqual([(r["technique"], r["timestamp"]) for r in first], [("kbuffer", "t0"), ("linked_list", "t1")])
        merge.merge(out, [shard])
        self.assertEqual(self.read(out), first)

    def test_a_file_that_is_not_an_oitbench_csv_is_named(self):
        bad = os.path.join(self.tmp.name, "notes.csv")
        with open(bad, "w") as f:
            f.write("a,b\n1,2\n")
        out = os.path.join(self.tmp.name, "merged.csv")
        with self.assertRaisesRegex(merge.MergeError, r"notes\.csv: not an oitbench CSV, no column\(s\) technique"):
            merge.merge(out, [bad])
        self.assertFalse(os.path.exists(out))
        short = self.write("short.csv", [row()])
        with open(short, "a") as f:
            f.write("x,y\n")
        with self.assertRaisesRegex(merge.MergeError, r"short\.csv:3: 2 fields, the header has 16"):
            merge.merge(out, [short])


class SweepFileTest(unittest.TestCase):
    def test_viewer_lines_become_bench_arguments_and_bad_lines_are_named(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "my sweep.txt")
            with open(path, "w") as f:
                f.write("# linked_list at 64x64\n"
                        "oitbench bench --technique linked_list --set 'sort=insertion' --scene quads "
                        "--size 64x64 --camera default --background 0,0,0 --csv oitbench_sweep.csv\n\n"
                        "build/harness/oitbench bench --technique kbuffer --scene quads --csv=x.csv\n")
            self.assertEqual(shards.read_sweep_file(path), [
                ["bench", "--technique", "linked_list", "--set", "sort=insertion", "--scene", "quads", "--size",
                 "64x64", "--camera", "default", "--background", "0,0,0"],
                ["bench", "--technique", "kbuffer", "--scene", "quads"]])
            self.assertEqual(shards.sweep_name(path), "my_sweep")
            with open(path, "a") as f:
                f.write("oitbench render --technique kbuffer --out x.png\n")
            with self.assertRaisesRegex(shards.SweepFileError, r"my sweep\.txt:5: expected 'oitbench bench"):
                shards.read_sweep_file(path)

    def test_a_shard_job_runs_every_bench_resuming_and_fails_without_done_if_one_fails(self):
        with tempfile.TemporaryDirectory() as tmp:
            # A stand-in oitbench: logs its arguments, fails on technique "broken".
            fake, log = os.path.join(tmp, "oitbench"), os.path.join(tmp, "calls.log")
            with open(fake, "w") as f:
                f.write(f"#!/bin/sh\necho \"$*\" >> {log}\ncase \"$*\" in *broken*) exit 3;; esac\n")
            os.chmod(fake, 0o755)
            spec, done = os.path.join(tmp, "s.json"), os.path.join(tmp, "s.done")
            shards.write_json_atomically(spec, [["bench", "--technique", t] for t in ("a", "broken", "c")])
            arguments = ["run", spec, "--oitbench", fake, "--device", "egl:1", "--csv", "s.csv", "--done", done]
            with self.assertRaisesRegex(SystemExit, "1 bench invocation"):
                shards.main(arguments)
            self.assertFalse(os.path.exists(done))
            with open(log) as f:
                self.assertEqual(f.read().splitlines(), [
                    f"--device egl:1 bench --technique {t} --csv s.csv --resume" for t in ("a", "broken", "c")])
            shards.write_json_atomically(spec, [["bench", "--technique", "a"]])
            shards.main(arguments)
            with open(done) as f:
                self.assertEqual(json.load(f), {"rows": 0, "status": {}, "devices": [], "csv": "s.csv"})

    def test_shards_are_named_by_their_content(self):
        benches = [["bench", "--technique", t] for t in ("a", "b", "c")]
        cut = shards.cut(benches, 2)
        self.assertEqual(list(cut.values()), [benches[:2], benches[2:]])
        self.assertEqual(list(shards.cut(benches[:2], 2)), list(cut)[:1])


if __name__ == "__main__":
    unittest.main()
