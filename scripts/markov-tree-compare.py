#!/usr/bin/env python3
"""The Markov tree's P_t against the measured tail at K = 0.1 (issue 40, docs/markov-tree.md): a Markdown table per
decade (model, measured, ratio, local exponents, the level that holds the model's survivors) and a PNG figure.

  scripts/markov-tree-compare.py --atlas a.json [--cli archipelago-cli] [--stats-csv DIR] [--out markov-tree-k0.1.png]
  scripts/markov-tree-compare.py model.json [--stats-csv DIR] [--out markov-tree-k0.1.png] [--table table.md]

--atlas: runs `archipelago-cli markov-tree --atlas a.json --alpha 18.9043 --b2 1.362484 --t-max 1009531200 --at <the
tail's levels> --json <out>.model.json` first (alpha: `stats` of the k0.1-minute run, q = 16; b2: stochastic_area at
4096^2, docs/atlas.md); model.json: such a file made by hand.
The measured tail: the levels of the sampler's run to 10^9 (docs/tail.md, "The run toward t = 10^9": N = 800, R = 16,
every level reliable) and its gamma over decade windows, as that document tabulates them (the run's file is not kept
in the repository); --stats-csv: the folder `archipelago-cli stats RUN --short RUN.short --csv DIR` wrote (its P.csv:
the run's spliced brute-force P_t).
Needs matplotlib (/usr/bin/python3 has it here).
"""
import argparse, csv, json, math, os

# docs/tail.md, "The run toward t = 10^9": t (steps), P_t, error.
TAIL = [(1008, 1.90e-4, 1.3e-6), (10095, 2.136e-5, 3.8e-7), (100944, 3.99e-7, 1.6e-8), (1009520, 1.689e-9, 3.3e-10),
        (10095312, 1.678e-10, 4.0e-11), (100953120, 1.084e-12, 2.9e-13), (468576000, 1.961e-13, 8.3e-14),
        (1009531200, 7.52e-14, 3.1e-14)]
# docs/tail.md, the brute-force validation table (10^12 steps of run, N = 200, R = 16): the levels between decades.
TAIL_VALIDATION = [(2160, 7.890e-5, 2.6e-6), (4672, 3.868e-5, 1.6e-6), (21744, 8.907e-6, 4.6e-7),
                   (46848, 2.170e-6, 1.5e-7), (217488, 5.725e-8, 7.9e-9), (468576, 6.706e-9, 1.8e-9),
                   (2174960, 4.635e-10, 1.4e-10), (4685824, 2.560e-10, 7.2e-11)]
# docs/tail.md, gamma over decade windows of the 10^9 run (the statistics' definition).
TAIL_GAMMA = [((1e3, 1e4), 0.912, 0.008), ((3e3, 3e4), 1.073, 0.008), ((1e4, 1e5), 1.817, 0.019),
              ((3e4, 3e5), 2.30, 0.03), ((1e5, 1e6), 2.47, 0.09), ((3e5, 3e6), 1.49, 0.09), ((1e6, 1e7), 0.96, 0.08),
              ((3e6, 3e7), 1.58, 0.05), ((1e7, 1e8), 2.32, 0.16), ((3e7, 3e8), 1.55, 0.22), ((1e8, 1e9), 1.15, 0.13)]

p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
p.add_argument("model", nargs="?")
p.add_argument("--atlas", help="an atlas JSON (archipelago-cli atlas --K 0.1 --depth 2 --json a.json): run markov-tree on it")
p.add_argument("--cli", default="build/default/app/archipelago-cli")
p.add_argument("--alpha", default="18.9043", help="the run's mean segment length, steps (q = 16: the tail's process)")
p.add_argument("--b2", default="1.362484", help="the stochastic area of the box")
p.add_argument("--stats-csv", help="folder of `stats --csv`: its P.csv is the run's P_t")
p.add_argument("--out", default="markov-tree-k0.1.png")
p.add_argument("--table", help="write the Markdown table here too")
a = p.parse_args()
if a.atlas:
    import subprocess
    a.model = os.path.splitext(a.out)[0] + ".model.json"
    levels = ",".join(str(x) for x, _, _ in TAIL + TAIL_VALIDATION)
    subprocess.run([a.cli, "markov-tree", "--atlas", a.atlas, "--alpha", a.alpha, "--b2", a.b2, "--t-max",
                    "1009531200", "--at", levels, "--quiet", "--json", a.model], check=True)
elif not a.model:
    raise SystemExit("give a model JSON or --atlas")
m = json.load(open(a.model))
S = m["survival"]
t = S["t"]
P = S["P"]
if P[0] is None:
    raise SystemExit("the model has no P_t: run markov-tree with --alpha and --b2")
w = m["entry"]["weight"]
levels = S["levels"]
index = {x: i for i, x in enumerate(t)}


