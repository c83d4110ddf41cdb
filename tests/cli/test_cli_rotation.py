#!/usr/bin/env python3
"""archipelago-cli rotation, end to end (issue 27): one orbit's rotation number and island chain (text and --json),
the rotation profile along a segment (--line ... --csv), and bad input (one ERROR line each)."""
import csv, io, json, math, os, tempfile

from clitest import check, finish, parse_report, run

K = 0.1
ALPHA = math.acos(1 - 2 * math.sqrt(K)) / (2 * math.pi)  # §2: cos α = 1 − 2√K, α/2π = 0.1900993 at K = 0.1
P138 = (0.0360286533088399281481, 0.0341809124510989600403)  # `periodic --period 138 --near 0.0358,0.034 --stable`

# Next to the elliptic fixed point: α/2π (the quadratic twist at d = 1e-5 is 3e-11).
r = run("rotation", "--K", "0.1", f"--x={-math.sqrt(K) + 1e-5!r}", "--y", "0")
header, rows = parse_report(r.stdout)
check(r.returncode == 0, f"rotation near the centre exits 0 ({r.stderr.strip()})")
omega = float(header.get("rotation", "nan"))
check(abs(omega - ALPHA) < 1e-10, f"rotation {omega!r} = alpha/2pi = {ALPHA!r} to 1e-10")
check(header.get("verdict", "").startswith("regular"), f"regular ({header.get('verdict')})")
check(header.get("period") == "1" and header.get("chain", "").startswith("an invariant curve"),
      f"no chain about the centre ({header.get('chain')})")

# Next to the elliptic period-138 orbit (§6): 138 = 6 x 23.
r = run("rotation", "--x", repr(P138[0] + 1e-6), "--y", repr(P138[1]))
header, rows = parse_report(r.stdout)
check(r.returncode == 0, f"rotation next to the 138-orbit exits 0 ({r.stderr.strip()})")
check(header.get("period") == "138", f"period 138 ({header.get('period')})")
check(header.get("chain", "").startswith("6 × 23 = 138, rotation 1/6 about the centre, 2/23 about its island"),
      f"chain named ({header.get('chain')})")
check([row["rational"] for row in rows] == ["1/6", "2/23", ""], f"levels' rationals {[row['rational'] for row in rows]}")
check([row["sense"] for row in rows] == ["clockwise", "counter-clockwise", "clockwise"], "levels' senses")
if len(rows) == 3:
    R = float(rows[2]["residue"])
    nu = math.acos(1 - 2 * R) / (2 * math.pi)
    check(abs(float(rows[2]["rotation"]) - nu) < 1e-6,
          f"rotation of Q^138 about its orbit {rows[2]['rotation']} ~ nu(R) = {nu:.12f} (twist at 1e-6: 9e-8)")

# --json: the same numbers as the text.
r2 = run("rotation", "--x", repr(P138[0] + 1e-6), "--y", repr(P138[1]), "--json")
doc = json.loads(r2.stdout) if r2.returncode == 0 else {}
check(doc.get("chain", {}).get("period") == 138 and doc.get("chain", {}).get("factors") == [6, 23],
      f"--json: period 138 = 6 x 23 ({doc.get('chain', {}).get('factors')})")
check(doc.get("rotation") == float(header.get("rotation", "nan")), "--json and text give the same rotation")
check(doc.get("map", {}).get("coefficients", {}).get("A") == 2927339757790823, "--json carries the exact map")

# Chaotic and escaping orbits get a reason, never a number.
r = run("rotation", "--x", "0.3", "--y", "0.3", "--json")
doc = json.loads(r.stdout) if r.returncode == 0 else {}
check(doc.get("rotation") is None and doc.get("verdict") == "escaping", f"escaping: no number ({doc.get('verdict')})")
check("nan" not in r.stdout.lower(), "no nan in the JSON")
r = run("rotation", "--x", "0.3", "--y", "0.3")
header, _ = parse_report(r.stdout)
check(header.get("rotation", "").startswith("none (escaping)"), f"text: {header.get('rotation')}")

