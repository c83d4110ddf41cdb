#!/usr/bin/env python3
"""Validation of `archipelago-cli tail` (issue 29, deliverable 2) against brute force, to t = 10^7 steps.

  scripts/tail-validate.py [--cli build/default/app/archipelago-cli] [--dir tail-validation] [--brute-steps 3e11]
                           [--t-max 1e7] [--replicas 16] [--seeds 0] [--K K] [--first T] [--level-bins B]
                           [--population N] [--brute-only] [--quick]

Everything at the paper's K = 0.1 box, Xr = 0.02, q = 16 (the default spec), niced; with --K, at that K in the box
of the K scan's rule (core/scan/ScanBox.hpp: xmin = -2 sqrt(K) - 0.2, xmax = sqrt(K) + 0.2), the box the tail scan
(issue 55) uses at each K.  --brute-only: (a) and (c) alone, the second estimator of issue 55 (brute force shares
nothing with splitting on segment age) against the sampler at one K.

 (a) brute force: `run` of --brute-steps steps (M = 256 orbits) and `stats` of it (DIR/stats/*.csv); the sampler
     (N = 200, --replicas, epsilon = the default) set against it with `tail --compare`: at every level where the run
     has at least 10 segments longer than t, z = (P_tail - P_brute)/sqrt(err^2 + err^2) is printed, and the check
     is |z| < 3 at every such level;
 (b) independence of epsilon (1, 10^3, 10^6 lattice units, six orders of magnitude) and of N (50, 200, 800): each
     run with its own seed, so that the estimates are independent; at every level that both runs of a pair call
     reliable, z of their difference; the check is |z| < 3;
 (c) the steps: the sampler's steps up to each level against the steps a brute-force run needs for the sampler's
     relative error there (tail --compare's brute_steps_same_error: from the run's own error where it has segments,
     else alpha/(P r^2)).
 (d) --seeds S > 0 (issue 39, deliverable 1 (d)): S more runs of (a)'s sampler (N = 200, --replicas), seeds 101 …
     100 + S, pooled with (a)'s seed 11: at each level the mean of the S + 1 estimates, its error from their spread
     (the seeds are independent; each seed's own error is not used), z against brute force, and where seed 11 falls
     among the seeds; then over the levels from 10^6 on (correlated: they share lineages, and the brute-force counts
     beyond t are nested) each seed's mean ratio P_tail/P_brute, one number per seed, so that the spread of those S + 1
     numbers carries the correlation: their mean and error.  The check: the pooled mean ratio within 3 sigma of 1, where
     sigma combines the seeds' spread and the brute force's own error of the same mean.

Runs already in DIR with the same settings are reused (delete DIR to start again).  --quick: 3·10^9 brute-force
steps, t_max 10^5, 8 replicas (a few minutes).  Prints a table per check and a last line "tail validation: PASS" or
"... FAIL (n checks)".  A 3-sigma check over ~10 levels and 6 pairs fails by chance in a few per cent of seeds:
read the table, not only the verdict.
"""
import argparse, csv, json, math, os, subprocess, sys

p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
p.add_argument("--cli", default=os.path.join(os.path.dirname(__file__), "..", "build", "default", "app", "archipelago-cli"))
p.add_argument("--dir", default="tail-validation")
p.add_argument("--brute-steps", type=float, default=3e11)
p.add_argument("--t-max", type=float, default=1e7)
p.add_argument("--replicas", type=int, default=16)
p.add_argument("--seeds", type=int, default=0, help="(d): this many more seeds of (a)'s sampler, pooled")
p.add_argument("--K", type=float, default=None, help="this K in the scan's box (default: the default spec's K = 0.1 box)")
p.add_argument("--first", type=float, default=None, help="the sampler's first level (tail --first; at K = 0.3 "
               "few segments last 10^3 steps)")
p.add_argument("--level-bins", type=int, default=None, help="tail --level-bins (3: levels x1.26 apart, where P falls "
               "steeply between levels, K = 0.3)")
p.add_argument("--population", type=int, default=200, help="(a)'s sampler's N")
p.add_argument("--brute-only", action="store_true", help="(a) and (c) only: the sampler against brute force")
p.add_argument("--quick", action="store_true")
a = p.parse_args()
# The spec options of every run and tail: the default spec, or K in the scan box's rule.
spec = [] if a.K is None else ["--K", repr(a.K), "--xmin", repr(-2 * math.sqrt(a.K) - 0.2),
                               "--xmax", repr(math.sqrt(a.K) + 0.2)]