def model_at(x):
    if x in index:
        return P[index[x]]
    raise SystemExit(f"t = {x} is not in the model's grid: run markov-tree with --at {x}")


def dominant(x):
    i = index[x]
    shares = [(lv[i] or 0) for lv in levels]
    total = sum(shares)
    k = max(range(len(shares)), key=lambda j: shares[j])
    return k, (shares[k] / total if total > 0 else float("nan"))


def gamma_model(lo, hi):
    # the model's gamma over the same window (core's definition; markov-tree --t-max 1009531200 gives the tail's
    # windows: decades ending at its last level 1.0095e9 * 10^(-k/2), which docs/tail.md labels 10^8-10^9, ...)
    for e in m["exponents"]:
        if abs(math.log10(e["from"] / lo)) < 0.06 and abs(math.log10(e["to"] / hi)) < 0.06:
            return e["gamma"]
    return float("nan")


rows = []
rows.append("| t (steps) | P_t measured | P_t model | model / measured | level holding the model's survivors |")
rows.append("|---:|---:|---:|---:|---|")
for x, y, e in sorted(TAIL + TAIL_VALIDATION):
    mp = model_at(x)
    k, share = dominant(x)
    ratio = (mp / y) if mp else 0.0
    rows.append(f"| {x:,} | {y:.3g} ± {e:.2g} | {mp:.3g} | {ratio:.3g} | {k} ({share:.0%}) |" if mp is not None else
                f"| {x:,} | {y:.3g} ± {e:.2g} | < 1e-308 | 0 | – |")
rows.append("")
rows.append("| window (steps) | γ measured | γ model |")
rows.append("|---|---:|---:|")
for (lo, hi), g, ge in TAIL_GAMMA:
    rows.append(f"| {lo:.0e}–{hi:.0e} | {g:.3g} ± {ge:.2g} | {gamma_model(lo, hi):.3g} |")
table = "\n".join(rows)
print(f"entry weight w = {w:.6g} visits per segment; mean visit {m['mean_visit']:.6g} steps "
      f"(Kac: {m['residence']:.6g}); {len(m['states'])} states, {len(m['lumped'])} chains lumped")
print(table)
if a.table:
    open(a.table, "w").write(table + "\n")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 9), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
xs = [x for x, y in zip(t, P) if y and y > 1e-30 and x >= 10]
ys = [y for x, y in zip(t, P) if y and y > 1e-30 and x >= 10]
top.plot(xs, ys, "-", color="k", lw=2, label="Markov tree (atlas depth %d), P_t = w S(t)" % m["atlas"]["depth"])
for k, lv in enumerate(levels):
    pts = [(x, w * v) for x, v in zip(t, lv) if v and w * v > 1e-30 and x >= 10]
    if pts:
        top.plot([u for u, _ in pts], [v for _, v in pts], "--", lw=1, color="C%d" % (k + 2),
                 label="model: survivors at level %d" % k)
if a.stats_csv:
    f = os.path.join(a.stats_csv, "P_t.csv")
    rd = [r for r in csv.reader(l for l in open(f) if not l.startswith("#"))]
    run = [(float(r[0]), float(r[1])) for r in rd[1:] if float(r[0]) >= 160 and float(r[1]) > 0]  # t >= 10 q
    top.plot([u for u, _ in run], [v for _, v in run], "-", color="C0", lw=1,
             label="run P_t (k0.1-minute, q = 16: the tail's process)")
tail = sorted(TAIL + TAIL_VALIDATION)
top.errorbar([x for x, _, _ in tail], [y for _, y, _ in tail], yerr=[e for _, _, e in tail], fmt="o", color="C3",
             ms=4, label="tail sampler (docs/tail.md)")
top.set_xscale("log")
top.set_yscale("log")
top.set_ylim(1e-16, 1)
top.set_ylabel("P_t")
top.legend(fontsize=8, loc="lower left")
top.set_title("K = 0.1: Markov tree from the atlas against the measured P_t")
gx = [math.sqrt(e["from"] * e["to"]) for e in m["exponents"]]
bottom.plot(gx, [e["gamma"] for e in m["exponents"]], "-", color="k", label="model γ(t), decade windows")
bottom.errorbar([math.sqrt(lo * hi) for (lo, hi), _, _ in TAIL_GAMMA], [g for _, g, _ in TAIL_GAMMA],
                yerr=[e for _, _, e in TAIL_GAMMA], fmt="o", color="C3", ms=4, label="tail sampler γ (docs/tail.md)")
bottom.set_ylim(0, 6)
bottom.set_ylabel("γ = −d ln P / d ln t")
bottom.set_xlabel("t (steps)")
bottom.legend(fontsize=8)
bottom.set_xlim(10, 2e9)
fig.tight_layout()
fig.savefig(a.out, dpi=110)
print("wrote", a.out)
