#!/usr/bin/python3
"""Every command README.md and docs/REFERENCE.md show runs as written.

The commands are read from the documents themselves: each line of a fenced
code block and each code span whose first word is a command (`oitbench`, a
path ending in /oitbench, `oitbench_gbench`, `bash`, `python3`, `snakemake`,
`ctest`, `xvfb-run`). Each one is either
  - RUN here, as written, with the built binary in place of the path, in one
    temporary directory in document order (REFERENCE's export and
    analysis.plot_stages read the CSV that README's example bench wrote;
    placeholders mapped in PLACEHOLDERS, COMMAND run for each command of
    the README's command table), and its outcome asserted: exit status, the
    files it promises and what it prints; or
  - listed in NOT_RUN with the reason and the tests that run it instead
    (which must exist); or
  - a synopsis of docs/REFERENCE.md's command list, whose every option the
    command's --help must name.
A command in neither list fails the test, and so does a listed command the
documents no longer show. argv[1]: the oitbench binary (oitbench_gbench is
taken from beside it)."""
import csv
import glob
import math
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
OITBENCH = os.path.abspath(sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(REPO, "build", "harness", "oitbench"))
sys.path.insert(0, HERE)
# The README's analysis commands as that test finds them (imported after the
# argument is taken: it takes argv[1] too).
import analysis_readme_test  # noqa: E402
GBENCH = os.path.join(os.path.dirname(OITBENCH), "oitbench_gbench")
DOCS = ("README.md", "docs/REFERENCE.md")
COMMAND_WORDS = {"oitbench", "oitbench_gbench", "bash", "python3", "/usr/bin/python3", "snakemake", "ctest", "xvfb-run"}

# The README's "Adding a technique" names a technique that does not exist:
# its commands run on the one-pass example it points to.
PLACEHOLDERS = {"my_oit": "unsorted"}

# command as the document writes it (whitespace joined, comment dropped) ->
# the check of its outcome (a method of RunCommandsTest).
RUN = {
    "oitbench bench -t unsorted -t weighted_blended -t linked_list -t linearized_fragment_buffer -t kbuffer -s quads "
    "--csv runs.csv": "check_example_bench",
    "build/harness/oitbench list --markdown": "check_list_markdown",
    "oitbench list --markdown": "check_list_markdown",
    "oitbench bench --technique my_oit --csv my_oit.csv": "check_my_oit_bench",
    "oitbench list": "check_list",
    "oitbench --help": "check_help",
    "oitbench COMMAND --help": "check_command_help",
    "oitbench stats": "check_stats",
    "python3 -m analysis.plot_stages runs.csv --out stages.png": "check_plot_stages",
    "oitbench export --wide runs.csv -o wide.csv": "check_export",
    "oitbench check-order": "check_check_order",
}

