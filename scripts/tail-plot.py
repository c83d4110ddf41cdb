#!/usr/bin/env python3
"""Plots a tail file (archipelago-cli tail --out FILE): P_t with its error bars at the reliable levels (the unreliable
ones hollow, not data), optionally the brute-force P_t of a `tail --compare-csv` file, and the running
exponent gamma(t) = -dlnP/dlnt over decade windows (stats' definition) with its error, against the literature's asymptotic values
(t^-1.57 Cristadoro & Ketzmerick 2008, t^-3/2 Venegeroles 2009, t^-1.3 Shepelyansky 2010, t^-3 Chirikov &
Shepelyansky 1999).

  scripts/tail-plot.py tail.json [--compare tail.compare.csv] [--out tail.png]
"""
import argparse, csv, json, math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
p.add_argument("tail")
p.add_argument("--compare")
p.add_argument("--out", default="tail.png")
a = p.parse_args()
d = json.load(open(a.tail))
L = d["levels"]
fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 8), sharex=True)
for reliable, style in ((True, dict(fmt="o", color="C0", label="tail, reliable")),
                        (False, dict(fmt="o", mfc="none", color="C0", alpha=0.5, label="tail, unreliable (not data)"))):
    pts = [x for x in L if x["reliable"] == reliable and x["P"] > 0]
    if pts:
        top.errorbar([x["t"] for x in pts], [x["P"] for x in pts], yerr=[x["P_error"] or 0 for x in pts], **style)
if a.compare:
    rows = [r for r in csv.DictReader(l for l in open(a.compare) if not l.startswith("#"))
            if r["brute_P"] and float(r["brute_P"]) > 0 and int(r["brute_segments"]) >= 10]
    top.errorbar([float(r["t"]) for r in rows], [float(r["brute_P"]) for r in rows],
                 yerr=[float(r["brute_error"] or 0) for r in rows], fmt="s", color="C3", ms=4,
                 label="brute force (>= 10 segments beyond t)")
top.set_xscale("log")
top.set_yscale("log")
top.set_ylabel("P_t")
top.legend()
E = d["exponents"]
bottom.errorbar([e["t"] for e in E], [e["gamma"] for e in E], yerr=[e["gamma_error"] or 0 for e in E],
                xerr=[[e["t"] - e["t_from"] for e in E], [e["t_to"] - e["t"] for e in E]], fmt="o", color="C0",
                label="γ(t) = -dlnP/dlnt over decade windows (horizontal bar), ±1σ")
for g, name, c in ((1.57, "1.57 Cristadoro & Ketzmerick 2008", "C1"), (1.5, "3/2 Venegeroles 2009", "C2"),
                   (1.3, "1.3 Shepelyansky 2010", "C4"), (3.0, "3 Chirikov & Shepelyansky 1999", "C5")):
    bottom.axhline(g, color=c, ls="--", lw=1, label=name)
bottom.set_xscale("log")
bottom.set_xlabel("t (steps)")
bottom.set_ylabel("running exponent γ(t)")
bottom.legend(fontsize=7)
sampler = d["sampler"]
fig.suptitle(f"K = {d['parameters']['K']}, q = {d['parameters']['q']}: N = {sampler['population']}, "
             f"R = {sampler['replicas']}, {d['steps']:.3g} steps")
fig.tight_layout()
fig.savefig(a.out, dpi=120)
print(f"wrote {a.out}")
