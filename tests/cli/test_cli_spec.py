#!/usr/bin/env python3
"""archipelago-cli presets / run --preset / --spec / --print-spec: the run spec of core is the one codec the CLI
reads and writes (issue 11, item 1); a preset, a spec file and explicit options combine as documented."""
import json, os, tempfile

from clitest import check, finish, run

tmp = tempfile.mkdtemp(prefix="archipelago-cli-spec-")

r = run("presets")
ids = [line.split()[0] for line in r.stdout.splitlines()[1:] if line and not line.startswith(("run one", "edit one"))]
check(r.returncode == 0 and ids[:5] == ["k0.1-minute", "k0.1-paper-fig6", "small-k-negative", "small-k-zero",
                                        "small-k-positive"], f"presets lists the paper's cases ({ids})")

r = run("presets", "k0.1-paper-fig6")
spec = json.loads(r.stdout) if r.returncode == 0 else {}
p = spec.get("parameters", {})
check(spec.get("format") == "archipelago-spec" and p.get("M") == 1600 and p.get("q") * p.get("T") == 2_000_000_000,
      f"presets ID prints the paper's fig. 6 run as a spec: M = 1600, qT = 2e9 ({p})")

# Explicit options override the preset; --print-spec runs nothing and reads back to the same spec.
r = run("run", "--preset", "small-k-zero", "--M", "4", "--T", "3000", "--subsets", "2", "--longest", "5", "--print-spec")
spec = json.loads(r.stdout) if r.returncode == 0 else {}
p = spec.get("parameters", {})
check(p.get("K") == 0 and p.get("xmin") == -0.05 and p.get("q") == 1 and p.get("M") == 4 and p.get("T") == 3000
      and p.get("longestKept") == 5, f"--preset with overrides ({p})")
path = os.path.join(tmp, "spec.json")
open(path, "w").write(r.stdout)
r2 = run("run", "--spec", path, "--print-spec")
check(r2.returncode == 0 and r2.stdout == r.stdout, "a printed spec read back with --spec prints the same spec")

out = os.path.join(tmp, "run.json")
r = run("run", "--spec", path, "--seed", "9", "--out", out, "--quiet")
params = json.load(open(out))["parameters"] if r.returncode == 0 else {}
check(params.get("K") == 0 and params.get("M") == 4 and params.get("seed") == 9,
      f"run --spec runs the spec, with --seed on top ({r.stderr.strip()} {params})")

# A hand-written spec may leave parameters out (documented defaults), never misspell one.
partial = os.path.join(tmp, "partial.json")
open(partial, "w").write('{"format": "archipelago-spec", "version": 1, "parameters": {"K": 0.2, "xmin": -1}}')
r = run("run", "--spec", partial, "--print-spec")
p = json.loads(r.stdout)["parameters"] if r.returncode == 0 else {}
check(p.get("K") == 0.2 and p.get("xmin") == -1 and p.get("xmax") == 0.5, f"a partial spec takes the defaults ({p})")

typo = os.path.join(tmp, "typo.json")
open(typo, "w").write('{"format": "archipelago-spec", "version": 1, "parameters": {"Kk": 0.2}}')
cases = [
    (["run", "--preset", "nope"], "not a preset"),
    (["run", "--preset", "small-k-zero", "--spec", path], "not both"),
    (["run", "--spec", typo], "unknown parameter 'Kk'"),
    (["run", "--spec", tmp], "it is a folder"),
    (["run", "--spec", os.path.join(tmp, "missing.json")], "missing.json"),
    (["run", "--preset", "small-k-zero", "--q", "0"], "q = 0 must lie in [1, 65536]"),
    (["run", "--preset", "small-k-zero", "--q", "70000"], "q = 70000 must lie in [1, 65536]"),
    (["run", "--longest", "4294967295", "--print-spec"], "longestKept = 4294967295 must lie in [0, 100000]"),
    (["run", "--resume", out, "--preset", "small-k-zero"], "do not also give --preset"),
    (["presets", "nope"], "no preset 'nope'"),
]
for args, mention in cases:
    r = run(*args)
    lines = r.stderr.strip().splitlines()
    check(r.returncode > 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0],
          f"{' '.join(args)} -> {r.returncode}: {r.stderr.strip()}")
finish()