if a.quick:
    a.brute_steps, a.t_max, a.replicas = 3e9, 1e5, 8
os.makedirs(a.dir, exist_ok=True)
Q, M = 16, 256
failures = 0


def cli(*args):
    cmd = ["nice", "-n", "10", a.cli, *map(str, args)]
    print("$ " + " ".join(cmd[3:]), flush=True)
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"failed: {r.stderr.strip()}")
    return r


def check(ok, what):
    global failures
    failures += 0 if ok else 1
    print(("ok   " if ok else "FAIL ") + what)


def table(path):
    rows = [l for l in open(path) if not l.startswith("#")]
    return list(csv.DictReader(rows))


def num(x):
    return float(x) if x not in ("", None) else float("nan")


# (a) brute force and the sampler against it ------------------------------------------------------------------
T = int(a.brute_steps / (M * Q))
brute = os.path.join(a.dir, f"brute-M{M}-T{T}.json")
if not os.path.exists(brute):
    cli("run", *spec, "--M", M, "--T", T, "--out", brute, "--quiet")
cli("stats", brute, "--csv", os.path.join(a.dir, "stats"))


def tail(name, *args):
    out = os.path.join(a.dir, name + ".json")
    cmp = os.path.join(a.dir, name + ".compare.csv")
    text = os.path.join(a.dir, name + ".txt")  # its report: the levels and the comparison with its pooled test
    if not (os.path.exists(out) and os.path.exists(cmp) and os.path.exists(text)):
        first = ([] if a.first is None else ["--first", int(a.first)]) + \
                ([] if a.level_bins is None else ["--level-bins", a.level_bins])
        r = cli("tail", *spec, *first, "--t-max", int(a.t_max), "--replicas", a.replicas, *args, "--out", out, "--csv",
                os.path.join(a.dir, name + ".csv"), "--compare", brute, "--compare-csv", cmp)
        open(text, "w").write(r.stdout)
    return json.load(open(out)), table(cmp)


base, compared = tail("base", "--population", a.population, "--seed", 11)
print(f"\n(a) tail (N = {a.population}, R = {a.replicas}) against brute force ({a.brute_steps:.3g} steps)")
print(f"{'t':>10} {'P_tail':>11} {'err':>9} {'P_brute':>11} {'err':>9} {'segments':>8} {'z':>6}  ancestors reliable")
worst = 0
for row, L in zip(compared, base["levels"]):
    z, n = num(row["z"]), int(row["brute_segments"])
    print(f"{num(row['t']):10.0f} {num(row['P']):11.4g} {num(row['P_error']):9.2g} {num(row['brute_P']):11.4g} "
          f"{num(row['brute_error']):9.2g} {n:8d} {z:6.2f}  {L['ancestors']:9d} {str(L['reliable']):>8}")
    if n >= 10 and math.isfinite(z):
        worst = max(worst, abs(z))
        check(abs(z) < 3, f"t = {num(row['t']):.0f}: |z| = {abs(z):.2f} < 3")

# The one test of the comparison: the levels pooled with the covariance of both estimators (core's pooledBias).
pooled = [l for l in open(os.path.join(a.dir, "base.txt")) if l.startswith("# pooled")]
print(pooled[0].rstrip() if pooled else "# pooled: not in the tail's report")

# (b) independence of epsilon and N --------------------------------------------------------------------------
runs = {}
if a.brute_only:
    seedsAndEps, seedsAndN = (), ()
else:
    seedsAndEps, seedsAndN = ((21, 1), (22, 1000), (23, 1000000)), ((31, 50), (32, 200), (33, 800))
for seed, eps in seedsAndEps:
    runs[f"eps={eps}"] = tail(f"eps{eps}", "--population", 200, "--epsilon", eps, "--seed", seed)[0]
for seed, n in seedsAndN:
    runs[f"N={n}"] = tail(f"N{n}", "--population", n, "--seed", seed)[0]


def pairs(keys):
    return [(x, y) for i, x in enumerate(keys) for y in keys[i + 1:]]


