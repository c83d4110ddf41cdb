#!/usr/bin/env python3
"""Issue 39, deliverable 4: `run` and `tail` warn when the box or its randomizing zone cuts the central island.
K = 0.3 in the paper's K = 0.1 box (-0.8, 0.5) is the case found (a longest segment of 192 steps): the run goes
on and says so, in core's words (checkBoxAgainstIsland); K = 0.1 in the same box, and K = 0.3 in the K scan's box,
say nothing.  The same text is Python's warning (tests/python)."""
import os, tempfile

from clitest import check, finish, run

tmp = tempfile.mkdtemp(prefix="archipelago-cli-box-island-")
short = ["--q", "16", "--T", "2000", "--M", "8", "--subsets", "4", "--quiet"]
expected = "WARNING: the box does not hold the central island at K = 0.3"

r = run("run", "--K", "0.3", *short, "--out", os.path.join(tmp, "k03.json"))
check(r.returncode == 0, f"run --K 0.3 runs ({r.stderr.strip()})")
check(expected in r.stderr, f"run --K 0.3 in the default box warns ({r.stderr.strip()})")
check("randomizing zone" in r.stderr and "reaches" in r.stderr, "the warning says the randomizing zone reaches into it")
check(r.stderr.count("WARNING:") == 1, "one warning")

r = run("run", "--K", "0.1", *short, "--out", os.path.join(tmp, "k01.json"))
check(r.returncode == 0 and "central island" not in r.stderr, f"run --K 0.1 in the default box does not warn ({r.stderr.strip()})")

# The K scan's box at K = 0.3 (xmin = -2 sqrt(K) - 0.2, xmax = sqrt(K) + 0.2) holds the island.
r = run("run", "--K", "0.3", "--xmin=-1.2954", "--xmax", "0.7477", *short, "--out", os.path.join(tmp, "wide.json"))
check(r.returncode == 0 and "central island" not in r.stderr, f"run --K 0.3 in the scan's box does not warn ({r.stderr.strip()})")

# tail: the same words (--print-levels: the spec is resolved, nothing is sampled).
r = run("tail", "--K", "0.3", "--print-levels", "--first", "100", "--t-max", "1000")
check(expected in r.stderr, f"tail --K 0.3 warns ({r.returncode}: {r.stderr.strip()})")
r = run("tail", "--K", "0.1", "--print-levels", "--first", "100", "--t-max", "1000")
check(r.returncode == 0 and "central island" not in r.stderr, f"tail --K 0.1 does not warn ({r.stderr.strip()})")

finish()
