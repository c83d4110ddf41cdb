"""b2 is an area (issue #14, item 1; Karney 1983, appendix A: b0 = L^2, b2 its stochastic part): stochastic-area
reports the area beside the occupied fraction, compares with the paper's 0.693 only at K = 0.1, and stats --b2 AREA
adds the box-invariant b2*D (eq. A3) and the sec. 6 figures."""
import csv, io, json, math, os, tempfile

from clitest import check, finish, run

tmp = tempfile.mkdtemp(prefix="cli-b2-")

# --- stochastic-area: area = fraction * L^2 on every row, in the CSV and the JSON -----------------------------
for K, xmin, xmax in ((0.1, -0.8, 0.5), (0.2, -1.1, 0.7)):
    js = os.path.join(tmp, f"a{K}.json")
    r = run("stochastic-area", "--K", str(K), "--xmin", str(xmin), "--xmax", str(xmax), "--iterations", "2000000",
            "--json", js)
    check(r.returncode == 0, f"stochastic-area at K = {K}")
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    L2 = (xmax - xmin) ** 2
    check(rows and list(rows[0].keys()) == ["iterations", "boxes_visited", "b2_area", "b2_fraction"],
          f"CSV columns name the area and the fraction: {list(rows[0].keys()) if rows else None}")
    check(all(abs(float(x["b2_area"]) - int(x["boxes_visited"]) / 1024 ** 2 * L2) <= 5e-7 and
              abs(float(x["b2_fraction"]) - int(x["boxes_visited"]) / 1024 ** 2) <= 5e-7 for x in rows),
          f"b2_area = b2_fraction * L^2 (L^2 = {L2:.4g}) on every row")
    j = json.load(open(js))
    check(abs(j["b2_area"] - j["b2_fraction"] * L2) < 1e-12 and abs(j["box_area"] - L2) < 1e-12 and "b2" not in j,
          "the JSON sidecar has b2_area, b2_fraction and box_area (no ambiguous 'b2')")
    mentions_paper = "0.693" in r.stderr
    check(mentions_paper == (K == 0.1), f"K = {K}: the paper's b2 = 0.693 is {'quoted' if K == 0.1 else 'not quoted'}")
    if K == 0.1:
        check("xmin = -0.8, xmax = 0.5" in r.stderr and "fig. 6" in r.stderr,
              "the comparison names this box and the paper's (fig. 6 caption)")
    check(f"{float(rows[-1]['b2_area']):.4f}" in r.stderr, "the summary on stderr states the area")

# --- stats --b2: b2*D, the sec. 6 factor, box_invariant.csv ----------------------------------------------------
rf = os.path.join(tmp, "r.json")
r = run("run", "--T", "5000", "--M", "8", "--subsets", "4", "--out", rf, "--quiet", "--threads", "1")
check(r.returncode == 0, "a small K = 0.1 run")
r = run("stats", rf, "--b2", "1.371", "--csv", os.path.join(tmp, "csv"))
D = float(next(l for l in r.stdout.splitlines() if l.startswith("D ")).split()[1])
b2D = float(next(l for l in r.stdout.splitlines() if l.startswith("b2*D")).split()[1])
check(r.returncode == 0 and abs(b2D - 1.371 * D) <= 1e-5 * b2D, f"stats --b2 1.371: b2*D = 1.371 * D ({b2D} vs {D})")
check(f"fraction {1.371 / 1.69:.5f}" in r.stdout, "stats --b2 shows the fraction of the box beside the area")
factor = 8 / math.pi ** 2 * 1.371
check(f"{factor:.4g}" in r.stdout, f"the sec. 6 factor (8/pi^2) b2 = {factor:.4g}")
rows = {x["quantity"]: x for x in csv.DictReader(l for l in open(os.path.join(tmp, "csv", "box_invariant.csv"))
                                                  if not l.startswith("#"))}
check(abs(float(rows["b2_D"]["value"]) - 1.371 * float(rows["D"]["value"])) < 1e-9 * float(rows["b2_D"]["value"]) and
      abs(float(rows["accelerator_factor_8_over_pi2_b2"]["value"]) - factor) < 1e-12 and
      abs(float(rows["enhancement_over_quasilinear_n1"]["value"]) - factor * float(rows["D"]["value"]) / math.pi ** 2) < 1e-9 * D,
      "box_invariant.csv: b2_D, the factor and the enhancement over quasi-linear diffusion")
ft = list(csv.DictReader(l for l in open(os.path.join(tmp, "csv", "f_t.csv")) if not l.startswith("#")))
b2ft = list(csv.DictReader(l for l in open(os.path.join(tmp, "csv", "b2_f_t.csv")) if not l.startswith("#")))
check(len(ft) == len(b2ft) > 10 and all(a["t"] == b["t"] and abs(float(b["b2_f_t"]) - 1.371 * float(a["f_t"])) <=
                                        1e-12 * float(b["b2_f_t"]) for a, b in zip(ft, b2ft)),
      "b2_f_t.csv: b2 * f_t at every t of f_t.csv")
check(all(a.get("blocks_affected") == b.get("blocks_affected") for a, b in zip(ft, b2ft)),
      "b2_f_t.csv marks the rows of blocks of q steps as f_t.csv does")
for bad, word in (("0", "(0, L^2"), ("1.7", "(0, L^2"), ("-1", "(0, L^2"), ("nan", "finite"), ("x", "finite")):
    r = run("stats", rf, f"--b2={bad}")
    lines = r.stderr.strip().splitlines()
    check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and word in lines[0],
          f"stats --b2={bad}: one ERROR line ({r.stderr.strip()})")
finish()
