#!/usr/bin/env python3
"""archipelago-cli orbit, end to end (issue 2's acceptance check, plus bad input)."""
import csv, io, math

from clitest import check, finish, run

# The orbit started on the elliptic fixed point (-sqrt K, 0) stays within 1e-12 of it for 1000 steps.
x0 = -0.31622776601683794
for direction in ([], ["--backward"]):
    r = run("orbit", "--K", "0.1", "--xmin", "-0.8", "--xmax", "0.5", "--x", repr(x0), "--y", "0",
            "--steps", "1000", *direction)
    check(r.returncode == 0, f"orbit {direction} exits 0 ({r.stderr.strip()})")
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    check(len(rows) == 1001, f"orbit {direction} prints 1001 rows")
    dist = max(math.hypot(float(row["x"]) - x0, float(row["y"])) for row in rows)
    check(dist < 1e-12, f"orbit {direction} stays within 1e-12 of the elliptic fixed point (max {dist:.3g})")

# Forward then backward from the last point returns exactly to the start (one-to-one map).
r = run("orbit", "--x", "0.1", "--y", "0.05", "--steps", "500")
last = list(csv.DictReader(io.StringIO(r.stdout)))[-1]
first = list(csv.DictReader(io.StringIO(r.stdout)))[0]
r2 = run("orbit", "--x", last["x"], "--y", last["y"], "--steps", "500", "--backward")
back = list(csv.DictReader(io.StringIO(r2.stdout)))[-1]
check((back["X"], back["Y"]) == (first["X"], first["Y"]), "500 steps of N then N^-1 return bit for bit")

# Bad input: one clear line, non-zero exit, no crash.
for args, mention in [
    (["orbit", "--K", "0.1", "--xmin", "-0.2", "--x", "0", "--y", "0"], "must be < −√K"),
    (["orbit", "--K", "nan", "--x", "0", "--y", "0"], "K = nan must be a finite number"),
    (["orbit", "--x", "0"], "--y is required"),
    (["orbit", "--x", "zero", "--y", "0"], "--x"),
    (["orbit", "--bogus", "--x", "0", "--y", "0"], "--bogus"),
    (["frobnicate"], "frobnicate"),
]:
    r = run(*args)
    lines = r.stderr.strip().splitlines()
    check(r.returncode not in (0,) and r.returncode > 0 and len(lines) == 1 and lines[0].startswith("ERROR: ")
          and mention in lines[0], f"{' '.join(args)} -> {r.returncode}: {r.stderr.strip()}")

finish()
