#!/usr/bin/env python3
"""archipelago-cli tail, end to end (issue 29): the tail file and CSV, bit-identical results over threads and
kernels, Ctrl-C (exit 130, a checkpoint) and --resume giving the uninterrupted result, the comparison with a run of
the same process, and bad input (one ERROR line each, nothing written)."""
import csv, io, json, os, subprocess, tempfile

from clitest import check, cli, finish, interrupt, leftovers, run, wait_for_file, options_with, tail_results

SETTINGS = {"--first": "150", "--t-max": "4000", "--population": "20", "--replicas": "3", "--min-ancestors": "4"}
SMALL = [x for kv in SETTINGS.items() for x in kv]


def small_with(args):
    """SMALL with the options of `args` replacing its own."""
    return options_with(SETTINGS, args)


results = tail_results


with tempfile.TemporaryDirectory() as d:
    out, table = os.path.join(d, "tail.json"), os.path.join(d, "tail.csv")
    r = run("tail", *SMALL, "--out", out, "--csv", table, "--threads", "1")
    check(r.returncode == 0, f"tail exits 0 ({r.stderr.strip()[-200:]})")
    doc = json.load(open(out))
    check(doc["format"] == "archipelago-tail" and doc["version"] == 1 and doc["finished"], "a finished tail file")
    levels = doc["levels"]
    check([L["t"] for L in levels] == [160, 368, 800, 1712, 3712, 8016], f"levels on histogram edges ({[L['t'] for L in levels]})")
    keys = {"t", "P", "P_error", "survivors", "ancestors", "reliable"}
    check(all(keys <= set(L) for L in levels) and doc["steps"] > 0, "every level has t, P, P_error, survivors, ancestors, reliable")
    check(all(a["P"] >= b["P"] > 0 for a, b in zip(levels, levels[1:])), "P decreases with t")
    check(levels[0]["ancestors"] == levels[0]["survivors"] >= 60 and levels[1]["ancestors"] <= 60
          and all(b["ancestors"] <= a["ancestors"] for a, b in zip(levels, levels[1:])),
          "lineages: every success of stage 0, then at most N R, never growing")
    rows = list(csv.DictReader(io.StringIO("".join(l for l in open(table) if not l.startswith("#")).split("\n\n")[0])))
    check(len(rows) == len(levels) and all(float(row["P"]) == L["P"] for row, L in zip(rows, levels)),
          "the CSV holds the file's levels")
    check("gamma" in r.stdout and "reliable" in r.stdout, "the table and the running exponent are printed")

    # The same request on two threads and the scalar kernel: the same file but time and kernel.
    other = os.path.join(d, "other.json")
    r = run("tail", *SMALL, "--out", other, "--threads", "2", "--kernel", "scalar", "--quiet")
    check(r.returncode == 0 and results(other) == results(out), "bit-identical over threads and kernels")

    # Ctrl-C: exit 130 with a checkpoint; --resume finishes with the uninterrupted result.  The signal comes once the
    # first checkpoint exists (0.2 s of work), so the run is stopped in its middle on any machine.
    LONG = ["--first", "1000", "--t-max", "1e7", "--population", "200", "--replicas", "2", "--quiet"]
    part = os.path.join(d, "part.json")
    p = subprocess.Popen([cli, "tail", *LONG, "--out", part, "--checkpoint-interval", "0.2"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    wait_for_file(part, p)
    _, err = interrupt(p)
    whole = os.path.join(d, "whole.json")
    r = run("tail", *LONG, "--out", whole)
    check(r.returncode == 0, "the same request, uninterrupted")
    if p.returncode == 0:
        check(True, "the run finished before the signal (nothing to resume)")
    else:
        check(p.returncode == 130 and "interrupted" in err and os.path.exists(part), f"SIGINT: exit 130, checkpoint ({err.strip()})")
        check(not json.load(open(part))["finished"], "the checkpoint is unfinished")
        r = run("tail", "--resume", part, "--out", part, "--quiet")
        check(r.returncode == 0, f"--resume finishes ({r.stderr.strip()})")
        check(results(part) == results(whole), "resumed: the uninterrupted result, bit for bit")
    r = run("tail", "--resume", whole, "--out", os.path.join(d, "again.json"))
    check(r.returncode != 0 and "already finished" in r.stderr, "a finished file is not resumed")

    # The comparison with a run of the same process (q = 16): the brute-force P at the same levels.
    runfile = os.path.join(d, "run.json")
    r = run("run", "--M", "16", "--T", "200000", "--out", runfile, "--quiet")
    check(r.returncode == 0, "a brute-force run")
    cmp = os.path.join(d, "cmp.csv")
    r = run("tail", *SMALL, "--out", os.path.join(d, "t2.json"), "--compare", runfile, "--compare-csv", cmp)
    check(r.returncode == 0 and "against brute force" in r.stdout, f"--compare prints the comparison ({r.stderr.strip()})")
    rows = list(csv.DictReader(l for l in open(cmp) if not l.startswith("#")))
    check(len(rows) == 6 and all(float(row["brute_P"]) > 0 for row in rows[:3]), "brute-force P at the levels")
    other_q = os.path.join(d, "q8.json")
    run("run", "--M", "4", "--subsets", "4", "--T", "1000", "--q", "8", "--out", other_q, "--quiet")
    r = run("tail", *SMALL, "--out", os.path.join(d, "t3.json"), "--compare", other_q)
    check(r.returncode != 0 and "q differs" in r.stderr and not os.path.exists(os.path.join(d, "t3.json")),
          "a run of another process is refused before any work")

    r = run("tail", "--print-levels", "--first", "1000", "--t-max", "1e7")
    lines = r.stdout.split("\n")
    check(r.returncode == 0 and lines[1:4] == ["1008", "2160", "4672"] and r.stdout.split()[-1] == "10095312",
          f"--print-levels ({lines[:4]})")

    # Bad input: one line "ERROR: ...", non-zero exit, nothing written.
    bad = os.path.join(d, "bad")
    os.makedirs(bad)
    target = os.path.join(bad, "t.json")
    for args, mention in [
        (["--population", "1"], "population = 1 must lie in [2, 1000000]"),
        (["--population", "2.5"], "--population = 2.5 must be an integer"),
        (["--replicas", "0"], "replicas = 0 must lie in [1, 4096]"),
        (["--t-max", "nan"], "--t-max = nan must be an integer"),
        (["--t-max", "-5"], "--t-max = -5 must be an integer"),
        (["--first", "0"], "first = 0 must lie in [1, "),
        (["--first", "1e8", "--t-max", "1e7"], "first = 100000000 must lie in [1, 10000000]"),
        (["--epsilon", "0"], "epsilon = 0 must lie in [1, 1099511627776]"),
        (["--epsilon", "1e300"], "--epsilon = 1e300 must be an integer"),
        (["--level-bins", "0"], "level-bins = 0 must lie in [1, 300]"),
        (["--clones", "magic"], "--clones 'magic' must be perturb or metropolis"),
        (["--min-ancestors", "0"], "min-ancestors = 0 must lie in [1, "),
        (["--population", "100000", "--replicas", "1000"], "walkers exceeds the limit"),
        (["--Xr", "2"], "Xr"),
        (["--K", "nan"], "--K = nan"),
        (["--compare-csv", os.path.join(bad, "c.csv")], "--compare-csv needs --compare"),
        (["--compare", os.path.join(bad, "missing.json")], "missing.json"),
        (["--resume", os.path.join(bad, "missing.json")], "missing.json"),
        (["--resume", out, "--K", "0.2"], "--resume takes the spec from the tail file; do not also give --K"),
        (["--resume", out, "--population", "5"], "do not also give --population"),
        (["--threads", "-1"], "threads = -1 must lie in [0, 256]"),  # the one table's rule and words (issue 35)
        (["--kernel", "quantum"], "quantum"),
        (["--slice", "3/3"], "--slice '3/3' must be I/N, whole numbers with I < N <= R = 3"),
        (["--slice", "0/4"], "--slice '0/4' must be I/N"),
        (["--slice", "0/0"], "--slice '0/0' must be I/N"),
        (["--slice", "-1/2"], "--slice"),
        (["--slice", "1/nan"], "--slice"),
        (["--slice", "1"], "--slice"),
        (["--resume", out, "--slice", "0/2"], "--resume takes the slice from the tail file; do not also give --slice"),
    ]:
        r = run("tail", *(args if "--resume" in args else small_with(args)), "--out", target)
        lines = r.stderr.strip().splitlines()
        check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0]
              and not os.path.exists(target), f"{' '.join(args)[:60]} -> {lines[:1]}")
    r = run("tail", *SMALL, "--out", os.path.join(d, "no-such-folder", "t.json"))
    check(r.returncode != 0 and r.stderr.startswith("ERROR: ") and len(r.stderr.strip().splitlines()) == 1,
          f"an unwritable --out is one ERROR before any work ({r.stderr.strip()})")
    # --slice I/N: the slices' tail files merge to the one-process run, bit for bit (steps included).
    slices = [os.path.join(d, f"slice{i}.json") for i in range(3)]
    for i in (2, 0, 1):
        r = run("tail", *SMALL, "--slice", f"{i}/3", "--out", slices[i])
        check(r.returncode == 0 and "merge the slices" in r.stderr, f"--slice {i}/3 ({r.stderr.strip()[-120:]})")
    check([json.load(open(f))["state"]["first_replica"] for f in slices] == [0, 1, 2]
          and all(len(json.load(open(f))["state"]["replicas"]) == 1 for f in slices), "each slice holds its replica")
    merged = os.path.join(d, "merged.json")
    r = run("merge", slices[2], slices[0], slices[1], "--out", merged)
    check(r.returncode == 0 and results(merged) == results(out), f"the merged slices are the whole run ({r.stderr.strip()})")
    for parts, mention in [([slices[0], slices[1]], "replicas [2, 3) are in no slice"),
                           ([slices[0], slices[0], slices[1], slices[2]], "give each input once"),
                           ([slices[1], slices[2]], "no slice holds replica 0"),
                           ([out, slices[1]], "overlaps"),
                           ([slices[0], os.path.join(d, "tail.csv")], "tail.csv")]:
        target = os.path.join(bad, "m.json")
        r = run("merge", *parts, "--out", target)
        lines = r.stderr.strip().splitlines()
        check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0]
              and not os.path.exists(target), f"merge {[os.path.basename(x) for x in parts]} -> {lines[:1]}")
    other = os.path.join(d, "other-slice.json")
    run("tail", *small_with(["--seed", "2"]), "--slice", "1/3", "--out", other)
    r = run("merge", slices[0], other, slices[2], "--out", os.path.join(bad, "m.json"))
    check(r.returncode != 0 and "another sampler run" in r.stderr, f"slices of another seed are refused ({r.stderr.strip()})")
    # An edited tail file is refused.
    text = open(out).read().replace('"population": 20', '"population": 21', 1)
    edited = os.path.join(d, "edited.json")
    open(edited, "w").write(text)
    r = run("tail", "--resume", edited, "--out", os.path.join(d, "e2.json"))
    check(r.returncode != 0 and "checksum" in r.stderr, f"an edited tail file is refused ({r.stderr.strip()})")
    check(not leftovers(d) and not leftovers(bad), "no temporaries or locks left behind")

finish()
