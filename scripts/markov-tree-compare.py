#!/usr/bin/env python3
"""The Markov tree's P_t against the measured tail (issue 40, docs/markov-tree.md): a Markdown table per level
(model, measured, ratio, the level that holds the model's survivors), the running exponents per decade window, and a
PNG figure.  The comparison is core's (`markov-tree --tail`: compareMarkovTreeWithTail); this script formats and draws.

  scripts/markov-tree-compare.py --atlas a.json --tail t.json [--alpha A --b2 B] [--stats-csv DIR] [--out F.png]
  scripts/markov-tree-compare.py model.json --tail t.json [--stats-csv DIR] [--out F.png] [--table table.md]

--atlas: runs `archipelago-cli markov-tree --atlas a.json --tail t.json --alpha A --b2 B --t-max <the tail's last
level> --at <its levels> --json <out>.model.json` first; model.json: such a file (made with --tail).
--tail: the sampler's file (`archipelago-cli tail ... --out t.json`) of the atlas's K and box: its reliable levels and
its gamma over decade windows.  At K = 0.1 docs/markov-tree.md's run:
  archipelago-cli tail --population 800 --replicas 16 --t-max 1e9 --out k01-1e9.json
--alpha: the run's mean segment length (`stats` of a run of the tail's process, q = 16, in the atlas's box); --b2: the
stochastic area of the box (`stochastic-area`). Both must be measured at the atlas's K and box: only for K = 0.1 in
the box [-0.8, 0.5) do they default (18.9043 from the k0.1-minute run, 1.362484 at 4096^2, docs/atlas.md).
--stats-csv: the folder `archipelago-cli stats RUN --csv DIR` wrote (its P_t.csv: the run's P_t, drawn from 10 q).
Needs matplotlib (/usr/bin/python3 has it here).
"""
import argparse, csv, json, math, os, subprocess

# K = 0.1 in the default box: the entry's inputs of docs/atlas.md and docs/markov-tree.md (core's
# kMarkovTreeDocsAlpha, kMarkovTreeDocsB2).
DEFAULT_MAP = (0.1, -0.8, 0.5)
DEFAULT_ALPHA, DEFAULT_B2 = "18.9043", "1.362484"

p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
p.add_argument("model", nargs="?")
p.add_argument("--atlas", help="an atlas JSON (archipelago-cli atlas --K 0.1 --depth 2 --json a.json): run markov-tree on it")
p.add_argument("--tail", required=True, help="the tail sampler's JSON at the atlas's map")
p.add_argument("--cli", default="build/default/app/archipelago-cli")
p.add_argument("--alpha", help="the run's mean segment length, steps (q = 16: the tail's process), at the atlas's map")
p.add_argument("--b2", help="the stochastic area of the atlas's box")
p.add_argument("--stats-csv", help="folder of `stats --csv`: its P_t.csv is the run's P_t")
p.add_argument("--out", help="the figure (default markov-tree-k<K>.png)")
p.add_argument("--table", help="write the Markdown table here too")
a = p.parse_args()


def same_map(x, y):
    return all(abs(u - v) <= 1e-12 * max(1.0, abs(u)) for u, v in zip(x, y))


def map_of(doc, what):
    mp = doc.get("map") or doc.get("parameters")
    try:
        return (float(mp["K"]), float(mp["xmin"]), float(mp["xmax"]))
    except (KeyError, TypeError, ValueError):
        raise SystemExit(f"{what}: no map (K, xmin, xmax) in the file")


def load(path, what):
    try:
        return json.load(open(path))
    except (OSError, ValueError) as e:
        raise SystemExit(f"{what} {path}: {e}")


td = load(a.tail, "--tail")
if td.get("format") != "archipelago-tail":
    raise SystemExit(f"--tail {a.tail}: not a tail sampler's file (format {td.get('format')!r})")
tail_levels = [l for l in td["levels"] if l["reliable"] and l["P"] > 0]
if not tail_levels:
    raise SystemExit(f"--tail {a.tail}: no reliable level with P > 0")
tail_gamma = [((float(e["t_from"]), float(e["t_to"])), float(e["gamma"]), float(e["gamma_error"]))
              for e in td["exponents"]]
tail_label = "tail sampler (%s: N = %d, R = %d)" % (os.path.basename(a.tail), td["sampler"]["population"],
                                                    td["sampler"]["replicas"])
