#!/usr/bin/env python3
"""archipelago-cli manifold and flux, end to end (issue 28): the flux by both methods at K = 0.05, 0.1, 0.2 checked
against an independent action sum in Python, the CSV of a branch (header, columns, invariance under the map,
atomic write), the Kac option, and hostile input (one ERROR line, non-zero exit)."""
import json
import math
import os
import stat
import tempfile
import time

from clitest import check, finish, leftovers, parse_report, run


def step(K, x, y):
    y = y + 2 * (x * x - K)
    return x + y, y


def inverse_step(K, x, y):
    x = x - y
    return x, y - 2 * (x * x - K)


def direct_action(K, x, y):
    """ΔW of the orbit through (x, y) homoclinic to (√K, 0) by iterating Q forward and Q⁻¹ backward in double with
    L(x, x') = (x' − x)²/2 + (2/3)x³ − 2Kx (core/manifolds/GeneratingFunction.hpp), until the orbit is within 1e-7 of
    the fixed point (terms ~1e-14; past that, double's rounding amplified by λ^t would take over)."""
    r = math.sqrt(K)
    L = lambda a, b: (b - a) ** 2 / 2 + 2 * a ** 3 / 3 - 2 * K * a
    ref = L(r, r)
    total = 0.0
    for forward in (True, False):
        px, py = x, y
        for _ in range(60):
            nx, ny = step(K, px, py) if forward else inverse_step(K, px, py)
            total += (L(px, nx) if forward else L(nx, px)) - ref
            px, py = nx, ny
            if math.hypot(px - r, py) < 1e-7:
                break
    return total


# --- flux --json at the three K --------------------------------------------------------------------------
for K in ("0.05", "0.1", "0.2"):
    t0 = time.monotonic()
    r = run("flux", "--K", K, "--json")
    seconds = time.monotonic() - t0
    check(r.returncode == 0, f"flux --K {K} --json exits 0 ({r.stderr.strip()})")
    doc = json.loads(r.stdout)
    lobe, zone = doc["lobe_area"], doc["zone_area"]
    digits = -math.log10(abs(lobe["action"] - lobe["polygon"]) / lobe["action"]) if lobe["action"] != lobe["polygon"] else 17
    check(digits >= 9, f"K = {K}: lobe area by action {lobe['action']:.16g} and polygon {lobe['polygon']:.16g} agree to "
                       f"{digits:.1f} >= 9 digits (reported {lobe['agreeing_digits']})")
    check(zone["action"] > 0 and abs(zone["action"] - zone["polygon"]) <= 1e-12 * zone["action"],
          f"K = {K}: zone area {zone['action']:.16g} by both methods")
    # Independent: the actions of the two printed homoclinic points by direct iteration (double precision; the
    # action is stationary on orbits, so the points' rounding enters squared; ~1e-15 absolute per action).
    h = doc["homoclinic_points"]
    w = [direct_action(float(K), *p["point"]) for p in h]
    check(abs(abs(w[0] - w[1]) - lobe["action"]) <= 1e-12,
          f"K = {K}: |ΔW(h) − ΔW(h')| by direct iteration {abs(w[0] - w[1]):.15g} equals the lobe area")
    check(abs(w[0] - zone["action"]) <= 1e-12, f"K = {K}: ΔW(h) by direct iteration {w[0]:.15g} equals the zone area")
    check(h[0]["symmetry_line"].startswith("S1") and h[1]["symmetry_line"].startswith("S2") and
          abs(h[1]["point"][1]) < 1e-15, f"K = {K}: homoclinic points on S1 and S2 (y = 0)")
    print(f"     flux --K {K} --json took {seconds:.3f} s (whole process)")

# Human-readable form, and --out writes the same JSON atomically.
with tempfile.TemporaryDirectory() as d:
    out = os.path.join(d, "flux.json")
    r = run("flux", "--K", "0.1", "--out", out)
    header, _ = parse_report(r.stdout)
    check(r.returncode == 0 and "lobe_area_action" in header and "zone_area_polygon" in header,
          f"flux prints '# key: value' lines ({r.stderr.strip()})")
    doc = json.loads(open(out).read()) if os.path.exists(out) else {}
    check(abs(doc.get("lobe_area", {}).get("action", 0) - float(header.get("lobe_area_action", "nan"))) < 1e-18,
          "--out holds the same lobe area as the text")
    check(leftovers(d) == [], "no temporary files left")