CI = "CI: .ci/run"
ANALYSIS = ("Analysis.ReadmeExamples",)
RUN_BY_ANALYSIS = "run on fixture CSVs by the analysis test, which reads it from the README too"
# command -> (why it is not run here, what runs it instead).
NOT_RUN = {
    "bash setup.sh bench": ("installs Debian packages (apt-get) and builds the tree, as CI does; its bench, "
                            "`oitbench bench --technique all --scene quads ...`, is the README's example bench "
                            "(run here) over every technique", (CI,)),
    "bash setup.sh test": ("installs, builds and runs this suite: it is what CI runs", (CI,)),
    "bash setup.sh build": ("installs Debian packages and builds: the first step of CI", (CI,)),
    "oitbench export --wide": ("the command's name (no input file); run in full as REFERENCE's "
                               "`oitbench export --wide runs.csv -o wide.csv`",
                               ("Cli.ExportWideHasAColumnPerParameterFigureAndStage",)),
    "oitbench pareto": ("the command's name in a sentence (as written, without its required --csv, it is "
                        "CLI11's usage error)",
                        ("Cli.ParetoSweepsTheDeclaredKnobsUnlessTheUserSetsThem",)),
    "build/harness/oitbench list --markdown --params my_oit":
        ("prints a technique README's parameter table; my_oit stands for a new technique: the tests run the "
         "command and hold every technique README to its output",
         ("TechniqueReadmes.CommandPrintsTheTableAndRefusesAnUnknownTechnique",
          "EveryTechnique/TechniqueReadme.HoldsTheGeneratedParameterTable/*")),
    "ctest -R MyOit": ("the test of the README's hypothetical my_oit technique, which does not exist", ()),
    "oitbench adaptive": ("as written over 10 minutes on llvmpipe (every switch of every technique on 4 scenes, "
                          "2 repeats)", ("AdaptiveCommand.EarlyExitAndSceneRectOnAndOffInTheTableAndTheCsv",)),
    "oitbench view": ("opens an interactive window", ("Viewer.UnderXvfb",)),
    "oitbench_gbench": ("the binary's name: as written it times every technique through Google Benchmark",
                        ("Cli.GoogleBenchmarkBinaryReportsManualTimeAndCounters",
                         "Cli.GoogleBenchmarkBinaryTakesBenchSweepOptionsAndItsOwnIterationFlags")),
    "python3 -m analysis.NAME --help": ("NAME stands for each analysis module", ANALYSIS),
    "/usr/bin/python3 -m analysis.reproduce --quick --out results/$(date +%F)":
        ("tens of minutes of sweeps on 2 cores", ("Analysis.Reproduce",)),
    "/usr/bin/python3 -m analysis.reproduce --full --out results/$(date +%F)":
        ("the papers' resolutions: hours, a GPU", ("Analysis.Reproduce",)),
    "/usr/bin/python3 -m analysis.plot_stages runs.csv --out stages.png": (RUN_BY_ANALYSIS, ANALYSIS),
    "/usr/bin/python3 -m analysis.pareto pareto.csv --out-dir plots": (RUN_BY_ANALYSIS, ANALYSIS),
    "/usr/bin/python3 -m analysis.approximate_oit table pareto.csv --out pareto.md": (RUN_BY_ANALYSIS, ANALYSIS),
    "/usr/bin/python3 -m analysis.merge --out all.csv a.csv b.csv": (RUN_BY_ANALYSIS, ANALYSIS),
    "snakemake -j 2": ("the default config's quick reproduce sweeps: tens of minutes; the test runs it on a small "
                       "sweep file", ("Workflow.Slurm",)),
    "snakemake --profile workflow/profiles/slurm --config reproduce=full out=results/full":
        ("needs a SLURM cluster and the full sweeps", ("Workflow.Slurm",)),
    "bash tests/fuzz/run_fuzzers.sh build/fuzz 600": ("600 s per fuzzer", ("Fuzz.Loaders",)),
    "oitbench": ("the program's name", ()),
    "build/harness/oitbench doctor": ("about a minute on llvmpipe; the doctor's test runs it as written",
                                      ("Doctor.PassesHereWithTheProfileTheFloorAndAVerdictPerExactTechnique",)),
    "oitbench doctor": ("the command's name in a sentence; run as README's `build/harness/oitbench doctor`",
                        ("Doctor.PassesHereWithTheProfileTheFloorAndAVerdictPerExactTechnique",)),
    "bash tools/gpu_survey.sh": ("the full survey at GPU sizes: minutes on a GPU; its test runs the --quick form",
                                 ("GpuSurvey.Quick",)),
    "oitbench stress": ("the reduced set, 317 cases each in its own process: about 90 s on llvmpipe",
                        ("EveryTechnique/Stress.ReducedSetPasses/*",)),
    "oitbench stress --full": ("every case: a superset of the reduced set's 90 s",
                               ("EveryTechnique/Stress.ReducedSetPasses/*",
                                "StressCases.ReducedIsASubsetOfFullAndCoversEveryKind")),
    "python3 -m analysis.pareto FILE --out-dir DIR": ("FILE and DIR stand for a pareto CSV and a folder; README's "
                                                      "`analysis.pareto pareto.csv --out-dir plots` is that", ANALYSIS),
    "oitbench bench ...": ("stands for the viewer's sweep-file line",
                           ("ViewerSweepLine.AppendedLineRunsAsABenchCommand",)),
    "oitbench export --wide FILE -o OUT": ("FILE and OUT stand for `runs.csv` and `wide.csv` of the command run above",
                                           ("Cli.ExportWideHasAColumnPerParameterFigureAndStage",)),
    "oitbench bench -t depth_peeling --set early_exit=true -s quads --scene-set layers=4 --size 128x128 --csv base.csv":
        ("the README's worked A/B, run with the same settings by the compare test", ("Analysis.Compare",)),
    "oitbench bench -t depth_peeling --set early_exit=false -s quads --scene-set layers=4 --size 128x128 --csv new.csv":
        ("the README's worked A/B, run with the same settings by the compare test", ("Analysis.Compare",)),
    "oitbench compare base.csv new.csv --ignore-param early_exit --stage peel --stage total":
        ("the README's worked A/B, whose verdict the compare test asserts", ("Analysis.Compare",)),
    "oitbench compare BASE.csv NEW.csv": ("BASE and NEW stand for two results CSVs", ("Analysis.Compare",)),
    "oitbench compare --builds DIR_A DIR_B -- <bench arguments>":
        ("DIR_A and DIR_B stand for two build directories", ("Analysis.Compare",)),
    "oitbench compare --builds build-old build -- <bench arguments>":
        ("build-old stands for a second build directory", ("Analysis.Compare",)),
    "xvfb-run -a oitbench view ... --frames 3 --screenshot out.png": ("needs an X server; `...` stands for the view",
                                                                      ("Viewer.UnderXvfb",)),
}


