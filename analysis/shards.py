"""The sweeps of the Snakemake workflow (workflow/Snakefile), cut into shards, and the job that runs one shard.

A sweep is a list of `oitbench bench` invocations: those of analysis.reproduce
(its sweeps as data, plan_as_data) or the lines of a sweep file as the
viewer's "Add this configuration to the sweep file" writes them
(`oitbench bench ... --csv FILE`, # comments). A shard is a run of
consecutive invocations executed by one job, named by a hash of its
invocations: a changed sweep makes new shards instead of reusing results
recorded for other runs.

    /usr/bin/python3 -m analysis.shards run SPEC.json --oitbench BIN --device DEV --csv SHARD.csv --done DONE.json

runs every invocation of the shard (SPEC: a JSON list of argument lists)
with `--csv SHARD.csv --resume`, so a job started again after a crash or a
cancellation runs only what the CSV lacks. A run that ends in an error row
does not fail the job (bench exits 4: its rows are all written, and the
error rows run again when the shard does); a bench that fails as a whole
(any other non-zero status) makes the job fail after the others ran, and
DONE (the job's output) is written only when no bench did.
"""
import argparse
import hashlib
import json
import os
import re
import shlex
import subprocess
import sys
from collections import Counter, OrderedDict

from analysis import reproduce, results_io

# bench's exit status when every row is written and some runs are error
# rows (docs/REFERENCE.md, bench).
RUNS_FAILED = 4


class SweepFileError(Exception):
    """A sweep file line that is not a bench command; the message names file and line."""


class ShardSpecError(Exception):
    """A shard spec that is not a JSON list of bench argument lists; the message names it."""