# The period-6 chain's outer separatrix: two heteroclinic points, both methods agree.
r = run("flux", "--K", "0.1", "--period", "6", "--near", "0.0157,0", "--json")
doc = json.loads(r.stdout) if r.returncode == 0 else {}
check(r.returncode == 0 and len(doc.get("heteroclinic_points", [])) == 2 and doc["orbit"]["period"] == 6,
      f"flux of the period-6 chain ({r.stderr.strip()})")
if doc:
    check(doc["lobe_area"]["agreeing_digits"] == "all" or doc["lobe_area"]["agreeing_digits"] >= 9,
          f"period 6: lobe {doc['lobe_area']['action']:.6g}, {doc['lobe_area']['agreeing_digits']} digits")

# A point inside one of the six islands gives the chain's hyperbolic partner.
r = run("flux", "--K", "0.1", "--period", "6", "--near=-0.602,-0.262", "--radius", "0.05", "--json")
check(r.returncode == 0 and abs(json.loads(r.stdout)["lobe_area"]["action"] - doc.get("lobe_area", {}).get("action", -1)) < 1e-15,
      f"--near inside an island finds the same separatrix ({r.stderr.strip()})")

# --kac: both sides of the Kac identity with errors (small here; scripts/kac-check.sh measures the full size).
r = run("flux", "--K", "0.2", "--kac", "--kac-samples", "2000", "--kac-zone-samples", "2000", "--kac-steps", "1000",
        "--threads", "2", "--json")
kac = json.loads(r.stdout).get("kac", {}) if r.returncode == 0 else {}
check(kac and kac["inconsistent_orbits"] == 0 and abs(kac["discrepancy_sigmas"]) < 4,
      f"--kac at K = 0.2: residence {kac.get('mean_residence')} +- {kac.get('mean_residence_error')} vs transit/flux "
      f"{kac.get('transit_area_over_flux')} +- {kac.get('transit_area_over_flux_error')}")

# --- manifold CSV -----------------------------------------------------------------------------------------------
with tempfile.TemporaryDirectory() as d:
    out = os.path.join(d, "m.csv")
    r = run("manifold", "--K", "0.1", "--branch", "unstable", "--length", "3", "--out", out)
    check(r.returncode == 0 and os.path.exists(out), f"manifold --out writes the CSV ({r.stderr.strip()})")
    text = open(out).read() if os.path.exists(out) else ""
    header, rows = parse_report(text)
    check(header.get("K") == "0.1000000000000000055511151231257827" or header.get("K", "").startswith("0.1000000000"),
          f"header carries K ({header.get('K')})")
    for key in ("branch", "side", "length_requested", "spacing", "angle", "points", "stopped_by", "origin", "map"):
        check(key in header, f"header carries {key}")
    check(text.splitlines()[len([l for l in text.splitlines() if l.startswith('#')])] == "s,x,y" or "s,x,y" in text,
          "columns s,x,y")
    check(len(rows) == int(header.get("points", -1)), f"{len(rows)} rows = points")
    pts = [(float(r_["s"]), float(r_["x"]), float(r_["y"])) for r_ in rows]
    check(abs(pts[0][1] - math.sqrt(0.1)) < 1e-15 and pts[0][0] == 0, "starts at (√K, 0) with s = 0")
    check(all(b[0] >= a[0] for a, b in zip(pts, pts[1:])), "s increases")
    check(float(header["length"]) >= 3, "reaches the requested length")
    # Invariance: the image of a point lies on the drawn curve (within spacing·angle/4 = 5e-5, ManifoldCurve.hpp),
    # for points whose image is still within the drawn length.
    K = 0.1
    worst = 0.0
    seg = [(pts[i][1], pts[i][2], pts[i + 1][1], pts[i + 1][2]) for i in range(len(pts) - 1)]
    for s_, x, y in pts[::40]:
        if s_ < 0.05 or s_ > 1.0:
            continue
        X, Y = step(K, x, y)
        best = min(math.hypot(X - min(max(X, min(a, c)), max(a, c)) if a == c else
                              (X - (a + max(0.0, min(1.0, ((X - a) * (c - a) + (Y - b) * (e - b)) / ((c - a) ** 2 + (e - b) ** 2))) * (c - a))),
                              Y - (b + max(0.0, min(1.0, ((X - a) * (c - a) + (Y - b) * (e - b)) / ((c - a) ** 2 + (e - b) ** 2))) * (e - b)))
                   for a, b, c, e in seg)
        worst = max(worst, best)
    check(worst <= 2e-3 * 0.1 / 4, f"images of drawn points lie on the drawn curve (worst {worst:.2g})")
    check(leftovers(d) == [], "no temporary files left")

