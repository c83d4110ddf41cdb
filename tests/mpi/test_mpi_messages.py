#!/usr/bin/env python3
"""Issue 36 class 7: archipelago-mpi's command-line errors (tail's options, --resume of a file that is not there,
an unknown option) were CLI11's message over several lines with its banner and no "ERROR:"; they are one
"ERROR: …" line, as archipelago-cli prints them (cli::parseErrorStatus, shared), and a non-zero status.
Issue 39, deliverable 4: core's warning that the box cuts the central island (K = 0.3 in the default box), which
`archipelago-cli run` and `tail` print once, was missing from `archipelago-mpi run` and printed once per rank by
`archipelago-mpi tail`: rank 0 prints it once, in both.
Issue 54, finding 8: under mpirun, MPI's banner followed the ERROR line (Open MPI's "mpirun detected that one or more
processes exited with non-zero status" block, or MPI_Abort's "MPI_ABORT was invoked"): on two ranks, a bad value, a
run that cannot start and a resume of a file that is not there, of run and of tail, print the ERROR line and nothing
else, with a non-zero status."""
import subprocess

from mpitest import check, env, error_lines, finish, launcher, p

CASES = [
    ("tail --population abc", ["tail", "--population", "abc"], "--population"),
    ("tail --bogus", ["tail", "--bogus"], "--bogus"),
    ("--resume of a file that is not there", ["--resume", p("missing.ckpt")], "missing.ckpt"),
    ("--bogus", ["--bogus"], "--bogus"),
]
for what, args, words in CASES:
    r = subprocess.run(launcher(1, *args), capture_output=True, text=True, timeout=120, env=env)
    ours = [l for l in r.stderr.splitlines() if "--help" in l or l.startswith("ERROR")]
    check(r.returncode != 0 and len(error_lines(r)) == 1 and words in error_lines(r)[0] and len(ours) == 1,
          f"{what}: one ERROR line naming {words}: " + r.stderr.strip()[-400:])

# Nothing after the ERROR line, on two ranks (the launcher's own lines included): run and tail.
for what, args in [("run --K nan", ["--K", "nan"]),
                   ("run --resume of a file that is not there", ["--resume", p("missing.ckpt")]),
                   ("tail --K nan", ["tail", "--K", "nan"]),
                   ("tail --resume of a file that is not there", ["tail", "--resume", p("missing.json")]),
                   ("tail whose first level is out of reach", ["tail", "--first", "1e7", "--t-max", "1e7",
                                                                "--population", "16", "--quiet", "--out", p("far.json")])]:
    r = subprocess.run(launcher(2, *args), capture_output=True, text=True, timeout=300, env=env)
    lines = (r.stdout + r.stderr).splitlines()
    check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: "),
          f"{what} on two ranks: the ERROR line alone (status {r.returncode}): " + (r.stdout + r.stderr).strip()[-600:])

# The box warning: once with two ranks (run printed none, tail one per rank), none at K = 0.1.
warning = "WARNING: the box does not hold the central island at K = 0.3"
short = ["--T", "200", "--M", "8", "--subsets", "4", "--quiet"]
for what, args in [("run", ["--q", "16", *short]),
                   ("tail", ["tail", "--first", "100", "--t-max", "1000", "--population", "16", "--quiet"])]:
    for K, count in (("0.3", 1), ("0.1", 0)):
        r = subprocess.run(launcher(2, *args, "--K", K, "--out", p(f"box-{what}-{K}.json")), capture_output=True,
                           text=True, timeout=600, env=env)
        check(r.returncode == 0 and r.stderr.count(warning[:40]) == count,
              f"{what} --K {K} on two ranks: the box warning {count} time(s) ({r.returncode}: {r.stderr.strip()[-400:]})")
finish()
