"""Issue #26, done when: `stats LONG --short SHORT` on a q = 100 run with its q = 1 companion gives S_t ∝ t^{1.6–1.7}
over 10²–10⁴ steps (a log-uniform fit); without the companion the CSV marks t < 10 q and the slope is the block
artefact's (1.36–1.37 with 1.6·10¹⁰ steps in the issue, also by an independent implementation of the map).  The fit
is computed here, independently of core's LogFits: log S_t interpolated linearly in log t at 10 points a decade."""
import json, math, os, tempfile

from clitest import check, finish, run


def series(path):
    """(t, value, blocks_affected or None) rows of a statistics CSV file."""
    rows = []
    with open(path) as f:
        lines = [l.strip() for l in f if l.strip() and not l.startswith("#")]
    header = lines[0].split(",")
    for line in lines[1:]:
        cells = line.split(",")
        rows.append((float(cells[0]), float(cells[1]), cells[3] if len(header) > 3 else None))
    return header, rows


def slope(rows, a=1e2, b=1e4, per_decade=10):
    pts = [(math.log(t), math.log(v)) for t, v, _ in rows if t > 0 and v > 0]
    n = round(math.log10(b / a) * per_decade)
    sample = []
    for j in range(n + 1):
        x = math.log(a) + j * (math.log(b) - math.log(a)) / n
        for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
            if x0 <= x <= x1:
                sample.append((x, y0 + (x - x0) / (x1 - x0) * (y1 - y0)))
                break
    mx = sum(p[0] for p in sample) / len(sample)
    my = sum(p[1] for p in sample) / len(sample)
    return sum((x - mx) * (y - my) for x, y in sample) / sum((x - mx) ** 2 for x, _ in sample)


with tempfile.TemporaryDirectory() as d:
    spec = os.path.join(d, "q100.spec.json")
    with open(spec, "w") as f:  # the paper's K = 0.1 box; 10⁹ steps of q = 100 and a companion of a tenth of them
        json.dump({"format": "archipelago-spec", "version": 1, "companion": 0.1,
                   "parameters": {"K": 0.1, "xmin": -0.8, "xmax": 0.5, "Xr": 0.02, "q": 100, "T": 78125, "M": 128,
                                  "seed": 12, "subsets": 16}}, f)
    out = os.path.join(d, "q100.json")
    r = run("run", "--spec", spec, "--out", out, "--quiet")
    check(r.returncode == 0 and os.path.exists(os.path.join(d, "q100.short.json")),
          f"run writes the run and its companion ({r.returncode}: {r.stderr.strip()[-200:]})")
    spliced, alone = os.path.join(d, "spliced"), os.path.join(d, "alone")
    r1 = run("stats", out, "--short", os.path.join(d, "q100.short.json"), "--csv", spliced)
    r2 = run("stats", out, "--csv", alone)
    check(r1.returncode == 0 and r2.returncode == 0 and "spliced     with the q = 1 companion" in r1.stdout
          and "blocks      below t = 10 q = 1000 steps" in r2.stdout, "stats says spliced / blocks below 10 q")
    h1, s1 = series(os.path.join(spliced, "S_t.csv"))
    h2, s2 = series(os.path.join(alone, "S_t.csv"))
    g1, g2 = slope(s1), slope(s2)
    check(1.6 <= g1 <= 1.7, f"spliced: S_t ~ t^{g1:.3f} over 10²–10⁴ (1.6–1.7)")
    check(g2 < 1.45, f"the q = 100 run alone: t^{g2:.3f}, the block artefact (the issue: 1.36–1.37)")
    check(h1 == ["t", "S_t", "S_t_error"], f"spliced: no blocks_affected column ({h1})")
    check(h2 == ["t", "S_t", "S_t_error", "blocks_affected"]
          and all((b == "1") == (t < 1000) for t, _, b in s2), "alone: blocks_affected is 1 exactly for t < 10 q")
finish()
