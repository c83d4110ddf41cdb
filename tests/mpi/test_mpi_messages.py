#!/usr/bin/env python3
"""Issue 36 class 7: archipelago-mpi's command-line errors (tail's options, --resume of a file that is not there,
an unknown option) were CLI11's message over several lines with its banner and no "ERROR:"; they are one
"ERROR: …" line, as archipelago-cli prints them (cli::parseErrorStatus, shared), and a non-zero status."""
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
finish()
