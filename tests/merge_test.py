#!/usr/bin/python3
"""analysis.merge and analysis.shards without a GPU or a cluster: the merge
keeps every recording of a run once (an error and the ok run after it, two
revisions, two devices), prefers a whole copy of a recording over one cut
short, merges CSVs from before run ids, matches columns by name across
headers that differ, keeps --out's rows, names every line and run it leaves
out, refuses special files and reports a full disk by name; a sweep file
line becomes bench arguments without --csv, a bad line or shard spec names
its file, and a shard job runs every bench with --resume, writing no .done
when a bench fails as a whole but one when runs only ended in error rows."""
import contextlib
import csv
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, REPO)
sys.path.insert(0, HERE)
import analysis_fixtures as fx  # noqa: E402
from analysis import merge, results_io, shards  # noqa: E402

HEADER = ["timestamp", "git_revision", "device", "gl_version", "platform", "technique", "params", "scene",
          "scene_params", "camera", "width", "height", "clock", "stage", "median_ms", "status", "message"]
RUN_HEADER = HEADER + ["run_id", "run_rows"]
T = ["2026-01-01T00:00:0%dZ" % n for n in range(10)]  # timestamps as the harness writes them


def row(technique="linked_list", stage="total", status="ok", timestamp=T[0], device="GPU A", median="1.0",
        width="64", revision="abc1234", **fields):
    return dict({"timestamp": timestamp, "git_revision": revision, "device": device, "gl_version": "4.5",
                 "platform": "egl-device", "technique": technique, "params": "sort=insertion", "scene": "quads",
                 "scene_params": "layers=4", "camera": "default", "width": width, "height": "64", "clock": "wall",
                 "stage": stage, "median_ms": median if status == "ok" else "", "status": status, "message": ""},
                **fields)


def run(run_id, stages=("fill", "total"), **fields):
    """The rows of one run with its run_id and run_rows."""
    return [row(stage=s, run_id=run_id, run_rows=str(len(stages)), **fields) for s in stages]


