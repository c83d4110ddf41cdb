#!/usr/bin/env python3
"""archipelago-cli periodic, end to end (issue 7): the period-138 chain of Karney (1983) §6, and bad input."""
import math

from clitest import check, finish, parse_report as parse, run

K = 0.1
# §6: a chain of order 6 x 23 = 138, one member at x + sqrt K ~ 0.352, y ~ 0.034.
r = run("periodic", "--K", "0.1", "--period", "138", "--near", "0.0358,0.034")
check(r.returncode == 0, f"periodic 138 exits 0 ({r.stderr.strip()})")
header, rows = parse(r.stdout)
check(header.get("period") == "138", f"period 138 reported ({header.get('period')})")
check(len(rows) == 138, f"138 points printed ({len(rows)})")
residue = float(header.get("residue", "nan"))
check(0 < residue < 1, f"residue {residue} in (0, 1)")
check(header.get("stable", "").startswith("yes"), f"reported stable ({header.get('stable')})")
check("23/138" in header.get("rotation_number", ""), f"rotation number 23/138 ({header.get('rotation_number')})")
check(header.get("inside_box", "").startswith("yes"), "orbit inside the default box")
if rows:
    x0, y0 = float(rows[0]["x"]), float(rows[0]["y"])
    check(abs(x0 + math.sqrt(K) - 0.352) < 1e-3 and abs(y0 - 0.034) < 1e-3,
          f"first point ({x0:.6f}, {y0:.6f}) is the member near x + sqrt K = 0.352, y = 0.034")
    # Consecutive points are images under Q (y' = y + 2(x^2 - K), x' = x + y'), cyclically.
    worst = 0.0
    for k, row in enumerate(rows):
        x, y = float(row["x"]), float(row["y"])
        yn = y + 2 * (x * x - K)
        xn = x + yn
        nxt = rows[(k + 1) % len(rows)]
        worst = max(worst, abs(xn - float(nxt["x"])), abs(yn - float(nxt["y"])))
    check(worst < 1e-13, f"points map to their successors under Q (max error {worst:.2g})")

# The central fixed point: R = sqrt K.
r = run("periodic", "--K", "0.1", "--period", "1", "--near=-0.32,0.001")
header, rows = parse(r.stdout)
check(r.returncode == 0 and abs(float(header.get("residue", "nan")) - math.sqrt(K)) < 1e-15,
      f"central fixed point has residue sqrt K ({header.get('residue')})")

check(header.get("class") == "elliptic" and header.get("stable") == "yes (elliptic, 0 < R < 1)"
      and "(linear, at the central fixed point)" in header.get("rotation_number", ""),
      f"central fixed point is elliptic with its linear rotation number ({header.get('rotation_number')})")

# Regression (issue #11 item 9): at K = 0 the fixed point x = y = 0 has R = 0 (the tangent bifurcation of §2).  It
# was reported as "hyperbolic with reflection, R >= 1" with rotation number "nan = 0/1"; it is parabolic, 0 = 0/1.
r = run("periodic", "--K", "0", "--period", "1", "--near=0,0")
header, rows = parse(r.stdout)
check(r.returncode == 0 and float(header.get("residue", "nan")) == 0, f"K = 0 fixed point has R = 0 ({r.stderr.strip()})")
check(header.get("class") == "parabolic" and header.get("stable") == "no (parabolic, R = 0)",
      f"R = 0 is reported as parabolic (class {header.get('class')}, stable {header.get('stable')})")
check(header.get("rotation_number", "").startswith("0 = 0/1 ") and "nan" not in r.stdout.lower(),
      f"its rotation number is 0 = 0/1, never nan ({header.get('rotation_number')})")

# Bad input: one clear line, non-zero exit, no crash.
for args, mention in [
    (["periodic", "--period", "0", "--near", "0,0"], "period = 0 must lie in [1, 100000]"),
    (["periodic", "--period", "6", "--near", "0.05"], "--near '0.05' must be two finite numbers x,y"),
    (["periodic", "--period", "6", "--near", "a,b"], "--near 'a,b'"),
    (["periodic", "--period", "6"], "--near is required"),
    (["periodic", "--period", "6", "--near", "0.05,0.1", "--radius", "-1"], "search radius"),
    (["periodic", "--K", "nan", "--period", "6", "--near", "0.05,0.1"], "K = nan must be a finite number"),
    (["periodic", "--xmin", "-0.2", "--period", "6", "--near", "0.05,0.1"], "must be < −√K"),
    (["periodic", "--period", "6", "--near", "5,5"], "no periodic orbit of period 6 found near (5, 5)"),
]:
    r = run(*args)
    lines = r.stderr.strip().splitlines()
    check(r.returncode > 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0],
          f"{' '.join(args)} -> {r.returncode}: {r.stderr.strip()}")

finish()
