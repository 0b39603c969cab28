"""Merge oitbench CSVs (the shards of a sweep, runs from several machines) into one, without duplicates.

Usage: /usr/bin/python3 -m analysis.merge --out merged.csv shard1.csv shard2.csv ...

A run is one configuration (the RUN_COLUMNS the header has: technique,
params, scene, scene_params, camera, width, height, scene_rect) on one machine
(MACHINE_COLUMNS: device, gl_version, platform). The same configuration
measured on two machines is two runs: both are kept, each row with its own
device and platform, so that they can be compared side by side.

A run can be recorded more than once: `bench --resume` runs an error row's
configuration again and appends the new rows, a shard retried after a crash
may hold a partial attempt, the same file may be given twice. A recording is
the rows of one run that share a timestamp (one bench invocation writes them
together). Per run the merge keeps one recording whole: the first ok or
skipped one in input order (--out's own rows first), else the last error one;
the others are left out and counted. Exact duplicate rows are written once.

The header is the union of the inputs' headers in first-seen order (columns
are matched by name, so CSVs written by builds with more or fewer columns
merge; a missing value is empty). If --out exists its rows are read first
and kept: merging again with more inputs only adds. The output is written to
a temporary file and renamed over --out, so a reader never sees half of it.
"""
import argparse
import csv
import os
import sys
import tempfile
from collections import OrderedDict

RUN_COLUMNS = ["technique", "params", "scene", "scene_params", "camera", "width", "height", "scene_rect"]
MACHINE_COLUMNS = ["device", "gl_version", "platform"]
REQUIRED = ["technique", "scene", "status", "timestamp", "device", "platform"]
DONE = ("ok", "skipped")


class MergeError(Exception):
    """An input that cannot be merged; the message names the file."""


def read_table(path):
    """(header, rows as dicts) of one CSV; an empty file has neither."""
    try:
        with open(path, newline="") as f:
            reader = csv.reader(f)
            header = next(reader, None)
            if header is None:
                return [], []
            missing = [c for c in REQUIRED if c not in header]
            if missing:
                raise MergeError(f"{path}: not an oitbench CSV, no column(s) {', '.join(missing)}")
            rows = []
            for number, record in enumerate(reader, start=2):
                if len(record) != len(header):
                    raise MergeError(f"{path}:{number}: {len(record)} fields, the header has {len(header)}")
                rows.append(dict(zip(header, record)))
            return header, rows
    except OSError as e:
        raise MergeError(f"{path}: cannot read: {e.strerror}") from e
    except csv.Error as e:
        raise MergeError(f"{path}: malformed CSV: {e}") from e


def run_identity(row):
    return tuple(row.get(c, "") for c in RUN_COLUMNS + MACHINE_COLUMNS)


def merge_rows(tables):
    """(header, rows, counts) from [(header, rows)] in priority order."""
    header = []
    recordings = OrderedDict()  # run identity -> OrderedDict(timestamp -> [rows])
    for table_header, rows in tables:
        header += [c for c in table_header if c not in header]
        for row in rows:
            recordings.setdefault(run_identity(row), OrderedDict()).setdefault(row["timestamp"], []).append(row)
    merged, counts = [], {"runs": len(recordings), "recordings_left_out": 0, "duplicate_rows": 0}
    for by_time in recordings.values():
        done = [rows for rows in by_time.values() if any(r["status"] in DONE for r in rows)]
        chosen = done[0] if done else list(by_time.values())[-1]
        counts["recordings_left_out"] += len(by_time) - 1
        seen = set()
        for row in chosen:
            values = tuple(row.get(c, "") for c in header)
            if values in seen:
                counts["duplicate_rows"] += 1
                continue
            seen.add(values)
            merged.append(values)
    return header, merged, counts


def write_atomically(path, header, rows):
    directory = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(prefix=".merge-", suffix=".csv", dir=directory)
    try:
        with os.fdopen(handle, "w", newline="") as f:
            writer = csv.writer(f, lineterminator="\n")
            writer.writerow(header)
            writer.writerows(rows)
            f.flush()
            os.fsync(f.fileno())
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise


def merge(out, inputs):
    """Merges `inputs` (and --out's rows, kept first) into `out`; returns the counts."""
    sources = [out] if os.path.exists(out) and os.path.abspath(out) not in map(os.path.abspath, inputs) else []
    tables = [read_table(p) for p in sources + list(inputs)]
    header, rows, counts = merge_rows(tables)
    if not header:
        raise MergeError(f"{', '.join(inputs)}: no CSV header in any input")
    write_atomically(out, header, rows)
    counts["rows"] = len(rows)
    counts["inputs"] = len(tables)
    return counts


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True, help="merged CSV (its rows, if it exists, are kept)")
    parser.add_argument("inputs", nargs="+", help="oitbench CSVs")
    args = parser.parse_args(argv)
    try:
        c = merge(args.out, args.inputs)
    except MergeError as e:
        sys.exit(f"merge: {e}")
    print(f"merge: {c['rows']} rows of {c['runs']} runs from {c['inputs']} file(s) -> {args.out} "
          f"({c['recordings_left_out']} superseded or repeated recording(s) and {c['duplicate_rows']} duplicate "
          f"row(s) left out)")


if __name__ == "__main__":
    main()