r = run("manifold", "--K", "0.1", "--branch", "stable", "--length", "2", "--box")
header, rows = parse_report(r.stdout)
check(r.returncode == 0 and header.get("branch") == "stable" and header.get("map", "").startswith("Q* in the box"),
      f"stable branch of Q* on stdout ({r.stderr.strip()})")
check(rows and all(-0.8 <= float(x["x"]) < 0.5 and -0.65 <= float(x["y"]) < 0.65 for x in rows), "all points in the box")

r = run("manifold", "--K", "0.1", "--period", "6", "--near", "0.0157,0", "--point", "2", "--length", "0.5")
header, rows = parse_report(r.stdout)
check(r.returncode == 0 and header.get("period") == "6" and header.get("side") == "outward" and rows,
      f"a branch of the period-6 orbit ({r.stderr.strip()})")

# --- hostile input: one ERROR line, non-zero exit ------------------------------------------------------------------
readonly_dir = tempfile.mkdtemp()
readonly_file = os.path.join(readonly_dir, "ro.csv")
open(readonly_file, "w").close()
os.chmod(readonly_file, stat.S_IRUSR)
cases = [
    (["flux", "--K", "nan"], "--K = nan"),
    (["flux", "--K", "inf"], "--K = inf"),
    (["flux", "--K", "1e300"], "K = 1e+300 must be a number in (0, 1]"),
    (["flux", "--K", "-0.1"], "must be a number in (0, 1]"),
    (["flux", "--K", "0"], "must be a number in (0, 1]"),
    (["flux", "--period", "6"], "--near x,y is required"),
    (["flux", "--period", "0"], "period = 0 must lie in [1, 2000]"),
    (["flux", "--period", "2.5", "--near", "0,0"], "--period = 2.5"),
    (["flux", "--period", "100000", "--near", "0,0"], "period = 100000 must lie in [1, 2000]"),
    (["flux", "--period", "6", "--near", "0.05"], "--near '0.05'"),
    (["flux", "--period", "6", "--near", "nan,0"], "--near 'nan,0'"),
    (["flux", "--period", "6", "--near", "a,b"], "--near 'a,b'"),
    (["flux", "--period", "6", "--near", "5,5"], "no hyperbolic periodic orbit"),
    (["flux", "--side", "up"], "--side 'up'"),
    (["flux", "--vertices", "2"], "vertices per arc"),
    (["flux", "--kac", "--kac-samples", "0"], "entry samples = 0"),
    (["flux", "--kac", "--kac-steps", "-5"], "--kac-steps = -5"),
    (["flux", "--out", "/nonexistent-folder/f.json"], "/nonexistent-folder"),
    (["flux", "--out", readonly_dir], readonly_dir),
    (["manifold", "--K", "nan"], "--K = nan"),
    (["manifold", "--K", "2"], "must be a number in (0, 1]"),
    (["manifold", "--length", "-1"], "length = -1"),
    (["manifold", "--length", "nan"], "--length = nan"),
    (["manifold", "--length", "1e300"], "length = 1e+300"),
    (["manifold", "--branch", "sideways"], "branch 'sideways' must be stable or unstable"),
    (["manifold", "--stable-from", "magic"], "stable_from 'magic' must be inverse or symmetry"),
    (["manifold", "--spacing", "0"], "spacing = 0"),
    (["manifold", "--angle", "-1"], "angle = -1"),
    (["manifold", "--domains", "0"], "domains = 0"),
    (["manifold", "--max-points", "3"], "maximum points = 3"),
    (["manifold", "--view", "1,0,0,1"], "the view must have finite bounds"),
    (["manifold", "--view", "0,1,0"], "--view '0,1,0'"),
    (["manifold", "--point", "3"], "point = 3 must lie in [0, 0]"),
    (["manifold", "--box", "--xmin", "-0.2"], "xmin"),
    (["manifold", "--box", "--xmax", "0.2"], "outside the box"),
    (["manifold", "--out", "/nonexistent-folder/m.csv"], "/nonexistent-folder"),
    (["manifold", "--out", readonly_file], readonly_file),
]
for args, mention in cases:
    t0 = time.monotonic()
    r = run(*args, timeout=600)
    lines = r.stderr.strip().splitlines()
    check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0]
          and time.monotonic() - t0 < 30,
          f"{' '.join(args)} -> {lines}")
check(os.listdir(readonly_dir) == ["ro.csv"], "nothing written beside a refused target")
os.chmod(readonly_file, stat.S_IRUSR | stat.S_IWUSR)
finish()
