"""oitbench compare: did a change make it faster?

    python3 -m analysis.compare BASE.csv NEW.csv [--ignore-param NAME] [--markdown] [--fail-if-slower PCT]
    python3 -m analysis.compare --builds DIR_A DIR_B [--build-rounds N] -- <bench arguments>

Runs are matched by configuration: technique, its parameters as run, scene,
scene parameters, camera, size, clock and device (--ignore-param NAME leaves
one parameter out of the match, to compare two settings of a knob). Per
configuration and stage it reports NEW/BASE of the medians with a 95%
bootstrap interval (scipy.stats.bootstrap), the p-value of a two-sided
Mann-Whitney U test over the per-frame samples (scipy.stats.mannwhitneyu),
and a verdict: `faster` or `slower` when the test is significant (p < 0.01)
and the whole interval lies beyond the noise threshold (default 5%), `same`
otherwise. Samples come from the CSV's samples_ms column; a CSV without it
(written before it existed) gets the ratio of the medians and no verdict.

--builds runs the same bench arguments with DIR_A/harness/oitbench and
DIR_B/harness/oitbench in alternating rounds (A B, B A, A B, ...), each into
its own CSV in --out, then compares B against A; the ratio is then paired by
round (the median of the per-round ratios, with the binomial interval of the
median).
"""
import argparse
import os
import subprocess
import sys
import tempfile

KEY = ["technique", "params", "scene", "scene_params", "camera", "width", "height", "clock", "device"]
ALPHA = 0.01


def parse_arguments(argv):
    parser = argparse.ArgumentParser(prog="oitbench compare", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="*", help="BASE.csv NEW.csv")
    parser.add_argument("--builds", nargs=2, metavar=("DIR_A", "DIR_B"),
                        help="two build directories: run the bench arguments after -- with each, alternating")
    parser.add_argument("--build-rounds", type=int, default=4, help="--builds: invocations per build (default 4)")
    parser.add_argument("--out", help="--builds: directory for a.csv and b.csv (default: a new temporary one)")
    parser.add_argument("--ignore-param", action="append", default=[], metavar="NAME",
                        help="leave this technique parameter out of the match (repeatable)")
    parser.add_argument("--threshold", type=float, default=5.0,
                        help="noise threshold in percent: a change inside it is `same` (default 5)")
    parser.add_argument("--stage", action="append", default=[],
                        help="only these stages (repeatable; default: every stage)")
    parser.add_argument("--fail-if-slower", type=float, metavar="PCT",
                        help="exit 1 when a configuration's total is `slower` by more than PCT percent")
    parser.add_argument("--markdown", action="store_true", help="print a Markdown table (for a pull request)")
    if "--" in argv:
        split = argv.index("--")
        arguments, bench = parser.parse_args(argv[:split]), argv[split + 1:]
    else:
        arguments, bench = parser.parse_args(argv), []
    if arguments.builds:
        if arguments.csv or not bench:
            parser.error("--builds DIR_A DIR_B takes the bench arguments after --, and no CSV files")
        if arguments.build_rounds < 2:
            parser.error("--build-rounds must be at least 2 (A B, B A)")
    elif len(arguments.csv) != 2:
        parser.error("give BASE.csv and NEW.csv, or --builds DIR_A DIR_B -- <bench arguments>")
    return arguments, bench


def run_key(row, ignored):
    params = " ".join(item for item in row["params"].split() if item.partition("=")[0] not in ignored)
    return tuple(params if column == "params" else row[column] for column in KEY)


def samples_of(row):
    text = row.get("samples_ms") or ""
    try:
        return [float(value) for value in text.split()]
    except ValueError:
        return []