class MergeTest(fx.TempDirTest):
    def setUp(self):
        super().setUp()
        self.out = self.path("merged.csv")

    def write(self, name, rows, header=HEADER):
        path = self.path(name)
        with open(path, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=header, lineterminator="\n", extrasaction="ignore")
            writer.writeheader()
            writer.writerows(rows)
        return path

    def read(self, path):
        with open(path, newline="") as f:
            return list(csv.DictReader(f))

    def merge(self, inputs):
        """merge.main on `inputs` into self.out: (exit status, stderr)."""
        errors = io.StringIO()
        with contextlib.redirect_stderr(errors), contextlib.redirect_stdout(io.StringIO()):
            try:
                merge.main(["--out", self.out] + inputs)
                status = 0
            except SystemExit as e:
                status = e.code
        return status, errors.getvalue()

    def test_every_recording_is_kept_once(self):
        # Shard 1: run A failed, then --resume ran it again (ok, two stages); run B ok.
        shard1 = self.write("s1.csv", [row(status="error", timestamp=T[1]), row(stage="fill", timestamp=T[2]),
                                       row(timestamp=T[2]), row(technique="kbuffer", timestamp=T[1])])
        shard2 = self.write("s2.csv", [row(technique="unsorted", timestamp=T[3])])
        counts, notes = merge.merge(self.out, [shard1, shard2, shard1])  # shard1 twice: its rows once
        self.assertEqual([(r["technique"], r["stage"], r["status"], r["timestamp"]) for r in self.read(self.out)],
                         [("linked_list", "total", "error", T[1]), ("linked_list", "fill", "ok", T[2]),
                          ("linked_list", "total", "ok", T[2]), ("kbuffer", "total", "ok", T[1]),
                          ("unsorted", "total", "ok", T[3])])
        self.assertEqual((counts["recordings"], counts["recordings_left_out"], counts["duplicate_rows"]), (4, 0, 4))
        self.assertEqual(notes, [])
        self.assertEqual(os.stat(self.out).st_mode & 0o777, 0o666 & ~self.umask())

    def umask(self):
        mask = os.umask(0)
        os.umask(mask)
        return mask

    def test_other_revisions_and_invocations_are_other_recordings(self):
        a = self.write("a.csv", [row(revision="aaaaaaa", timestamp=T[1], median="1.0"),
                                 row(revision="bbbbbbb", timestamp=T[2], median="2.0")])
        b = self.write("b.csv", run("r1", timestamp=T[3], median="3.0") + run("r2", timestamp=T[4], median="4.0"),
                       header=RUN_HEADER)
        merge.merge(self.out, [a, b])
        self.assertEqual([(r["git_revision"], r["run_id"], r["median_ms"]) for r in self.read(self.out)],
                         [("aaaaaaa", "", "1.0"), ("bbbbbbb", "", "2.0"), ("abc1234", "r1", "3.0"),
                          ("abc1234", "r1", "3.0"), ("abc1234", "r2", "4.0"), ("abc1234", "r2", "4.0")])

    def test_a_copy_cut_short_never_wins_over_a_whole_one(self):
        # A shard that crashed after one of run r1's two rows, retried (run r2 whole); then r1 whole elsewhere.
        crashed = self.write("crashed.csv", run("r1", timestamp=T[1])[:1] + run("r2", timestamp=T[2]),
                             header=RUN_HEADER)
        lone = self.write("lone.csv", run("r3", timestamp=T[3])[1:], header=RUN_HEADER)
        whole = self.write("whole.csv", run("r1", timestamp=T[1], median="5.0"), header=RUN_HEADER)
        counts, notes = merge.merge(self.out, [crashed, lone, whole])
        self.assertEqual([(r["run_id"], r["stage"], r["median_ms"]) for r in self.read(self.out)],
                         [("r1", "fill", "5.0"), ("r1", "total", "5.0"), ("r2", "fill", "1.0"),
                          ("r2", "total", "1.0")])
        self.assertEqual(notes, [
            f"{crashed}: line 2: run r1 has 1 row(s) of 2 (a run cut short is not a result); the whole copy "
            f"in {whole} is kept: left out",
            f"{lone}: line 2: run r3 has 1 row(s) of 2 (a run cut short is not a result), and no input "
            "holds it whole: left out"])
        self.assertEqual(counts["recordings_left_out"], 1)

    def test_a_csv_from_before_run_ids_merges_whole_and_reads_back_whole(self):
        models = os.path.join(REPO, "results", "reference", "models_256.csv")
        new = self.write("new.csv", run("r1", technique="unsorted"), header=RUN_HEADER)
        status, errors = self.merge([models, new])
        self.assertEqual((status, errors), (0, ""))
        header, kept = results_io.whole_rows(self.out)
        self.assertEqual(len(kept), 128 + 2)
        self.assertEqual(header[-2:], ["run_id", "run_rows"])

    def test_a_row_shifted_by_an_open_quote_is_named_and_the_rows_after_it_kept(self):
        shard = self.write("s.csv", [row(technique=t, timestamp=T[i]) for i, t in enumerate("abcde")])
        with open(shard) as f:
            lines = f.readlines()
        lines[2] = lines[2].replace(",ok,", ',ok,"out of memory,', 1)  # an error message whose quote never closes
        lines[4] = lines[4].replace(",d,", ",4.5 (Core Profile,", 1)  # a technique the harness never writes
        with open(shard, "w") as f:
            f.writelines(lines)
        status, errors = self.merge([shard])
        self.assertEqual(status, 0)
        self.assertEqual([r["technique"] for r in self.read(self.out)], ["a", "c", "e"])
        self.assertIn(f"{shard}: line 3: a quote left open, never closed: left out\n", errors)
        self.assertIn(f"{shard}: line 5: technique '4.5 (Core Profile' is not a technique id: left out\n", errors)

    def test_two_devices_are_two_recordings_with_their_own_device_and_platform(self):
        a = self.write("a.csv", [row(device="GPU A", median="1.0")])
        b = self.write("b.csv", [dict(row(device="GPU B", median="2.0"), platform="egl-device, 4k")])
        merge.merge(self.out, [a, b])
        self.assertEqual([(r["device"], r["platform"], r["median_ms"]) for r in self.read(self.out)],
                         [("GPU A", "egl-device", "1.0"), ("GPU B", "egl-device, 4k", "2.0")])

    def test_columns_are_matched_by_name_and_the_header_is_their_union(self):
        old = self.write("old.csv", [row()])
        newer_header = HEADER[:5] + ["tiles"] + HEADER[5:]
        new = self.write("new.csv", [dict(row(technique="kbuffer"), tiles="4")], header=list(reversed(newer_header)))
        merge.merge(self.out, [old, new])
        with open(self.out, newline="") as f:
            header = next(csv.reader(f))
        self.assertEqual(header, HEADER + ["tiles"])
        self.assertEqual([(r["technique"], r["tiles"], r["median_ms"]) for r in self.read(self.out)],
                         [("linked_list", "", "1.0"), ("kbuffer", "4", "1.0")])

    def test_rows_already_in_out_are_kept_and_merging_again_changes_nothing(self):
        self.write("merged.csv", [row(technique="kbuffer", timestamp=T[0])])
        shard = self.write("s.csv", [row(timestamp=T[1]), row(technique="kbuffer", timestamp=T[9])])
        merge.merge(self.out, [shard])
        first = self.read(self.out)
        self.assertEqual([(r["technique"], r["timestamp"]) for r in first],
                         [("kbuffer", T[0]), ("linked_list", T[1]), ("kbuffer", T[9])])
        merge.merge(self.out, [shard])
        self.assertEqual(self.read(self.out), first)

    def test_a_file_that_is_not_an_oitbench_csv_is_named(self):
        bad = self.path("notes.csv")
        with open(bad, "w") as f:
            f.write("a,b\n1,2\n")
        with self.assertRaisesRegex(merge.MergeError, r"notes\.csv: not an oitbench CSV, no column\(s\) technique"):
            merge.merge(self.out, [bad])
        self.assertFalse(os.path.exists(self.out))
        short = self.write("short.csv", [row()])
        with open(short, "a") as f:
            f.write("x,y\n")
        counts, notes = merge.merge(self.out, [short])
        self.assertEqual(notes, [f"{short}: line 3: 2 fields, the header has 17: left out"])
        self.assertEqual(counts["rows"], 1)

    def test_special_files_are_refused_not_read_or_written(self):
        # Run in a child with a time limit: reading /dev/zero would never end.
        shard = self.write("s.csv", [row()])
        os.symlink("/dev/full", self.out)
        for inputs, message in (([shard, "/dev/zero"], "merge: /dev/zero is not a regular file"),
                                ([shard], f"merge: --out {self.out} is not a regular file")):
            out = self.out if "/dev/zero" not in inputs else self.path("m.csv")
            result = subprocess.run([sys.executable, "-m", "analysis.merge", "--out", out] + inputs, cwd=REPO,
                                    capture_output=True, text=True, timeout=60)
            self.assertEqual((result.returncode, result.stderr), (1, message + "\n"))
        self.assertEqual(os.readlink(self.out), "/dev/full")

    def test_a_full_disk_is_an_error_naming_the_file(self):
        # A file-size limit on the child: its writes fail as on a full disk.
        shard = self.write("s.csv", [row(technique=f"t{i}", timestamp=T[i % 10]) for i in range(100)])
        code = ("import resource, signal, sys; signal.signal(signal.SIGXFSZ, signal.SIG_IGN);"
                "resource.setrlimit(resource.RLIMIT_FSIZE, (2000, 2000));"
                "from analysis import merge; merge.main(sys.argv[1:])")
        result = subprocess.run([sys.executable, "-c", code, "--out", self.out, shard], cwd=REPO,
                                capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr, f"merge: cannot write '{self.out}': [Errno 27] File too large\n")
        self.assertEqual(sorted(os.listdir(self.tmp.name)), ["s.csv"])


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

    def test_runs_ending_in_error_rows_do_not_fail_the_job(self):
        with tempfile.TemporaryDirectory() as tmp:
            fake = os.path.join(tmp, "oitbench")  # bench's status when some runs wrote error rows
            with open(fake, "w") as f:
                f.write("#!/bin/sh\nexit 4\n")
            os.chmod(fake, 0o755)
            spec, done = os.path.join(tmp, "s.json"), os.path.join(tmp, "s.done")
            shards.write_json_atomically(spec, [["bench", "--technique", "a"]])
            shards.main(["run", spec, "--oitbench", fake, "--csv", os.path.join(tmp, "s.csv"), "--done", done])
            self.assertTrue(os.path.exists(done))

    def test_a_malformed_spec_is_an_error_naming_it(self):
        with tempfile.TemporaryDirectory() as tmp:
            spec = os.path.join(tmp, "shard.json")
            for text, why in (("[[\"bench\"", "not a JSON shard spec (Expecting"),
                              ("{\"bench\": 1}", "not a list of bench argument lists"),
                              ("[[\"render\", \"--out\", \"x.png\"]]", "not a list of bench argument lists"),
                              (None, "is not a regular file"),
                              ("", "cannot read: No such file or directory")):
                if os.path.lexists(spec):
                    os.unlink(spec)
                if text is None:
                    os.symlink("/dev/zero", spec)
                elif text:
                    with open(spec, "w") as f:
                        f.write(text)
                else:
                    spec = os.path.join(tmp, "missing.json")
                result = subprocess.run([sys.executable, "-m", "analysis.shards", "run", spec, "--oitbench", "true",
                                         "--csv", os.path.join(tmp, "s.csv"), "--done", os.path.join(tmp, "d")],
                                        cwd=REPO, capture_output=True, text=True, timeout=60)
                self.assertEqual(result.returncode, 1, result.stderr)
                self.assertTrue(result.stderr.startswith(f"shards: {spec}"), result.stderr)
                self.assertIn(why, result.stderr)
                self.assertNotIn("Traceback", result.stderr)

    def test_shards_are_named_by_their_content(self):
        benches = [["bench", "--technique", t] for t in ("a", "b", "c")]
        cut = shards.cut(benches, 2)
        self.assertEqual(list(cut.values()), [benches[:2], benches[2:]])
        self.assertEqual(list(shards.cut(benches[:2], 2)), list(cut)[:1])


if __name__ == "__main__":
    unittest.main()
