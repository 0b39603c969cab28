"""oitbench analysis: result CSVs (harness/run/results_csv.cpp) into plots.

Every module is both importable (the tests inspect the matplotlib figures its
functions return) and runnable from the repository root as
`/usr/bin/python3 -m analysis.NAME` (e.g. `-m analysis.carnecky_fig14 runs.csv
--out fig14.png`; `--help` lists each one's options). pyproject.toml names the
package and its dependencies. `analysis.reproduce` runs the sweeps each plot
needs and draws them all.

Run as `python3 -m analysis.NAME`, the package is imported before NAME: it
checks first that this Python can import what NAME needs (require_modules),
so an interpreter without Debian's packages stops before any work with a
message saying what to install and which Python to use.
"""
import importlib
import sys

# The Debian package of each library analysis/ may import.
DEBIAN_PACKAGES = {"numpy": "python3-numpy", "pandas": "python3-pandas", "matplotlib": "python3-matplotlib",
                   "scipy": "python3-scipy"}
PLOTTING = ("numpy", "pandas", "matplotlib")
# Entry points that need only the standard library (the workflow's jobs);
# every other one draws, or (reproduce) draws after its sweeps.
STANDARD_LIBRARY_ONLY = {"analysis.merge", "analysis.shards"}


def require_modules(program, modules=PLOTTING):
    """Exits (status 1) naming the `modules` this Python cannot import,
    their Debian packages and the interpreter to use; returns otherwise."""
    missing = []
    for name in modules:
        try:
            importlib.import_module(name)
        except Exception:  # noqa: BLE001 - missing, or built for another Python: either way unusable
            missing.append(name)
    if missing:
        packages = " ".join(DEBIAN_PACKAGES.get(name, name) for name in missing)
        sys.exit(f"{program}: this Python ({sys.executable}) cannot import {', '.join(missing)}: run it with "
                 f"Debian's /usr/bin/python3 (`/usr/bin/python3 -m {program} ...` from the repository root) "
                 f"with {packages} installed (`apt-get install {packages}`)")


def module_run_as_main():
    """NAME when this process runs `python3 -m NAME` and is still locating
    it (sys.argv[0] is "-m" until then), else None."""
    if not sys.argv or sys.argv[0] != "-m":
        return None
    argv = getattr(sys, "orig_argv", [])  # Python 3.10+
    for i, word in enumerate(argv[1:], start=1):
        if word == "-m":
            return argv[i + 1] if i + 1 < len(argv) else None
        if word.startswith("-m"):
            return word[2:]
    return None


# Entry points that need more than the plotting libraries.
NEEDS = {"analysis.compare": ("numpy", "scipy")}

_main = module_run_as_main()
if _main and _main.startswith("analysis.") and _main not in STANDARD_LIBRARY_ONLY:
    require_modules(_main, NEEDS.get(_main, PLOTTING))