def collect(path, ignored):
    """{(configuration, stage): {"samples": [...], "medians": [...], "rounds": {timestamp: [...]}}} of a CSV's
    ok runs; every recording of a configuration is pooled, and its per-invocation samples kept for pairing."""
    from analysis.results_io import read_rows

    collected = {}
    for row in read_rows(path):
        if row.get("status") != "ok" or not row.get("stage"):
            continue
        entry = collected.setdefault((run_key(row, ignored), row["stage"]),
                                     {"samples": [], "medians": [], "rounds": {}, "noisy": False})
        entry["noisy"] |= row.get("noisy") == "true"
        samples = samples_of(row)
        entry["samples"] += samples
        entry["medians"].append(float(row["median_ms"]))
        entry["rounds"].setdefault(row["timestamp"], []).extend(samples)
    if not collected:
        raise SystemExit(f"oitbench compare: {path} holds no ok run to compare")
    return collected


def bootstrap_ratio(new, base):
    import numpy as np
    from scipy import stats

    def ratio(n, b, axis=-1):
        return np.median(n, axis=axis) / np.median(b, axis=axis)

    result = stats.bootstrap((np.asarray(new), np.asarray(base)), ratio, vectorized=True, paired=False,
                             confidence_level=0.95, n_resamples=2000, method="percentile",
                             random_state=np.random.default_rng(1))
    return result.confidence_interval.low, result.confidence_interval.high


def paired_ratio(new_rounds, base_rounds):
    """The median of per-round ratios (rounds in invocation order) and the binomial interval of that median."""
    import numpy as np
    from scipy import stats

    ratios = sorted(np.median(n) / np.median(b) for n, b in zip(new_rounds, base_rounds) if n and b)
    if not ratios:
        return None
    count = len(ratios)
    lower = 1
    while lower + 1 <= (count + 1) // 2 and 2 * stats.binom.cdf(lower, count, 0.5) <= 0.05:
        lower += 1
    return float(np.median(ratios)), ratios[lower - 1], ratios[count - lower]


def compare_entry(base, new, threshold, paired):
    import numpy as np
    from scipy import stats

    base_median = float(np.median(base["samples"])) if base["samples"] else float(np.median(base["medians"]))
    new_median = float(np.median(new["samples"])) if new["samples"] else float(np.median(new["medians"]))
    row = {"base_ms": base_median, "new_ms": new_median, "ratio": new_median / base_median if base_median else None,
           "low": None, "high": None, "p": None, "verdict": "no samples"}
    if len(base["samples"]) < 2 or len(new["samples"]) < 2 or not base_median:
        return row
    if paired:
        rounds = paired_ratio(list(new["rounds"].values()), list(base["rounds"].values()))
        if rounds:
            row["ratio"], row["low"], row["high"] = rounds
    if row["low"] is None:
        row["low"], row["high"] = bootstrap_ratio(new["samples"], base["samples"])
    row["p"] = float(stats.mannwhitneyu(new["samples"], base["samples"], alternative="two-sided").pvalue)
    limit = threshold / 100.0
    if row["p"] < ALPHA and row["low"] > 1.0 + limit:
        row["verdict"] = "slower"
    elif row["p"] < ALPHA and row["high"] < 1.0 - limit:
        row["verdict"] = "faster"
    else:
        row["verdict"] = "same"
    return row


def label(key):
    technique, params, scene, scene_params, camera, width, height, clock, device = key
    text = " ".join(part for part in [technique, params, "on", scene, scene_params, f"{width}x{height}"] if part)
    return text + ("" if camera == "default" else f" camera {camera}")


def compare(base_path, new_path, arguments, paired=False):
    ignored = set(arguments.ignore_param)
    base, new = collect(base_path, ignored), collect(new_path, ignored)
    rows, unmatched, noisy = [], [], []
    for key in sorted(set(base) | set(new)):
        configuration, stage = key
        if arguments.stage and stage not in arguments.stage:
            continue
        if key not in base or key not in new:
            unmatched.append((label(configuration), stage,
                              "not compared: only in " + (base_path if key in base else new_path)))
            continue
        rows.append((label(configuration), stage, compare_entry(base[key], new[key], arguments.threshold, paired)))
        if stage == "total" and (base[key]["noisy"] or new[key]["noisy"]):
            noisy.append(label(configuration))
    for configuration in noisy:
        unmatched.append((configuration, "total", "a run was flagged noisy (another process loaded the host, or the "
                          "GPU clock moved): a change may be the disturbance's; compare --builds pairs rounds"))
    return rows, unmatched


