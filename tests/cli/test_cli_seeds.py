#!/usr/bin/env python3
"""archipelago-cli run --seeds / stats over several run files (issue #14, item 2): each seed's file is the plain
`run --seed K`; stats pools the histograms (the pooled f_t counts are the sums), gives D per seed, refuses runs
that differ in more than the seed, and bad seed lists are one clear ERROR line with nothing written."""
import csv, json, os, tempfile

from clitest import check, finish, run

tmp = tempfile.mkdtemp(prefix="archipelago-cli-seeds-")
params = ["--K", "0.1", "--xmin", "-0.8", "--xmax", "0.5", "--q", "4", "--T", "30000", "--M", "8", "--subsets", "4"]


def state(path):
    d = json.load(open(path))
    return d["parameters"], d["subsets"], d["longest"], d["orbits"], d["blocksDone"]


def counts(path):
    """{bin: count} summed over the subsets of a run file."""
    total = {}
    for subset in json.load(open(path))["subsets"]:
        for b, n, _ in subset:
            total[b] = total.get(b, 0) + n
    return total


def value(stdout, key):
    """The first number after `key` at the start of a line of stats' report."""
    for line in stdout.splitlines():
        if line.startswith(key):
            return float(line[len(key):].split()[0])
    return None


def one_error(r):
    lines = r.stderr.strip().splitlines()
    return r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: ")


# --- run --seeds writes one ordinary run file per seed --------------------------------------------------------
out = os.path.join(tmp, "ens.json")
r = run("run", *params, "--seeds", "1..2,5", "--out", out, "--quiet")
files = [os.path.join(tmp, f"ens.seed-{k}.json") for k in (1, 2, 5)]
check(r.returncode == 0 and all(map(os.path.exists, files)), f"run --seeds 1..2,5 writes NAME.seed-K.json ({r.stderr.strip()})")
check(sorted(os.listdir(tmp)) == sorted(os.path.basename(f) for f in files), f"and nothing else ({os.listdir(tmp)})")
for k, f in zip((1, 2, 5), files):
    plain = os.path.join(tmp, f"plain-{k}.json")
    r = run("run", *params, "--seed", str(k), "--out", plain, "--quiet")
    check(r.returncode == 0 and state(plain) == state(f), f"seed {k}'s file equals a plain run --seed {k}")
    os.remove(plain)

# --- stats pools them ---------------------------------------------------------------------------------------
csvdir, taildir = os.path.join(tmp, "csv"), os.path.join(tmp, "tail")
r = run("stats", *files, "--csv", csvdir, "--tail-csv", taildir, "--bootstrap", "200")
check(r.returncode == 0, f"stats over three seeds ({r.stderr.strip()})")
pooled = {}
for f in files:
    for b, n in counts(f).items():
        pooled[b] = pooled.get(b, 0) + n
check(value(r.stdout, "segments") == sum(pooled.values()), "pooled segments = the sum over the seeds")
# f_t in the exact bins (t ≤ 50 blocks) is N_t / (M (T + 1 − t)) / q² with M the pooled orbits (appendix A, B).
q, T, M = 4, 30000, 3 * 8
rows = list(csv.DictReader(l for l in open(os.path.join(csvdir, "f_t.csv")) if not l.startswith("#")))
exact = [(round(float(row["t"]) / q), float(row["f_t"])) for row in rows if float(row["t"]) <= 50 * q]
check(len(exact) > 10 and all(abs(f * M * (T + 1 - t) * q * q - pooled[t]) <= 1e-6 * pooled[t] for t, f in exact),
      f"pooled f_t counts are the sums of the seeds' counts ({len(exact)} exact bins)")
check("# ensemble: 3 runs pooled, seeds 1 2 5" in open(os.path.join(csvdir, "f_t.csv")).read(),
      "the ensemble's CSV files name its seeds")
