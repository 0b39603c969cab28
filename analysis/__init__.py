"""oitbench analysis: result CSVs (harness/core/results_csv.cpp) into plots.

Every module is both importable (the tests inspect the matplotlib figures its
functions return) and runnable from the repository root as
`/usr/bin/python3 -m analysis.NAME` (e.g. `-m analysis.carnecky_fig14 runs.csv
--out fig14.png`; `--help` lists each one's options). pyproject.toml names the
package and its dependencies. `analysis.reproduce` runs the sweeps each plot
needs and draws them all.
"""
