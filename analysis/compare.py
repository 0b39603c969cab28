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
DIR_B/harness/oitbench in alternating rounds (A B, B A, A B, ...), each
invocation into its own CSV (--out/a/round_01.csv, --out/b/round_01.csv,
...), then compares B against A paired by round: the ratio is the median of
the per-round ratios of the medians, with the binomial interval of that
median, and p comes from the exact Wilcoxon signed-rank test of the per-round
log ratios (scipy.stats.wilcoxon). Frames of one round share the host's load
and the GPU's clock, so they are not independent samples of a build; rounds
are. At least 8 rounds are needed for p < 0.01 to be reachable at all.
"""
import argparse
import os
import subprocess
import sys
import tempfile

KEY = ["technique", "params", "scene", "scene_params", "camera", "width", "height", "clock", "device"]
ALPHA = 0.01
MIN_PAIRED_ROUNDS = 8  # the exact signed-rank test's smallest two-sided p with n rounds is 2 / 2^n


def parse_arguments(argv):
    parser = argparse.ArgumentParser(prog="oitbench compare", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="*", help="BASE.csv NEW.csv")
    parser.add_argument("--builds", nargs=2, metavar=("DIR_A", "DIR_B"),
                        help="two build directories: run the bench arguments after -- with each, alternating")
    parser.add_argument("--build-rounds", type=int, default=10,
                        help=f"--builds: invocations per build (default 10, at least {MIN_PAIRED_ROUNDS})")
    parser.add_argument("--out", help="--builds: an empty directory for a/round_NN.csv and b/round_NN.csv "
                        "(default: a new temporary one)")
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
        if arguments.build_rounds < MIN_PAIRED_ROUNDS:
            parser.error(f"--build-rounds {arguments.build_rounds}: give at least {MIN_PAIRED_ROUNDS}; with fewer "
                         f"rounds the paired test can never reach p < {ALPHA}")
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


def collect(paths, ignored):
    """{(configuration, stage): {"samples": [...], "medians": [...], "rounds": [[...], ...]}} of the ok runs in
    PATHS; every recording of a configuration is pooled, and each file's samples are kept as one round."""
    from analysis.results_io import read_rows

    collected = {}
    for index, path in enumerate(paths):
        for row in read_rows(path):
            if row.get("status") != "ok" or not row.get("stage"):
                continue
            entry = collected.setdefault((run_key(row, ignored), row["stage"]),
                                         {"samples": [], "medians": [], "rounds": {}, "noisy": False})
            entry["noisy"] |= row.get("noisy") == "true"
            samples = samples_of(row)
            entry["samples"] += samples
            entry["medians"].append(float(row["median_ms"]))
            entry["rounds"].setdefault(index, []).extend(samples)
    if not collected:
        raise SystemExit(f"oitbench compare: {', '.join(paths)} holds no ok run to compare")
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


def round_ratios(new, base):
    """NEW/BASE of the medians, round by round, over the rounds both hold."""
    import numpy as np

    return [float(np.median(new["rounds"][index]) / np.median(base["rounds"][index]))
            for index in sorted(set(new["rounds"]) & set(base["rounds"]))
            if new["rounds"][index] and base["rounds"][index] and np.median(base["rounds"][index]) > 0]


def median_interval(values):
    """The median of VALUES and its distribution-free 95% interval (binomial order statistics)."""
    import numpy as np
    from scipy import stats

    ordered, count = sorted(values), len(values)
    lower = 1
    while lower + 1 <= (count + 1) // 2 and 2 * stats.binom.cdf(lower, count, 0.5) <= 0.05:
        lower += 1
    return float(np.median(ordered)), ordered[lower - 1], ordered[count - lower]


def verdict(p, low, high, threshold):
    limit = threshold / 100.0
    if p < ALPHA and low > 1.0 + limit:
        return "slower"
    if p < ALPHA and high < 1.0 - limit:
        return "faster"
    return "same"


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
        ratios = round_ratios(new, base)
        if len(ratios) < MIN_PAIRED_ROUNDS:
            row["verdict"] = f"{len(ratios)} rounds"
            return row
        row["ratio"], row["low"], row["high"] = median_interval(ratios)
        logs = np.log(ratios)
        row["p"] = 1.0 if not np.any(logs) else float(stats.wilcoxon(logs, alternative="two-sided").pvalue)
    else:
        row["low"], row["high"] = bootstrap_ratio(new["samples"], base["samples"])
        row["p"] = float(stats.mannwhitneyu(new["samples"], base["samples"], alternative="two-sided").pvalue)
    row["verdict"] = verdict(row["p"], row["low"], row["high"], threshold)
    return row