# D per seed: each equals stats of that file alone.
alone = [value(run("stats", f, "--bootstrap", "50").stdout, "D ") for f in files]
line = next((l for l in r.stdout.splitlines() if l.startswith("D per seed")), "")
per_seed = [float(part.split(" (seed")[0]) for part in line[len("D per seed"):].split(", ")] if line else []
check(len(per_seed) == 3 and all(abs(a - b) <= 1e-3 * abs(a) for a, b in zip(per_seed, alone)),
      f"D per seed {per_seed} = stats of each file alone {alone}")
summary = {row["quantity"]: row for row in csv.DictReader(l for l in open(os.path.join(taildir, "tail_summary.csv"))
                                                          if not l.startswith("#"))}
steps = list(csv.DictReader(l for l in open(os.path.join(taildir, "D_vs_steps.csv")) if not l.startswith("#")))
check(len(steps) == 12 and float(steps[-1]["D"]) == float(summary["D"]["value"])
      and float(steps[-1]["steps"]) == M * T * q, "D against steps: 12 subsets, ending at the pooled D over M T q steps")
# The report never prints a ± for D when it says the tail dominates.
dline = next(l for l in r.stdout.splitlines() if l.startswith("D  "))
dominated = summary["dominated"]["value"] == "1"
check(("+-" not in dline and "cannot be estimated" in dline) if dominated else "+-" in dline,
      f"D's line agrees with the verdict (dominated = {dominated}): {dline[:90]}")
for key in ("tail end", "gamma_P", "literature", "forecast", "verdict"):
    check(any(l.startswith(key) for l in r.stdout.splitlines()), f"stats prints '{key}'")
check(sorted(os.listdir(taildir)) == sorted(["tail_summary.csv", "D_vs_steps.csv", "tail_fit.csv",
                                              "segments_beyond.csv", "P_t.reference.csv"]),
      f"stats --tail-csv writes the tail's five files ({sorted(os.listdir(taildir))})")
check("tail_summary.csv" not in os.listdir(csvdir), "and --csv only the GUI's set")

# --- refusals -------------------------------------------------------------------------------------------------
other = os.path.join(tmp, "other.json")
run("run", *params[:-6], "--T", "20000", "--M", "8", "--subsets", "4", "--seed", "9", "--out", other, "--quiet")
r = run("stats", files[0], other)
check(one_error(r) and "differ in T" in r.stderr, f"runs of different T are refused ({r.stderr.strip()})")
r = run("stats", files[0], files[0])
check(one_error(r) and "give each input once" in r.stderr, f"the same file twice is refused ({r.stderr.strip()})")
r = run("stats", files[0], "--bootstrap", "5")
check(one_error(r) and "replicates" in r.stderr, f"too few bootstrap replicates are refused ({r.stderr.strip()})")

bad = os.path.join(tmp, "bad")
os.mkdir(bad)
for seeds in ["nan", "inf", "-1..3", "-3", "1..nan", "0x10", "1.5", "", "5..1", "1,1", "1..3,2", "1..",
              "..4", "1...4", "1..100000000000", "18446744073709551615..18446744073709551616", "0..1000"]:
    r = run("run", *params, "--seeds", seeds, "--out", os.path.join(bad, "x.json"), "--quiet")
    check(one_error(r) and "--seeds" in r.stderr and os.listdir(bad) == [],
          f"--seeds '{seeds}' is refused with one line and writes nothing ({r.stderr.strip()[:100]})")
for extra in (["--seed", "3"], ["--print-spec"]):
    r = run("run", *params, "--seeds", "1..2", *extra, "--out", os.path.join(bad, "x.json"), "--quiet")
    check(one_error(r) and os.listdir(bad) == [], f"--seeds with {extra[0]} is refused ({r.stderr.strip()})")
r = run("run", "--seeds", "1..2", "--resume", files[0], "--out", os.path.join(bad, "x.json"), "--quiet")
check(one_error(r) and "resume" in r.stderr and os.listdir(bad) == [], f"--seeds with --resume is refused ({r.stderr.strip()})")

finish()
