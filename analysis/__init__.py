"""oitbench analysis: result CSVs (harness/core/results_csv.cpp) into plots.

Every module is both importable (the tests inspect the matplotlib figures its
functions return) and runnable, e.g. `/usr/bin/python3 -m analysis.carnecky_fig14
runs.csv -o fig14.png` from the repository root. `analysis.reproduce` runs the
sweeps each plot needs and draws them all.
"""