for title, keys in (() if a.brute_only else
                    (("epsilon", ["eps=1", "eps=1000", "eps=1000000"]), ("N", ["N=50", "N=200", "N=800"]))):
    print(f"\n(b) independence of {title}: P (error) at each level, * reliable")
    print(f"{'t':>10} " + " ".join(f"{k:>24}" for k in keys))
    levels = min(len(runs[k]["levels"]) for k in keys)
    for i in range(levels):
        cells = []
        for k in keys:
            L = runs[k]["levels"][i]
            cells.append(f"{L['P']:11.4g} ({(L['P_error'] or 0):8.2g}){'*' if L['reliable'] else ' '}")
        print(f"{runs[keys[0]]['levels'][i]['t']:10.0f} " + " ".join(f"{c:>24}" for c in cells))
    for x, y in pairs(keys):
        zs = []
        for Lx, Ly in zip(runs[x]["levels"], runs[y]["levels"]):
            if Lx["reliable"] and Ly["reliable"] and Lx["P_error"] and Ly["P_error"]:
                zs.append((Lx["t"], (Lx["P"] - Ly["P"]) / math.hypot(Lx["P_error"], Ly["P_error"])))
        if zs:
            t, z = max(zs, key=lambda v: abs(v[1]))
            check(abs(z) < 3, f"{x} vs {y}: {len(zs)} reliable levels, largest |z| = {abs(z):.2f} (t = {t:.0f})")

# (c) steps --------------------------------------------------------------------------------------------------
print("\n(c) the sampler's steps (cumulative, all replicas) against brute-force steps for the same relative error")
print(f"{'t':>10} {'rel. error':>10} {'tail steps':>12} {'brute steps':>12} {'ratio':>8}")
for row in compared:
    t, P, e = num(row["t"]), num(row["P"]), num(row["P_error"])
    bs, ts = num(row["brute_steps_same_error"]), num(row["tail_steps"])
    tag = "" if row["measured"] == "1" else " (alpha/(P r^2))"
    print(f"{t:10.0f} {e / P if P > 0 else float('nan'):10.3g} {ts:12.4g} {bs:12.4g} {bs / ts:8.3g}{tag}")

# (d) more seeds of (a)'s sampler, pooled --------------------------------------------------------------------
if a.seeds > 0:
    seeds = [11] + [100 + i for i in range(1, a.seeds + 1)]
    per = [compared] + [tail(f"seed{s}", "--population", 200, "--seed", s)[1] for s in seeds[1:]]
    print(f"\n(d) {len(seeds)} seeds of (a)'s sampler (N = 200, R = {a.replicas}) pooled, against brute force")
    print(f"{'t':>10} {'P pooled':>11} {'err':>9} {'P brute':>11} {'err':>9} {'z':>6} {'seed 11 / pooled':>16} "
          f"{'seeds below 11':>14}")
    ratios = {s: [] for s in seeds}  # each seed's P_tail / P_brute at the levels from 10^6 on
    brute_rel = []
    for i, row in enumerate(compared):
        t, Pb, eb = num(row["t"]), num(row["brute_P"]), num(row["brute_error"])
        Ps = [num(rows[i]["P"]) for rows in per]
        mean = sum(Ps) / len(Ps)
        sd = math.sqrt(sum((x - mean) ** 2 for x in Ps) / (len(Ps) - 1))
        err = sd / math.sqrt(len(Ps))
        z = (mean - Pb) / math.hypot(err, eb) if Pb > 0 and math.isfinite(eb) else float("nan")
        below = sum(1 for x in Ps[1:] if x < Ps[0])
        print(f"{t:10.0f} {mean:11.4g} {err:9.2g} {Pb:11.4g} {eb:9.2g} {z:6.2f} {Ps[0] / mean:16.3f} "
              f"{below:8d} of {len(Ps) - 1}")
        if t >= 1e6 and Pb > 0:
            for s, x in zip(seeds, Ps):
                ratios[s].append(x / Pb)
            brute_rel.append(eb / Pb)
    if brute_rel:
        means = [sum(v) / len(v) for v in ratios.values()]
        m = sum(means) / len(means)
        e = math.sqrt(sum((x - m) ** 2 for x in means) / (len(means) - 1) / len(means))
        # The brute force's error of the same mean ratio: its levels' relative errors, fully correlated (the
        # nested counts beyond t) as the bound.
        eb = m * sum(brute_rel) / len(brute_rel)
        z = (m - 1) / math.hypot(e, eb)
        print(f"levels from 10^6 on ({len(brute_rel)}): mean P_tail/P_brute per seed: seed 11 {means[0]:.3f}, "
              f"the others {min(means[1:]):.3f} … {max(means[1:]):.3f}; pooled {m:.3f} ± {e:.3f} (seeds) "
              f"± {eb:.3f} (brute force)")
        check(abs(z) < 3, f"pooled mean ratio {m:.3f} within 3 sigma of 1 (z = {z:.2f})")

print(f"\ntail validation: {'PASS' if failures == 0 else f'FAIL ({failures} checks)'}")
sys.exit(1 if failures else 0)