def read(doc):
    with open(os.path.join(REPO, doc)) as f:
        return f.read()


def normalised(text):
    """One line, single spaces, a trailing shell comment dropped."""
    return " ".join(re.sub(r"(^|\s)#.*$", "", text, flags=re.M).split())


def is_command(text):
    words = text.split()
    return bool(words) and (words[0] in COMMAND_WORDS or words[0].endswith("/oitbench"))


def fenced_blocks(text):
    return re.findall(r"^```[^\n]*\n(.*?)^```", text, re.S | re.M)


def synopsis_block():
    """docs/REFERENCE.md's list of commands: the first fenced block under
    "## Command line"."""
    text = read("docs/REFERENCE.md")
    return fenced_blocks(text[text.index("\n## Command line\n"):])[0]


def synopses():
    """Each unindented line of the synopsis block with its continuation
    lines (indented, starting with an option or `[`)."""
    entries = []
    for line in synopsis_block().splitlines():
        if line.startswith("oitbench"):
            entries.append(line)
        elif entries and re.match(r"^\s+[\[-]", line) and not entries[-1].endswith("\n"):
            entries[-1] += " " + line.strip()
        elif entries:
            entries[-1] += "\n"  # its description: nothing after this continues the synopsis
    return [entry.strip() for entry in entries]


def doc_commands(doc):
    """The commands of `doc`, in order, each once: fenced block lines and code
    spans (anywhere, also inside blocks; a span may wrap lines)."""
    text = read(doc)
    synopsis_lines = set(synopsis_block().splitlines()) if doc == "docs/REFERENCE.md" else set()
    found = [normalised(line) for block in fenced_blocks(text) for line in block.splitlines()
             if is_command(line) and line not in synopsis_lines]
    found += [normalised(span) for span in re.findall(r"(?<!`)`([^`]+)`(?!`)", text) if is_command(span)]
    return list(dict.fromkeys(command for command in found if command))


def readme_technique_table():
    text = read("README.md")
    begin, end = "<!-- technique table: oitbench list --markdown -->\n", "<!-- end of technique table -->"
    return text[text.index(begin) + len(begin):text.index(end)]


def readme_techniques():
    """id -> (kind, parameter names) from the README's technique table."""
    techniques = {}
    for row in readme_technique_table().splitlines()[2:]:
        cells = [cell.strip() for cell in row.strip("|").split(" | ")]
        techniques[cells[0].strip("`")] = (cells[3], re.findall(r"`(\w+)` \(", cells[4]))
    return techniques


def readme_command_table():
    """The first word of each row of the README's command table."""
    text = read("README.md")
    table = text[text.index("| command | what it does |"):]
    table = table[:table.index("\n\n")]
    return [re.match(r"\| `([\w-]+)", row).group(1) for row in table.splitlines()[2:]]


def subcommands(help_text):
    return re.findall(r"^  ([\w-]+)  ", help_text.split("Subcommands:")[1], re.M)


def ctest_name_exists(name):
    """A CTest name: an add_test NAME or a GoogleTest TEST/TEST_F/TEST_P
    (parameterised ones as Prefix/Suite.Name/*)."""
    if name == CI:
        with open(os.path.join(REPO, ".ci", "run")) as f:
            return "bash setup.sh test" in f.read()
    with open(os.path.join(HERE, "CMakeLists.txt")) as f:
        if re.search(rf"add_test\(NAME {re.escape(name)} ", f.read()):
            return True
    suite, test = re.sub(r"^\w+/|/\*$", "", name).split(".")
    for source in glob.glob(os.path.join(HERE, "*.cpp")):
        with open(source) as f:
            if re.search(rf"^TEST(_F|_P)?\({suite}, {test}\)", f.read(), re.M):
                return True
    return False


