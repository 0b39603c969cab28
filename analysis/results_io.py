"""What the analysis reads and writes, held to the harness's rules
(docs/REFERENCE.md, "Reliability"): only whole runs of a results CSV count, and a plot is
written whole or not at all.

Kept free of pandas and matplotlib imports so that reproduce.py can use it
before it draws anything."""
import csv
import gzip
import io
import os
import sys
import tempfile
from collections import Counter


def whole_text(text, source):
    """`text` up to the end of its last complete record: a last line cut
    short (no final newline, or inside a quoted field) is left out, and
    stderr says so. The harness cuts such an end back itself on its next
    append; a plot drawn before that must not read it."""
    lines = text.splitlines(keepends=True)
    consumed, end = 0, 0

    def feed():
        nonlocal consumed
        for line in lines:
            consumed += 1
            yield line

    try:
        for _ in csv.reader(feed(), strict=True):
            if lines[consumed - 1].endswith(("\n", "\r")):
                end = consumed
    except csv.Error:
        pass
    if end < len(lines):
        print(f"{source}: line {end + 1} is cut short (a crash or a full disk while it was appended): left out",
              file=sys.stderr)
    return "".join(lines[:end])


def read_results(path, **read_csv_arguments):
    """pandas.read_csv of a results CSV's whole runs only (whole_text, then
    whole_runs)."""
    import pandas as pd

    text = whole_text(read_text(path), path)
    return whole_runs(pd.read_csv(io.StringIO(text), **read_csv_arguments), path)


def stored_path(path):
    """`path`, or `path`.gz where only the compressed file exists: committed
    CSVs over 1 MiB (results/reference/) are stored gzip-compressed."""
    return path if os.path.exists(path) or not os.path.exists(path + ".gz") else path + ".gz"


def read_text(path):
    """The text of a results CSV, from `path` or its `.gz` (stored_path)."""
    stored = stored_path(path)
    with (gzip.open(stored, "rt", newline="") if stored.endswith(".gz") else open(stored, newline="")) as f:
        return f.read()


def read_rows(path):
    """csv.DictReader rows of a results CSV's whole runs (or of its .gz);
    none for a missing or empty file."""
    stored = stored_path(path)
    if not os.path.exists(stored) or os.path.getsize(stored) == 0:
        return []
    return whole_run_rows(list(csv.DictReader(io.StringIO(whole_text(read_text(path), path)))))


def whole_run_rows(rows):
    """csv.DictReader rows of the runs the file holds whole: all `run_rows`
    rows of their `run_id`. A run cut short (a crash or a full disk while the
    harness appended it) is not there; it runs again."""
    counts = Counter(r.get("run_id") or "" for r in rows)
    return [r for r in rows if r.get("run_id") and r.get("run_rows") == str(counts[r["run_id"]])]


def whole_runs(runs, source):
    """The rows of a pandas frame that belong to whole runs (as whole_run_rows),
    saying on stderr how many rows were left out. A frame without run_id
    (a hand-made CSV) is taken as it is."""
    if "run_id" not in runs or runs.empty:
        return runs
    ids = runs["run_id"].astype(str)
    counts = ids.map(ids.value_counts())
    whole = (ids != "") & (counts.astype(str) == runs["run_rows"].astype(str))
    if not whole.all():
        print(f"{source}: {int((~whole).sum())} row(s) of incomplete runs left out (a run cut short is not a "
              f"result)", file=sys.stderr)
    return runs[whole]


def save_figure(fig, path, **savefig_arguments):
    """fig.savefig into `path` whole: a temporary file in the same directory,
    synced, then renamed over `path` (a link is followed and kept). Raises
    OSError naming `path` when anything fails; `path` is then as it was."""
    target = os.path.realpath(path)
    if os.path.exists(target) and not os.path.isfile(target):
        raise OSError(f"cannot write '{path}': it is not a regular file")
    directory = os.path.dirname(target)
    os.makedirs(directory, exist_ok=True)
    extension = os.path.splitext(target)[1].lstrip(".").lower() or "png"
    fd, temporary = tempfile.mkstemp(prefix=f".{os.path.basename(target)}.", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "wb") as f:
            fig.savefig(f, format=extension, **savefig_arguments)
            f.flush()
            os.fsync(f.fileno())
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # as a new file gets; mkstemp makes 0600
        os.replace(temporary, target)
    except (OSError, ValueError) as e:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise OSError(f"cannot write '{path}': {e}") from e