def label(key):
    technique, params, scene, scene_params, camera, width, height, clock, device = key
    text = " ".join(part for part in [technique, params, "on", scene, scene_params, f"{width}x{height}"] if part)
    return text + ("" if camera == "default" else f" camera {camera}")


def compare(base_paths, new_paths, arguments, paired=False):
    ignored = set(arguments.ignore_param)
    base, new = collect(base_paths, ignored), collect(new_paths, ignored)
    rows, unmatched, noisy = [], [], []
    for key in sorted(set(base) | set(new)):
        configuration, stage = key
        if arguments.stage and stage not in arguments.stage:
            continue
        if key not in base or key not in new:
            unmatched.append((label(configuration), stage, "not compared: only in " +
                              ("the base" if key in base else "the new") + " results"))
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


def print_table(rows, unmatched, markdown, threshold, paired):
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
    test = ("Wilcoxon signed-rank over the rounds' ratios; new/base is the median of the rounds' ratios, base ms "
            "and new ms the medians of every frame, so their quotient may differ") if paired \
        else "Mann-Whitney U over the frames"
    print(f"\n(verdict: faster/slower when p < {ALPHA} ({test}) and the whole 95% interval lies beyond the "
          f"{threshold:g}% noise threshold; `no samples`: a CSV without samples_ms; `N rounds`: fewer than "
          f"{MIN_PAIRED_ROUNDS} rounds held the configuration in both builds)")
    for configuration, stage, why in unmatched:
        print(f"note: {configuration} / {stage}: {why}", file=sys.stderr)


def run_builds(arguments, bench):
    """Runs the bench with build A and build B in alternating rounds; returns the per-round CSVs of each."""
    binaries = [os.path.join(directory, "harness", "oitbench") for directory in arguments.builds]
    for binary in binaries:
        if not os.access(binary, os.X_OK):
            raise SystemExit(f"oitbench compare: {binary} is not an executable oitbench (build it first)")
    if "--csv" in bench:
        raise SystemExit("oitbench compare --builds: leave --csv out of the bench arguments: each round of each "
                         "build writes its own CSV in --out")
    out = arguments.out or tempfile.mkdtemp(prefix="oitbench-compare-")
    directories = [os.path.join(out, "a"), os.path.join(out, "b")]
    for directory in directories:
        if os.path.exists(directory):
            raise SystemExit(f"oitbench compare: {directory} exists; give an --out directory without a/ and b/")
        os.makedirs(directory)
    csvs = [[os.path.join(directory, f"round_{index + 1:02d}.csv") for index in range(arguments.build_rounds)]
            for directory in directories]
    for round_index in range(arguments.build_rounds):
        order = (0, 1) if round_index % 2 == 0 else (1, 0)
        for which in order:
            command = [binaries[which], "bench", *bench, "--csv", csvs[which][round_index]]
            print(f"round {round_index + 1}/{arguments.build_rounds}: {'AB'[which]}: {' '.join(command)}",
                  file=sys.stderr)
            finished = subprocess.run(command, stdout=subprocess.DEVNULL)
            if finished.returncode != 0:
                raise SystemExit(f"oitbench compare: build {'AB'[which]} exited with {finished.returncode} in round "
                                 f"{round_index + 1}; its CSV is {csvs[which][round_index]}")
    print(f"CSVs: {directories[0]}/ (A) and {directories[1]}/ (B), a file per round", file=sys.stderr)
    return csvs


def main(argv=None):
    arguments, bench = parse_arguments(sys.argv[1:] if argv is None else argv)
    paired = bool(arguments.builds)
    base_paths, new_paths = run_builds(arguments, bench) if paired else ([arguments.csv[0]], [arguments.csv[1]])
    rows, unmatched = compare(base_paths, new_paths, arguments, paired=paired)
    if not rows:
        raise SystemExit("oitbench compare: no configuration is in both files (see --ignore-param)")
    print_table(rows, unmatched, arguments.markdown, arguments.threshold, paired)
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