def run(command, cwd):
    """`command` as written: the documented path of oitbench replaced by the
    built one, placeholders by their stand-ins; python3 is this test's
    (Debian's), the analysis package found as from the repository root."""
    words = [PLACEHOLDERS.get(word, word) for word in shlex.split(command)]
    words[0] = sys.executable if words[0] == "python3" else OITBENCH
    start = time.monotonic()
    result = subprocess.run(words, cwd=cwd, capture_output=True, text=True, timeout=300,
                            env=dict(os.environ, PYTHONPATH=REPO))
    result.seconds = time.monotonic() - start
    return result


def csv_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def summary_rows(text):
    """technique -> (status, max error, dropped, the lines below it) of a
    bench summary table. A row is the technique, its parameters where any
    differ from the defaults (as run: resolved `auto`s show), the status,
    the median±half-width, the ratio and its [interval], the max error, the
    dropped fragments and the noisy column ("yes" or empty: whether a run was
    noisy depends on the machine's load, not on what the README shows). Of
    the lines below a row only `params:` and `work saved:` are kept: warnings
    and precision notes depend on the machine too."""
    rows, last = {}, None
    for line in text.splitlines():
        words = line.split()
        status_at = next((i for i in (1, 2) if len(words) > i and words[i] in ("ok", "error", "skipped")), None)
        if status_at and words[status_at] == "ok" and len(words) in (status_at + 6, status_at + 7):
            last = words[0]
            rows[last] = (words[status_at], words[status_at + 4], words[status_at + 5], [])
        elif last and line.startswith("    "):
            if line.strip().startswith(("params:", "work saved:")):
                rows[last][3].append(line.strip())
        else:
            last = None
    return rows


class DocumentCommandsTest(unittest.TestCase):
    """Every command is run or listed; the lists hold nothing stale."""

    def test_every_command_is_run_or_listed_and_every_listed_one_is_shown(self):
        shown = [command for doc in DOCS for command in doc_commands(doc)]
        unaccounted = [command for command in shown if command not in RUN and command not in NOT_RUN]
        self.assertEqual(unaccounted, [], "commands in the documents neither run nor listed in NOT_RUN")
        stale = [command for command in list(RUN) + list(NOT_RUN) if command not in shown]
        self.assertEqual(stale, [], "listed commands the documents no longer show")

    def test_documented_paths_of_oitbench_are_where_the_build_puts_it(self):
        """`build/...oitbench` in the documents: the path of the built binary
        inside its build folder (the one holding CMakeCache.txt), whatever
        that folder's name."""
        build = os.path.dirname(OITBENCH)
        while not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            self.assertNotEqual(build, os.path.dirname(build), f"{OITBENCH} is in no CMake build folder")
            build = os.path.dirname(build)
        paths = {command.split()[0] for doc in DOCS for command in doc_commands(doc) if "/" in command.split()[0]}
        paths = {path for path in paths if path.endswith("oitbench")}
        self.assertTrue(paths)
        for path in paths:
            self.assertEqual(path, "build/" + os.path.relpath(OITBENCH, build))

    def test_what_runs_a_listed_command_instead_exists(self):
        for command, (reason, tests) in NOT_RUN.items():
            self.assertTrue(reason, command)
            for name in tests:
                self.assertTrue(ctest_name_exists(name), f"`{command}`: no test {name}")

    def test_analysis_commands_are_the_ones_analysis_readme_test_runs(self):
        other = analysis_readme_test
        runs = {f"analysis.{module} " + " ".join(arguments) for module, arguments in other.readme_commands()
                if module not in other.NOT_RUN}
        for command, (reason, _) in NOT_RUN.items():
            if reason == RUN_BY_ANALYSIS:
                self.assertIn(command.split(" -m ", 1)[1], runs)

    def test_synopses_name_only_options_the_commands_have_and_cover_every_command(self):
        top = subprocess.run([OITBENCH, "--help"], capture_output=True, text=True).stdout
        described = set()
        for synopsis in synopses():
            words = synopsis.split()
            if words[0] == "oitbench_gbench":
                binary, command = [GBENCH], None
            else:
                command = words[1] if re.fullmatch(r"[\w-]+", words[1]) else None
                binary = [OITBENCH] + ([command] if command else [])
            described.add(command or words[0])
            result = subprocess.run(binary + ["--help"], capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, synopsis)
            for option in re.findall(r"--[a-z][\w-]*", synopsis):
                if option == "--benchmark_":  # `--benchmark_*`: Google Benchmark's flags, listed under its heading
                    self.assertIn("Google Benchmark's flags:", result.stdout)
                    continue
                self.assertRegex(result.stdout, rf"(?<![\w-]){re.escape(option)}(?![\w-])", f"{synopsis}: {option}")
            if "[bench's options]" in synopsis:
                bench = subprocess.run([OITBENCH, "bench", "--help"], capture_output=True, text=True).stdout
                for option in set(re.findall(r"^\s+(?:-\w,)?(--[\w-]+)", bench, re.M)):
                    self.assertRegex(result.stdout, rf"(?<![\w-]){re.escape(option)}(?![\w-])", f"pareto: {option}")
        self.assertEqual(described, set(subcommands(top)) | {"oitbench", "oitbench_gbench"})