t_max = max(l["t"] for l in tail_levels)

if a.atlas:
    atlas_map = map_of(load(a.atlas, "--atlas"), "--atlas")
    if a.alpha is None or a.b2 is None:
        if not same_map(atlas_map, DEFAULT_MAP):
            raise SystemExit(f"--alpha and --b2 default to K = 0.1's numbers only: give both, measured at K = "
                             f"{atlas_map[0]:g} in the box [{atlas_map[1]:g}, {atlas_map[2]:g})")
        a.alpha = a.alpha or DEFAULT_ALPHA
        a.b2 = a.b2 or DEFAULT_B2
    out = a.out or "markov-tree-k%g.png" % atlas_map[0]
    a.model = os.path.splitext(out)[0] + ".model.json"
    levels_at = ",".join(str(l["t"]) for l in tail_levels)
    subprocess.run([a.cli, "markov-tree", "--atlas", a.atlas, "--tail", a.tail, "--alpha", str(a.alpha), "--b2",
                    str(a.b2), "--t-max", str(t_max), "--at", levels_at, "--quiet", "--json", a.model], check=True)
elif not a.model:
    raise SystemExit("give a model JSON or --atlas")
m = load(a.model, "model")
model_map = map_of(m, "model")
if "comparison" not in m:
    raise SystemExit(f"{a.model}: no comparison: make it with markov-tree --tail {a.tail}")
if not same_map(model_map, map_of(td, "--tail")):
    raise SystemExit(f"the model's map (K, xmin, xmax) = {model_map} is not the tail's {map_of(td, '--tail')}")
out = a.out or "markov-tree-k%g.png" % model_map[0]
S = m["survival"]
t = S["t"]
P = S["P"]
w = m["entry"]["weight"]
levels = S["levels"]
comparison = m["comparison"]


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


def tenth_power(log10):  # a number below the smallest double, from its log10
    e = math.floor(log10)
    return f"{10 ** (log10 - e):.2g}e{e}"


for c in comparison["levels"]:
    model = f"{c['model']:.3g}" if c["model"] is not None else tenth_power(c["log10_model"])
    ratio = f"{c['ratio']:.3g}" if c["ratio"] is not None else tenth_power(c["log10_ratio"])
    hold = f"{c['holding_level']} ({c['holding_share']:.0%})" if c["holding_level"] >= 0 else "–"
    rows.append(f"| {c['t']:,.0f} | {c['measured']:.3g} ± {c['measured_error']:.2g} | {model} | {ratio} | {hold} |")
rows.append("")
rows.append(f"Model / measured within a factor {comparison['factor']:g} last at t = {comparison['reach']:,.0f} steps.")
rows.append("")
rows.append("| window (steps) | γ measured | γ model |")
rows.append("|---|---:|---:|")
for (lo, hi), g, ge in tail_gamma:
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
             label="run P_t (q = 16: the tail's process)")
top.errorbar([l["t"] for l in tail_levels], [l["P"] for l in tail_levels], yerr=[l["P_error"] for l in tail_levels], fmt="o", color="C3",
             ms=4, label=tail_label)
top.set_xscale("log")
top.set_yscale("log")
top.set_ylim(1e-16, 1)
top.set_ylabel("P_t")
top.legend(fontsize=8, loc="lower left")
top.set_title("K = %g: Markov tree from the atlas against the measured P_t" % model_map[0])
gx = [math.sqrt(e["from"] * e["to"]) for e in m["exponents"]]
bottom.plot(gx, [e["gamma"] for e in m["exponents"]], "-", color="k", label="model γ(t), decade windows")
bottom.errorbar([math.sqrt(lo * hi) for (lo, hi), _, _ in tail_gamma], [g for _, g, _ in tail_gamma],
                yerr=[e for _, _, e in tail_gamma], fmt="o", color="C3", ms=4, label=tail_label + " γ")
bottom.set_ylim(0, 6)
bottom.set_ylabel("γ = −d ln P / d ln t")
bottom.set_xlabel("t (steps)")
bottom.legend(fontsize=8)
bottom.set_xlim(10, 2 * t_max)
fig.tight_layout()
fig.savefig(out, dpi=110)
print("wrote", out)
