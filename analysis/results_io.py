"""What the analysis reads and writes, held to the harness's rules
(docs/REFERENCE.md, "Reliability"): only whole runs of a results CSV count;
a line that does not hold a whole, plausible row is named on stderr and left
out, and reading goes on after it (as `bench --resume` does); a file is
written whole or not at all.

Kept free of pandas and matplotlib imports so that reproduce.py and merge.py
can use it without them."""
import csv
import gzip
import math
import os
import re
import stat
import sys
import tempfile
from collections import OrderedDict

RUN_COLUMNS = ["technique", "params", "scene", "scene_params", "camera", "width", "height", "scene_rect"]
MACHINE_COLUMNS = ["device", "gl_version", "platform"]
KEY_COLUMNS = ["technique", "status"]  # what every reader of results needs
# What each column of a row can hold (harness/run/results_csv.cpp,
# csv_rows): a row shifted by a stray quote or a lost field fails these.
PLAUSIBLE = {"timestamp": (r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", "a UTC timestamp"),
             "git_revision": (r"[0-9A-Za-z._+-]*", "a git revision"),
             "device": (r".+", "a device name"),
             "technique": (r"[A-Za-z0-9_]+", "a technique id"),
             "status": (r"ok|skipped|error", "ok, skipped or error"),
             "width": (r"[0-9]+", "a width"),
             "height": (r"[0-9]+", "a height"),
             "frames": (r"[0-9]*", "a frame count"),
             "warmup": (r"[0-9]*", "a frame count"),
             "run_rows": (r"[0-9]*", "a row count")}
FREE_TEXT = {"message", "warnings"}  # the columns whose text may hold a line break
PROBLEMS_SHOWN = 20  # per file: a file of garbage is named, not printed


class ResultsError(ValueError):
    """A results CSV that cannot be read, or that leaves nothing to plot; the message names it."""


def stored_path(path):
    """`path`, or `path`.gz where only the compressed file exists: committed
    CSVs over 1 MiB (results/reference/) are stored gzip-compressed."""
    return path if os.path.exists(path) or not os.path.exists(path + ".gz") else path + ".gz"


def require_regular_file(path):
    """Raises ResultsError unless `path` (a link followed) is missing or a
    regular file: reading /dev/zero or a FIFO would never end."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return
    except OSError as e:
        raise ResultsError(f"{path}: cannot read: {e.strerror}") from e
    if not stat.S_ISREG(mode):
        raise ResultsError(f"{path} is not a regular file")


def read_text(path):
    """The text of a results CSV, from `path` or its `.gz` (stored_path),
    without a UTF-8 byte order mark; ResultsError naming the file when it is
    not a readable text file."""
    stored = stored_path(path)
    require_regular_file(stored)
    try:
        with open(stored, "rb") as f:
            data = f.read()
        if stored.endswith(".gz"):
            data = gzip.decompress(data)
    except (OSError, EOFError) as e:
        raise ResultsError(f"{stored}: cannot read: {getattr(e, 'strerror', None) or e}") from e
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise ResultsError(f"{stored}: not a CSV text file (byte {data[e.start]:#04x} at offset {e.start} is not "
                           f"UTF-8)") from e
    if "\0" in text:
        raise ResultsError(f"{stored}: not a CSV text file (it holds NUL bytes)")
    return text


def implausible(header, fields):
    """Why a record with the header's field count cannot be a row the
    harness wrote, or None."""
    if fields == header:
        return "the header again (two files joined?)"
    for column, value in zip(header, fields):
        if column not in FREE_TEXT and ("\n" in value or "\r" in value):
            return f"{column} holds a line break (a quote left open on an earlier line?)"
        pattern, what = PLAUSIBLE.get(column, (None, None))
        if pattern and not re.fullmatch(pattern, value):
            return f"{column} {value[:60]!r} is not {what}"
    return None


def records(lines, header):
    """(line number, fields, why it is no row or None) of each record after
    the header. After a bad record reading starts again at the line after its
    first: a quote left open swallows the lines after it, which are rows."""
    start = 1
    while start < len(lines):
        consumed = start

        def feed():
            nonlocal consumed
            while consumed < len(lines):
                consumed += 1
                yield lines[consumed - 1]

        reader = csv.reader(feed(), strict=True)
        while True:
            begin = consumed
            try:
                fields = next(reader)
            except StopIteration:
                return
            except csv.Error as e:
                fields, why = None, csv_problem(e, begin, consumed)
            else:
                if not fields:
                    continue  # a blank line
                why = record_problem(lines, begin, consumed, header, fields)
            yield begin + 1, fields, why
            if why:
                start = begin + 1
                break


def csv_problem(error, begin, end):
    """What the csv.Error `error` on lines[begin:end] means for a reader."""
    if "unexpected end of data" in str(error):
        return "a quote left open, never closed"
    if end - begin > 1:
        return f"a quote left open (the field runs on into line {end}: {error})"
    return f"malformed ({error})"


def record_problem(lines, begin, end, header, fields):
    """Why lines[begin:end], read as `fields`, is no row (or None)."""
    if not lines[end - 1].endswith(("\n", "\r")):
        return "cut short (no final newline: a crash or a full disk while it was appended)"
    if len(fields) != len(header):
        spans = f" over lines {begin + 1}-{end} (a quote left open?)" if end - begin > 1 else ""
        return f"{len(fields)} fields{spans}, the header has {len(header)}"
    return implausible(header, fields)


def parse(text, source):
    """(header, [(line number, row dict)], problems) of a results CSV's text:
    a problem names a line that is no row, which is left out."""
    lines = re.findall(r"[^\n]*\n|[^\n]+$", text)  # only LF ends a line (CRLF too), as for the csv module
    if not lines:
        return [], [], []
    header = next(csv.reader([lines[0]]), [])
    rows, problems = [], []
    for number, fields, why in records(lines, header):
        row = dict(zip(header, fields)) if fields and len(fields) == len(header) and fields != header else {}
        if why:
            run = f" (run {row['run_id']})" if row.get("run_id") else ""
            problems.append(f"{source}: line {number}{run}: {why}: left out")
        else:
            rows.append((number, row))
    return header, rows, problems


def read_table(path):
    """parse() of the results CSV at `path` (or its .gz); ResultsError for a
    missing or unreadable file."""
    if not os.path.exists(stored_path(path)):
        raise ResultsError(f"{path}: no such file")
    return parse(read_text(path), path)


def run_key(row):
    """Which run a row belongs to: its run_id. A row written before run_id
    existed (both run_id and run_rows empty or absent) belongs to the run of
    its configuration, machine, revision and timestamp: one bench
    invocation wrote those rows together."""
    if row.get("run_id") or row.get("run_rows"):
        return ("run_id", row.get("run_id", ""))
    return ("legacy",) + tuple(row.get(c, "") for c in RUN_COLUMNS + MACHINE_COLUMNS + ["git_revision", "timestamp"])


def run_problem(key, rows):
    """Why the rows of run `key` (run_key) are not a whole run, or None. A
    run with a run_id is whole with all its run_rows rows; one from before
    run ids is taken as it is."""
    if key[0] == "legacy":
        return None
    declared = {row.get("run_rows", "") for row in rows}
    if not key[1]:
        return f"{len(rows)} row(s) with run_rows but no run_id"
    if len(declared) != 1 or not declared.pop().isdigit():
        return f"run {key[1]} has {len(rows)} row(s) without one valid run_rows"
    expected = int(rows[0]["run_rows"])
    if len(rows) != expected:
        return f"run {key[1]} has {len(rows)} row(s) of {expected} (a run cut short is not a result)"
    return None


def whole_runs(numbered_rows, source):
    """(the (line, row) pairs of whole runs, in file order; problems naming
    the runs left out by their first line). A row that repeats an earlier
    row of its run exactly (a file appended to itself) is named and read
    once."""
    runs, first_line, problems = OrderedDict(), {}, []
    for number, row in numbered_rows:
        key = run_key(row)
        values = (key, tuple(row.values()))
        if key[0] == "run_id" and values in first_line:
            problems.append(f"{source}: line {number}: a copy of line {first_line[values]}: left out")
            continue
        first_line[values] = number
        runs.setdefault(key, []).append((number, row))
    kept = []
    for key, members in runs.items():
        why = run_problem(key, [row for _, row in members])
        if why:
            problems.append(f"{source}: line {members[0][0]}: {why}: left out")
        else:
            kept += members
    return sorted(kept, key=lambda pair: pair[0]), problems


def report(problems, limit=PROBLEMS_SHOWN):
    """Each problem on stderr, at most `limit` of them (None: all)."""
    for problem in problems[:limit]:
        print(problem, file=sys.stderr)
    if limit is not None and len(problems) > limit:
        print(f"... and {len(problems) - limit} more line(s) left out", file=sys.stderr)


def whole_rows(path, columns=()):
    """(header, [(line, row dict)] of the whole runs) of a results CSV, the
    lines and runs left out named on stderr. ResultsError when the file is
    empty or lacks KEY_COLUMNS or `columns`."""
    header, rows, problems = read_table(path)
    if not header:
        raise ResultsError(f"{path}: empty (no header): not an oitbench results CSV")
    missing = [c for c in dict.fromkeys(KEY_COLUMNS + list(columns)) if c not in header]
    if missing:
        raise ResultsError(f"{path}: no column {', '.join(repr(c) for c in missing)}: not an oitbench results CSV "
                           f"(or one too old for this)")
    kept, run_problems = whole_runs(rows, path)
    report(problems + run_problems)
    return header, kept


def read_results(path, columns=()):
    """The whole runs of a results CSV (whole_rows) as a pandas frame of
    strings, indexed by their line in the file."""
    import pandas as pd

    header, kept = whole_rows(path, columns)
    frame = pd.DataFrame([[row[c] for c in header] for _, row in kept], columns=header,
                         index=pd.Index([number for number, _ in kept], name="line"), dtype=str)
    return frame


def read_rows(path):
    """The rows (dicts) of a results CSV's whole runs (whole_rows); none for
    a missing or empty file."""
    stored = stored_path(path)
    require_regular_file(stored)
    if not os.path.exists(stored) or os.path.getsize(stored) == 0:
        return []
    return [row for _, row in whole_rows(path)[1]]


def describe_run(row):
    """A run as a reader would name it: technique, params, scene, size, clock, stage."""
    parts = [row.get("technique", ""), row.get("params", ""), "on", row.get("scene", ""), row.get("scene_params", ""),
             f"{row.get('width', '')}x{row.get('height', '')}", row.get("clock", ""), row.get("stage", "")]
    return " ".join(p for p in parts if p)


def usable_times(runs, source, column="median_ms"):
    """The rows of the runs in `runs` (read_results: indexed by line) whose
    every `column` is a positive number; each run left out is named on
    stderr with the value that rules it out. ResultsError when no run is
    left: a plot of nothing is no result."""
    import pandas as pd

    values = pd.to_numeric(runs[column], errors="coerce") if column in runs else pd.Series(math.nan, runs.index)
    usable = ((values > 0) & (values < math.inf)).to_numpy()
    rows = runs.to_dict("records")
    keys = [run_key(row) for row in rows]
    ruled_out = OrderedDict()
    for position in range(len(rows)):
        if not usable[position]:
            ruled_out.setdefault(keys[position], position)
    for position in ruled_out.values():
        value = rows[position].get(column, "(no such column)")
        print(f"{source}: line {runs.index[position]}: {describe_run(rows[position])}: {column} {value!r} is not a "
              "positive number: run left out", file=sys.stderr)
    kept = runs[[key not in ruled_out for key in keys]]
    if kept.empty:
        raise ResultsError(f"{source}: no run with a positive {column} ({len(ruled_out)} left out, see above): "
                           "nothing to plot")
    return kept


def write_whole(path, write, binary=True):
    """write(f) into `path` whole: a temporary file in the same directory,
    synced, then renamed over `path` (a link is followed and kept), with the
    permissions a new file gets. Raises OSError naming `path` when anything
    fails (a special file, a full disk); `path` is then as it was."""
    target = os.path.realpath(path)
    if os.path.exists(target) and not os.path.isfile(target):
        raise OSError(f"cannot write '{path}': it is not a regular file")
    directory = os.path.dirname(target)
    temporary = None
    try:
        os.makedirs(directory, exist_ok=True)
        fd, temporary = tempfile.mkstemp(prefix=f".{os.path.basename(target)}.", suffix=".tmp", dir=directory)
        with (os.fdopen(fd, "wb") if binary else os.fdopen(fd, "w", newline="")) as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # as a new file gets; mkstemp makes 0600
        os.replace(temporary, target)
    except (OSError, ValueError) as e:
        if temporary and os.path.exists(temporary):
            os.unlink(temporary)
        raise OSError(f"cannot write '{path}': {e}") from e


def save_figure(fig, path, **savefig_arguments):
    """fig.savefig into `path` whole (write_whole), in the format its
    extension names (png by default)."""
    extension = os.path.splitext(os.path.realpath(path))[1].lstrip(".").lower() or "png"
    write_whole(path, lambda f: fig.savefig(f, format=extension, **savefig_arguments))