class RunCommandsTest(unittest.TestCase):
    """The RUN commands, run once each in document order in one directory."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = cls.tmp.name
        cls.results = {}
        for doc in DOCS:
            for command in doc_commands(doc):
                if command in RUN and command not in cls.results and "COMMAND" not in command:
                    cls.results[command] = run(command, cls.dir)
                    print(f"{cls.results[command].seconds:6.1f} s  {command}", file=sys.stderr)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_each_command_does_what_the_documents_say(self):
        for command, check in RUN.items():
            with self.subTest(command=command):
                if "COMMAND" not in command:
                    result = self.results[command]
                    self.assertEqual(result.returncode, 0, f"{command}\n{result.stdout}\n{result.stderr}")
                getattr(self, check)(command)

    def path(self, name):
        return os.path.join(self.dir, name)

    def check_example_bench(self, command):
        """The README's "Example output": its header and block lines, and per
        technique the status, dropped fragments, params and work-saved lines
        and max error (to the printed three digits, 1 %) of the shown table;
        the CSV holds each run at 256x256 (size auto on software GL) with 1
        warm-up frame and at least 6 timed frames in 6 rounds or more."""
        out = self.results[command].stdout
        text = read("README.md")
        shown = next(block for block in fenced_blocks(text[text.index("## Example output"):])
                     if block.startswith("technique "))
        header, scene_line = shown.splitlines()[:2]
        self.assertEqual(out.splitlines()[1], header)  # after an empty line, as the README shows it
        self.assertIn(f"\n{scene_line}\n", out)
        expected, actual = summary_rows(shown), summary_rows(out)
        self.assertEqual(set(actual), set(expected))
        for technique, (status, error, dropped, below) in expected.items():
            self.assertEqual(actual[technique][0], status, technique)
            self.assertEqual(actual[technique][2], dropped, technique)
            self.assertEqual(actual[technique][3], below, technique)
            self.assertLessEqual(abs(float(actual[technique][1]) - float(error)), 0.01 * float(error), technique)
        rows = csv_rows(self.path("runs.csv"))
        self.assertEqual({row["technique"] for row in rows}, set(expected))
        totals = [row for row in rows if row["stage"] == "total"]
        self.assertEqual(sorted(row["technique"] for row in totals), sorted(expected))
        for row in totals:
            self.assertEqual((row["status"], row["scene"], row["width"], row["height"], row["warmup"]),
                             ("ok", "quads", "256", "256", "1"), row["technique"])
            self.assertGreaterEqual(int(row["frames"]), 6, row["technique"])
            self.assertGreaterEqual(int(row["rounds"]), 6, row["technique"])

    def check_list_markdown(self, command):
        self.assertIn(readme_technique_table(), self.results[command].stdout)

    def check_my_oit_bench(self, command):
        """Times it (its stages and total), compares it (an error against the
        reference) and writes the CSV."""
        rows = csv_rows(self.path("my_oit.csv"))
        self.assertEqual({row["technique"] for row in rows}, {"unsorted"})
        self.assertEqual([row["stage"] for row in rows], ["total", "fill"])  # unsorted's stages, README's table
        for row in rows:
            self.assertEqual(row["status"], "ok")
            self.assertGreater(float(row["median_ms"]), 0)
            self.assertTrue(0 < float(row["error_max"]) < 1, row["error_max"])  # unsorted is approximate
        self.assertRegex(self.results[command].stdout, r"(?m)^unsorted +ok ")

    def check_list(self, command):
        """Limits, every technique with each parameter's default and meaning,
        every scene of the README's table."""
        out = self.results[command].stdout
        self.assertRegex(out, r"(?m)^Limits: largest buffer \d+ MiB .*; memory budget [\d.]+ GiB")
        techniques = out.split("\nTechniques:\n")[1].split("\nScenes")[0]
        for technique, (_, parameters) in readme_techniques().items():
            section = re.search(rf"(?ms)^  {technique} .*?(?=^  \S|\Z)", techniques)
            self.assertTrue(section, technique)
            for parameter in parameters:
                # A long range wraps onto the next lines before the dash.
                self.assertRegex(section.group(0), rf"(?m)^      {parameter} +default [^—]* —\s+\S", parameter)
        scenes = out.split("\nScenes")[1]
        text = read("README.md")
        for scene in re.findall(r"^\| `(\w+)` \|", text[text.index("## Scenes"):], re.M):
            self.assertRegex(scenes, rf"(?m)^  {scene} ", scene)

    def check_help(self, command):
        commands = set(readme_command_table()) - {"oitbench_gbench"}  # its own binary
        self.assertEqual(set(subcommands(self.results[command].stdout)), commands)

    def check_command_help(self, command):
        """COMMAND: each command of the README's command table."""
        for name in readme_command_table():
            if name == "oitbench_gbench":
                continue
            result = run(command.replace("COMMAND", name), self.dir)
            self.assertEqual(result.returncode, 0, name)
            if name == "compare":  # its options are analysis/compare.py's (argparse)
                self.assertRegex(result.stdout, r"(?m)^usage: oitbench compare \[-h\]", name)
                continue
            self.assertRegex(result.stdout, rf"(?m)^Usage: \S*oitbench {name} \[OPTIONS\]$", name)
            self.assertIn("\nOptions:\n  -h,--help ", result.stdout, name)

    def check_stats(self, command):
        """The default view: 32 full-screen quads at 256x256."""
        out = self.results[command].stdout
        for line in ("fragments         2,097,152", "covered pixels    65,536 of 65,536 (100.0%)",
                     "depth complexity  max 32, mean 32.000 over all pixels, 32.000 over covered pixels",
                     "psi               1.0000 (share of all pixels whose list is longer than 2/3 of 32)"):
            self.assertIn(f"\n{line}\n", out)
        self.assertRegex(out, r"30-32: 65,536 +\(100\.0%\)")

    def check_plot_stages(self, command):
        """The example bench's stages: a PNG and an SVG beside it, naming
        each technique and its stages."""
        self.assertEqual(analysis_readme_test.png_size(self.path("stages.png"))[0] > 0, True)
        _, texts = analysis_readme_test.svg_texts(self.path("stages.svg"))
        texts = {text for _, text in texts}
        for row in csv_rows(self.path("runs.csv")):
            self.assertIn(row["technique"], texts)
            if row["stage"] != "total":
                self.assertIn(row["stage"], texts)

    def check_export(self, command):
        """One row per run of the example bench's runs.csv, a column per
        parameter, scene parameter and stage figure, equal to the long CSV."""
        long = {(row["technique"], row["stage"]): row for row in csv_rows(self.path("runs.csv"))}
        wide = csv_rows(self.path("wide.csv"))
        self.assertEqual(sorted(row["technique"] for row in wide), sorted({t for t, _ in long}))
        for row in wide:
            self.assertEqual(float(row["total.wall.median_ms"]), float(long[(row["technique"], "total")]["median_ms"]))
            self.assertEqual(row["scene.layers"], "32")
            self.assertEqual(row["param.k"], "16" if row["technique"] == "kbuffer" else "")
        self.assertIn(f"{len(wide)} runs, ", self.results[command].stdout + self.results[command].stderr)

    def check_check_order(self, command):
        """Every technique passes; each run its class holds to the reference
        (exact ones, and those exact while storage covers that dropped
        nothing) gives the original image in every order."""
        out = self.results[command].stdout
        techniques = readme_techniques()
        rows = {words[0]: words for words in (line.split() for line in out.splitlines())
                if words and words[0] in techniques}
        self.assertEqual(set(rows), set(techniques))
        for technique, words in rows.items():
            kind = techniques[technique][0]
            held = {"approximate": {"approximate"}, "exact while storage covers": {"exact", "truncated"}}
            self.assertIn(words[1], held.get(kind, {"exact"}), technique)
            self.assertEqual(words[2], "pass", technique)
            if words[1] == "exact":
                self.assertEqual(words[3:6], ["0", "0", "-"], technique)
            self.assertTrue(math.isfinite(float(words[4])), technique)


if __name__ == "__main__":
    unittest.main(verbosity=2)
