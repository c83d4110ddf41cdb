#!/usr/bin/env python3
"""The distribution over K of a tail scan's local exponent per window, against the literature's asymptotic exponents
(issue 55): for each window of PREFIX_gamma.csv (written by `archipelago-cli tail-scan --csv PREFIX`), the K that
reach it, the K-average with its spread and error as PREFIX_average.csv gives them, the smallest, median and largest
γ over K, and how many K lie above 1.57 (Cristadoro & Ketzmerick 2008) and below 1.44 (ln 2/ln(1 + r_g)).  Prints a
Markdown table (docs/tail.md's).  Reads the CSVs only: every number of the averages is the scan's own.

Usage: python3 scripts/tail-scan-distribution.py PREFIX
"""
import csv
import statistics
import sys

CK, ULTRAMETRIC = 1.57, 1.44


def number(text):
    return float(text) if text else float("nan")


def main(prefix):
    gamma = list(csv.DictReader(open(prefix + "_gamma.csv")))
    average = list(csv.DictReader(open(prefix + "_average.csv")))
    print("| window (steps) | K reaching | γ̄ | spread over K | error of γ̄ | min – median – max over K "
          f"| K above {CK} | K below {ULTRAMETRIC} |")
    print("|---|---|---|---|---|---|---|---|")
    for w in average:
        values = sorted(number(g["gamma"]) for g in gamma
                        if g["t_from"] == w["t_from"] and g["t_to"] == w["t_to"] and g["gamma"])
        if not values:
            continue
        print(f"| {float(w['t_from']):.3g} – {float(w['t_to']):.3g} | {w['K_count']} | {number(w['gamma_mean']):.3f} "
              f"| {number(w['gamma_spread']):.3f} | {number(w['gamma_mean_error']):.3f} "
              f"| {values[0]:.2f} – {statistics.median(values):.2f} – {values[-1]:.2f} "
              f"| {sum(v > CK for v in values)} | {sum(v < ULTRAMETRIC for v in values)} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