def number(value, pattern="{:.3g}"):
    return "" if value is None else pattern.format(value)


def print_table(rows, unmatched, markdown, threshold):
    header = ["configuration", "stage", "base ms", "new ms", "new/base [95%]", "p", "verdict"]
    lines = []
    for configuration, stage, r in rows:
        interval = f" [{r['low']:.3f}-{r['high']:.3f}]" if r["low"] is not None else ""
        lines.append([configuration, stage, number(r["base_ms"]), number(r["new_ms"]),
                      number(r["ratio"], "{:.3f}") + interval, number(r["p"], "{:.2g}"), r["verdict"]])
    if markdown:
        print("| " + " | ".join(header) + " |")
        print("|" + "---|" * len(header))
        for line in lines:
            print("| " + " | ".join(cell.replace("|", "\\|") for cell in line) + " |")
    else:
        widths = [max(len(str(line[i])) for line in [header] + lines) for i in range(len(header))]
        for line in [header] + lines:
            print("  ".join(str(cell).ljust(width) for cell, width in zip(line, widths)).rstrip())
    print(f"\n(verdict: faster/slower when p < {ALPHA} (Mann-Whitney U over the frames) and the whole 95% interval "
          f"lies beyond the {threshold:g}% noise threshold; `no samples`: a CSV without samples_ms)")
    for configuration, stage, why in unmatched:
        print(f"note: {configuration} / {stage}: {why}", file=sys.stderr)


def run_builds(arguments, bench):
    binaries = [os.path.join(directory, "harness", "oitbench") for directory in arguments.builds]
    for binary in binaries:
        if not os.access(binary, os.X_OK):
            raise SystemExit(f"oitbench compare: {binary} is not an executable oitbench (build it first)")
    if "--csv" in bench:
        raise SystemExit("oitbench compare --builds: leave --csv out of the bench arguments: each build writes "
                         "its own CSV in --out")
    out = arguments.out or tempfile.mkdtemp(prefix="oitbench-compare-")
    os.makedirs(out, exist_ok=True)
    csvs = [os.path.join(out, "a.csv"), os.path.join(out, "b.csv")]
    for path in csvs:
        if os.path.exists(path):
            raise SystemExit(f"oitbench compare: {path} exists; give an empty --out directory")
    for round_index in range(arguments.build_rounds):
        order = (0, 1) if round_index % 2 == 0 else (1, 0)
        for which in order:
            command = [binaries[which], "bench", *bench, "--csv", csvs[which]]
            print(f"round {round_index + 1}/{arguments.build_rounds}: {'AB'[which]}: {' '.join(command)}",
                  file=sys.stderr)
            finished = subprocess.run(command, stdout=subprocess.DEVNULL)
            if finished.returncode not in (0,):
                raise SystemExit(f"oitbench compare: build {'AB'[which]} exited with {finished.returncode}; "
                                 f"its CSV is {csvs[which]}")
    print(f"CSVs: {csvs[0]} (A) and {csvs[1]} (B)", file=sys.stderr)
    return csvs


def main(argv=None):
    arguments, bench = parse_arguments(sys.argv[1:] if argv is None else argv)
    paired = bool(arguments.builds)
    base_path, new_path = run_builds(arguments, bench) if paired else arguments.csv
    rows, unmatched = compare(base_path, new_path, arguments, paired=paired)
    if not rows:
        raise SystemExit("oitbench compare: no configuration is in both files (see --ignore-param)")
    print_table(rows, unmatched, arguments.markdown, arguments.threshold)
    if arguments.fail_if_slower is not None:
        worse = [c for c, stage, r in rows if stage == "total" and r["verdict"] == "slower"
                 and r["ratio"] > 1.0 + arguments.fail_if_slower / 100.0]
        if worse:
            print(f"oitbench compare: slower by more than {arguments.fail_if_slower:g}%: " + "; ".join(worse),
                  file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
