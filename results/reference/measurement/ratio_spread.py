"""The spread of `x unsorted` over three invocations of ratio_spread.sh:
/usr/bin/python3 ratio_spread.py OUT_DIR. Before: the plain ratio of the
medians of sequential runs; after: the ratio paired by round (the CSV's
`ratio`)."""
import csv
import statistics
import sys

out = sys.argv[1]
for mode in ("before", "after"):
    ratios = {}
    for i in (1, 2, 3):
        with open(f"{out}/{mode}_{i}.csv", newline="") as f:
            rows = [r for r in csv.DictReader(f) if r["stage"] == "total" and r["status"] == "ok"]
        base = next(float(r["median_ms"]) for r in rows if r["technique"] == "unsorted")
        for r in rows:
            value = float(r["ratio"]) if mode == "after" and r.get("ratio") else float(r["median_ms"]) / base
            ratios.setdefault(r["technique"], []).append(value)
    print(mode)
    for technique, values in ratios.items():
        middle = statistics.median(values)
        deviation = max(abs(v - middle) / middle for v in values) * 100
        print(f"  {technique:28s} {' '.join(f'{v:7.2f}' for v in values)}   largest deviation from the median "
              f"{deviation:5.1f}%")
