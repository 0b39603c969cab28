"""Merge oitbench CSVs (the shards of a sweep, runs from several machines) into one, keeping every recording once.

Usage: /usr/bin/python3 -m analysis.merge --out merged.csv shard1.csv shard2.csv ...

A recording is the rows one bench invocation wrote for one run: one run_id
(results_io.run_key; a CSV written before run ids existed: the rows of one
configuration, machine, git revision and timestamp). Every recording is
kept: the same configuration measured by another invocation (a `bench
--resume` after an error row, another git revision, another machine) is
another recording, side by side with its own device, platform and revision.
A recording found in several inputs (a shard given twice, a shard retried
after a crash) is written once: the first whole copy, in input order with
--out's own rows first (from before run ids: the first with the most
rows); a copy cut short is left out when a whole one exists. A recording
no input holds whole is left out.

Lines that are no row (a quote left open, a field count or value the
harness never writes) are left out as the readers leave them out
(analysis.results_io); everything left out other than exact duplicates is
named on stderr with file, line, run and reason.

The header is the union of the inputs' headers in first-seen order (columns
are matched by name, so CSVs written by builds with more or fewer columns
merge; a missing value is empty). If --out exists its rows are read first
and kept: merging again with more inputs only adds. The output is written
whole (results_io.write_whole) or not at all.
"""
import argparse
import csv
import os
import sys
from collections import OrderedDict

from analysis import results_io
from analysis.results_io import RUN_COLUMNS, MACHINE_COLUMNS

REQUIRED = ["technique", "scene", "status", "timestamp", "device", "platform"]


class MergeError(Exception):
    """An input or output that cannot be merged; the message names the file."""


def read_table(path):
    """(header, [(line, row dict)], problems) of one CSV; an empty file has none."""
    try:
        header, rows, problems = results_io.read_table(path)
    except results_io.ResultsError as e:
        raise MergeError(str(e)) from e
    missing = [c for c in REQUIRED if header and c not in header]
    if missing:
        raise MergeError(f"{path}: not an oitbench CSV, no column(s) {', '.join(missing)}")
    return header, rows, problems


def recording_key(row):
    """One bench invocation's rows of one run: its run key, configuration,
    machine, revision and timestamp (a run_id is unique, the rest guards
    against two invocations that drew the same one)."""
    return results_io.run_key(row) + tuple(row.get(c, "") for c in RUN_COLUMNS + MACHINE_COLUMNS +
                                           ["git_revision", "timestamp"])


class Copy:
    """The rows of one recording in one input, exact duplicates once."""

    def __init__(self, source):
        self.source, self.lines, self.rows, self.seen, self.duplicates = source, [], [], set(), 0

    def add(self, number, row):
        values = tuple(sorted(row.items()))
        if values in self.seen:
            self.duplicates += 1
            return
        self.seen.add(values)
        self.lines.append(number)
        self.rows.append(row)

    def problem(self):
        return results_io.run_problem(results_io.run_key(self.rows[0]), self.rows)

    def where(self):
        return f"{self.source}: line{'s' if len(self.lines) > 1 else ''} {', '.join(map(str, self.lines))}"


def choose(copies):
    """(the copy to keep or None, [(copy, why left out)], exact duplicate rows)."""
    whole = [c for c in copies if c.problem() is None]
    duplicates = sum(c.duplicates for c in copies)
    if not whole:
        return None, [(c, c.problem() + ", and no input holds it whole") for c in copies], duplicates
    chosen = max(whole, key=lambda c: len(c.rows))  # the first of the largest: an old CSV's copy may lack rows
    left_out = []
    for c in copies:
        if c is chosen:
            continue
        if {tuple(sorted(r.items())) for r in c.rows} <= chosen.seen:
            duplicates += len(c.rows)
        else:
            left_out.append((c, f"{c.problem() or 'a copy that differs'}; the whole copy in {chosen.source} "
                                f"is kept"))
    return chosen, left_out, duplicates


def merge_rows(tables):
    """(header, rows as value tuples, counts, notes) from [(source, header,
    numbered rows)] in priority order."""
    header, recordings = [], OrderedDict()  # recording key -> OrderedDict(source index -> Copy)
    for index, (source, table_header, rows) in enumerate(tables):
        header += [c for c in table_header if c not in header]
        for number, row in rows:
            copies = recordings.setdefault(recording_key(row), OrderedDict())
            copies.setdefault(index, Copy(source)).add(number, row)
    merged, notes = [], []
    counts = {"recordings": len(recordings), "recordings_left_out": 0, "duplicate_rows": 0}
    for copies in recordings.values():
        chosen, left_out, duplicates = choose(list(copies.values()))
        counts["duplicate_rows"] += duplicates
        counts["recordings_left_out"] += chosen is None
        for copy, why in left_out:
            run = f"run {copy.rows[0].get('run_id') or results_io.describe_run(copy.rows[0])}"
            notes.append(f"{copy.where()}: {why if why.startswith(run) else f'{run}: {why}'}: left out")
        if chosen:
            merged += [tuple(row.get(c, "") for c in header) for row in chosen.rows]
    return header, merged, counts, notes


def output_target(out, inputs):
    """--out's rows come first unless it is an input too; refuses a special file."""
    try:
        results_io.require_regular_file(out)
    except results_io.ResultsError as e:
        raise MergeError(f"--out {e}") from e
    exists = os.path.exists(out)
    return [out] if exists and os.path.realpath(out) not in map(os.path.realpath, inputs) else []


def merge(out, inputs):
    """Merges `inputs` (and --out's rows, kept first) into `out`; returns
    the counts and the notes naming what was left out."""
    sources = output_target(out, inputs) + list(inputs)
    tables, notes = [], []
    for path in sources:
        header, rows, problems = read_table(path)
        tables.append((path, header, rows))
        notes += problems
    header, rows, counts, left_out = merge_rows(tables)
    if not header:
        raise MergeError(f"{', '.join(inputs)}: no CSV header in any input")

    def write(f):
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(header)
        writer.writerows(rows)

    try:
        results_io.write_whole(out, write, binary=False)
    except OSError as e:
        raise MergeError(str(e)) from e
    counts.update(rows=len(rows), inputs=len(tables), lines_left_out=len(notes))
    return counts, notes + left_out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True, help="merged CSV (its rows, if it exists, are kept)")
    parser.add_argument("inputs", nargs="+", help="oitbench CSVs")
    args = parser.parse_args(argv)
    try:
        c, notes = merge(args.out, args.inputs)
    except MergeError as e:
        sys.exit(f"merge: {e}")
    results_io.report(notes, limit=None)
    print(f"merge: {c['rows']} rows of {c['recordings']} recordings from {c['inputs']} file(s) -> {args.out} "
          f"({c['lines_left_out']} line(s) that are no row, {c['recordings_left_out']} recording(s) held whole by "
          f"no input and {c['duplicate_rows']} duplicate row(s) left out)")


if __name__ == "__main__":
    main()
