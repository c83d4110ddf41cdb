#!/usr/bin/env python3
"""The tail sampler's seeds against one brute-force run, level by level (issue 55's second estimator): reads the
comparison CSVs that `archipelago-cli tail --compare RUN --compare-csv FILE` writes for several seeds of the same
settings, and prints per level the mean ratio P_tail/P_brute over the seeds, its error (the seeds' spread/sqrt(n) and
the brute force's relative error, in quadrature: the seeds share the one brute-force run), its z, and the seeds'
spread of the ratio against the errors a single run quotes (the sampler's and the brute force's, in quadrature): a
quotient above 1 says one run's error is too small there.  Reads the CSVs only.

Usage: python3 scripts/tail-seeds-vs-brute.py cmp-seed1.csv cmp-seed2.csv ...   (two or more)
"""
import csv
import math
import statistics
import sys


def levels(files):
    by_t = {}
    for name in files:
        with open(name) as f:
            for row in csv.DictReader(line for line in f if not line.startswith("#")):
                if row["brute_P"] and row["P"]:
                    by_t.setdefault(float(row["t"]), []).append(
                        (float(row["P"]), float(row["P_error"]), float(row["brute_P"]), float(row["brute_error"])))
    return by_t


def main(files):
    if len(files) < 2:
        sys.exit("give two or more comparison CSVs (one per seed)")
    print("| t | seeds | mean P_tail/P_brute | error | z | seeds' spread / one run's quoted error |")
    print("|---|---|---|---|---|---|")
    for t, rows in sorted(levels(files).items()):
        if len(rows) < 2:
            continue
        ratios = [p / b for p, _, b, _ in rows]
        mean, spread = statistics.mean(ratios), statistics.stdev(ratios)
        brute = rows[0][3] / rows[0][2]
        error = math.sqrt(spread ** 2 / len(rows) + brute ** 2)
        quoted = statistics.mean(math.sqrt((pe / p) ** 2 + (be / b) ** 2) for p, pe, b, be in rows)
        print(f"| {t:.0f} | {len(rows)} | {mean:.4f} | {error:.4f} | {(mean - 1) / error:+.2f} | {spread / quoted:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