def read_sweep_file(path):
    """The bench invocations of a sweep file as argument lists (["bench", ...])
    without the binary and --csv (the shard job sets both)."""
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise SweepFileError(f"{path}: cannot read: {e.strerror}") from e
    benches = []
    for number, line in enumerate(lines, start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        where = f"{path}:{number}"
        try:
            words = shlex.split(line)
        except ValueError as e:
            raise SweepFileError(f"{where}: {e}") from e
        if len(words) < 2 or os.path.basename(words[0]) != "oitbench" or words[1] != "bench":
            raise SweepFileError(f"{where}: expected 'oitbench bench ...', found {line.strip()!r}")
        arguments, rest = ["bench"], iter(words[2:])
        for word in rest:
            if word == "--csv":
                if next(rest, None) is None:
                    raise SweepFileError(f"{where}: --csv without a file")
            elif word.startswith("--csv="):
                continue
            elif word in ("--resume", "--device") or word.startswith("--device="):
                raise SweepFileError(f"{where}: {word} is set by the workflow (config: device), not per line")
            else:
                arguments.append(word)
        benches.append(arguments)
    if not benches:
        raise SweepFileError(f"{path}: no 'oitbench bench' line")
    return benches


def shard_id(benches):
    return hashlib.sha1(json.dumps(benches).encode()).hexdigest()[:12]


def cut(benches, per_shard):
    """OrderedDict shard id -> its invocations, `per_shard` consecutive ones each."""
    if per_shard < 1:
        raise ValueError(f"benches_per_shard {per_shard} must be at least 1")
    shards = OrderedDict()
    for start in range(0, len(benches), per_shard):
        chunk = benches[start:start + per_shard]
        shards[shard_id(chunk)] = chunk
    return shards


def sweep_name(path):
    return re.sub(r"[^A-Za-z0-9_]+", "_", os.path.splitext(os.path.basename(path))[0]).strip("_") or "sweep"


def workflow_sweeps(config, oitbench):
    """name -> {"kind": "reproduce" or "file", "benches", "heatmaps", "plots"}
    for the workflow's config (workflow/config.yaml documents the keys)."""
    sweeps = OrderedDict()
    mode = str(config.get("reproduce", "none"))
    if mode not in ("none", "quick", "full"):
        raise ValueError(f"config reproduce: '{mode}' is not one of none, quick, full")
    if mode != "none":
        planned = reproduce.plan(reproduce.catalogue_of(oitbench, reproduce.oitbench_environment(oitbench)),
                                 mode == "quick")
        only = config.get("only") or [s.name for s in planned]
        unknown = set(only) - {s.name for s in planned}
        if unknown:
            raise ValueError(f"config only: unknown sweep(s) {', '.join(sorted(unknown))}: expected "
                             f"{', '.join(s.name for s in planned)}")
        for data in reproduce.plan_as_data([s for s in planned if s.name in only]):
            if data["skipped"]:
                print(f"workflow: {data['name']} skipped: {data['skipped']}", file=sys.stderr)
                continue
            sweeps[data["name"]] = dict(data, kind="reproduce")
    for path in config.get("sweep_files") or []:
        name = sweep_name(path)
        if name in sweeps:
            raise ValueError(f"config sweep_files: {path} would be sweep '{name}', which is already taken: "
                             "rename the file")
        sweeps[name] = {"kind": "file", "benches": read_sweep_file(path), "heatmaps": [], "plots": ["plot_stages"]}
    return sweeps


def write_json_atomically(path, data):
    """`data` as JSON into `path`, whole (results_io.write_whole)."""
    def write(f):
        json.dump(data, f, indent=1)
        f.write("\n")
    results_io.write_whole(path, write, binary=False)


def read_spec(path):
    """The bench argument lists of a shard spec (as write_json_atomically
    wrote them); ShardSpecError naming the file otherwise."""
    try:
        results_io.require_regular_file(path)
        with open(path) as f:
            benches = json.load(f)
    except results_io.ResultsError as e:
        raise ShardSpecError(str(e)) from e
    except OSError as e:
        raise ShardSpecError(f"{path}: cannot read: {e.strerror}") from e
    except ValueError as e:  # not JSON, or not text
        raise ShardSpecError(f"{path}: not a JSON shard spec ({e})") from e
    if not isinstance(benches, list) or not all(
            isinstance(b, list) and b[:1] == ["bench"] and all(isinstance(w, str) for w in b) for b in benches):
        raise ShardSpecError(f"{path}: not a list of bench argument lists (like [[\"bench\", \"--technique\", "
                             f"\"unsorted\"]]): write it with the workflow's shard_spec rule")
    return benches


def run_shard(spec, oitbench, device, csv_path):
    """Runs the shard's invocations; returns the commands that failed as a
    whole (error rows alone are no failure: RUNS_FAILED)."""
    benches = read_spec(spec)
    env = reproduce.oitbench_environment(oitbench)
    failed = []
    for i, arguments in enumerate(benches, start=1):
        command = [oitbench, "--device", device] + arguments + ["--csv", csv_path, "--resume"]
        print(f"[{i}/{len(benches)}] {shlex.join(command)}", flush=True)
        try:
            status = subprocess.run(command, env=env).returncode
        except OSError as e:
            print(f"  cannot run {oitbench}: {e.strerror}", flush=True)
            status = None
        if status == RUNS_FAILED:
            print(f"  some runs ended in error rows (kept in {csv_path}; they run again when the shard does)",
                  flush=True)
        elif status != 0:
            print(f"  exit status {status}" if status is not None else "  not run", flush=True)
            failed.append(command)
    return failed


def summary(csv_path):
    """What the shard's CSV holds: row count, statuses, devices."""
    rows = reproduce.read_rows(csv_path)
    return {"rows": len(rows), "status": dict(Counter(r.get("status", "") for r in rows)),
            "devices": sorted({f"{r.get('device', '')} ({r.get('platform', '')})" for r in rows})}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run one shard (a Snakemake job)")
    run.add_argument("spec", help="JSON list of bench argument lists")
    run.add_argument("--oitbench", required=True)
    run.add_argument("--device", default="auto", help="oitbench --device")
    run.add_argument("--csv", required=True, help="the shard's CSV (appended to, never replaced)")
    run.add_argument("--done", required=True, help="written when no bench failed as a whole")
    args = parser.parse_args(argv)
    try:
        failed = run_shard(args.spec, args.oitbench, args.device, args.csv)
        if failed:
            sys.exit(f"shards: {len(failed)} bench invocation(s) failed as a whole (see above); the rows they wrote "
                     f"stay in {args.csv} and a new attempt resumes from them")
        write_json_atomically(args.done, dict(summary(args.csv), csv=args.csv))
    except (ShardSpecError, results_io.ResultsError, OSError) as e:
        sys.exit(f"shards: {e}")


if __name__ == "__main__":
    main()