# A profile along y = 0 from the centre outwards: 0.19 decreasing, then the sea.
with tempfile.TemporaryDirectory() as d:
    path = os.path.join(d, "profile.csv")
    r = run("rotation", "--line=-0.3162,0:0.3,0", "--points", "60", "--iterations", "3000", "--csv", path, "--quiet")
    check(r.returncode == 0 and os.path.exists(path), f"profile written ({r.stderr.strip()})")
    lines = [l for l in open(path).read().splitlines() if not l.startswith("#")] if os.path.exists(path) else []
    table = list(csv.DictReader(io.StringIO("\n".join(lines))))
    check(len(table) == 60, f"60 rows ({len(table)})")
    regular = [float(t["rotation"]) for t in table if t["verdict"] == "regular"]
    check(len(regular) > 20 and abs(regular[0] - ALPHA) < 1e-6, f"starts at alpha/2pi ({regular[:1]})")
    check(all(t["rotation"] == "" for t in table if t["verdict"] != "regular"), "no number without a regular verdict")
    check("points=60" in r.stdout, f"summary line ({r.stdout.strip()})")

# Bad input: one clear line, non-zero exit, no crash.
with tempfile.TemporaryDirectory() as d:
    csv_path = os.path.join(d, "p.csv")
    for args, mention in [
        (["rotation", "--x", "0.1"], "give --x and --y"),
        (["rotation"], "give --x and --y"),
        (["rotation", "--x", "nan", "--y", "0"], "--x = nan must be a finite number"),
        (["rotation", "--x", "1e308", "--y", "0"], "must lie in the box"),
        (["rotation", "--x", "0.6", "--y", "0"], "must lie in the box"),
        (["rotation", "--x=-0.3", "--y", "0", "--iterations", "0"], "iterations = 0 must lie in [16, 10000000]"),
        (["rotation", "--x=-0.3", "--y", "0", "--iterations", "1.5"], "--iterations = 1.5 must be an integer"),
        (["rotation", "--x=-0.3", "--y", "0", "--iterations", "-1"], "--iterations = -1 must be an integer"),
        (["rotation", "--x=-0.3", "--y", "0", "--threshold", "17"], "digits threshold = 17 must lie in [0, 16]"),
        (["rotation", "--x=-0.3", "--y", "0", "--threshold", "inf"], "--threshold = inf must be a finite number"),
        (["rotation", "--x=-0.3", "--y", "0", "--max-period", "0"], "maxPeriod = 0 must lie in [1, 100000]"),
        (["rotation", "--K", "1.5", "--xmin", "-2", "--x=-0.3", "--y", "0"], "must lie in (0, 1)"),
        (["rotation", "--K", "-0.1", "--x=-0.3", "--y", "0"], "must lie in (0, 1)"),
        (["rotation", "--xmin", "-0.2", "--x=-0.3", "--y", "0"], "must be < −√K"),
        (["rotation", "--x=-0.3", "--y", "0", "--csv", csv_path], "--csv is for a profile"),
        (["rotation", "--line=-0.3,0:0.1,0"], "--line needs --csv"),
        (["rotation", "--line=-0.3,0:0.1,0", "--x", "0", "--y", "0", "--csv", csv_path], "not both"),
        (["rotation", "--line=-0.3,0,0.1,0", "--csv", csv_path], "--line '-0.3,0,0.1,0' must be two points"),
        (["rotation", "--line=nan,0:0.1,0", "--csv", csv_path], "must be two points"),
        (["rotation", "--line=-0.3,0:9,0", "--csv", csv_path], "to = (9, 0) must lie in the box"),
        (["rotation", "--line=-0.3,0:0.1,0", "--points", "0", "--csv", csv_path], "points = 0 must lie in [1, 1000000]"),
        (["rotation", "--line=-0.3,0:0.1,0", "--points", "4294967296", "--csv", csv_path], "--points = 4294967296"),
        (["rotation", "--line=-0.3,0:0.1,0", "--csv", os.path.join(d, "missing", "p.csv")], "p.csv"),
        (["rotation", "--line=-0.3,0:0.1,0", "--csv", d], d),
        (["rotation", "--line=-0.3,0:0.1,0", "--csv", csv_path, "--kernel", "nope"], "unknown kernel 'nope'"),
    ]:
        r = run(*args)
        lines = r.stderr.strip().splitlines()
        check(r.returncode > 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0],
              f"{' '.join(args)} -> {r.returncode}: {r.stderr.strip()}")
    check(os.listdir(d) == [], f"no file left behind by the refused calls ({os.listdir(d)})")

finish()
