#!/usr/bin/env python3
"""archipelago-cli markov, end to end (issue 14, item 4): the Markov model of Karney (1983) appendix C, and bad
input.  Reference values: D_is = sum m_k^2 / 2N (appendix C) and C_is(tau) = (m - tau)/N."""
import csv, os, tempfile

from clitest import check, finish, parse_report as parse, run

r = run("markov", "--m", "10", "--N", "1000", "--tau-max", "40")
check(r.returncode == 0, f"markov --m 10 --N 1000 exits 0 ({r.stderr.strip()})")
header, rows = parse(r.stdout)
D, Dmark = float(header["D_matrix"].split()[0]), float(header["D_dmark"].split()[0])
check(abs(D - Dmark) <= 1e-14 * D, f"D by the matrix formula {D} = eq. (dmark) {Dmark}")
island = float(header["D_island"].split()[0])
check(abs(island - 100 / 2000) < 1e-14, f"island part of D {island} = m^2/2N = 0.05")
check(len(rows) == 41 and rows[0]["tau"] == "0" and rows[-1]["tau"] == "40", f"tau = 0 ... 40 ({len(rows)} rows)")
check(all(abs(float(row["C_is"]) - max(10 - int(row["tau"]), 0) / 1000) < 1e-17 for row in rows),
      "C_is(tau) = (m - tau)/N")
check(all(abs(float(row["epsilon"])) <= 10 / 1000 for row in rows[1:]), "|epsilon| <= m/N for tau > 0 (N >= m^2)")

with tempfile.TemporaryDirectory() as folder:
    path = os.path.join(folder, "markov.csv")
    r = run("markov", "--m", "10,20", "--N", "5000", "--csv", path)
    check(r.returncode == 0 and os.path.exists(path), f"--csv writes the file ({r.stderr.strip()})")
    with open(path) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 4 * 30 + 1, f"default tau-max is 4m = 120 ({len(rows)} rows)")

bad = [
    (["--m", "10,x", "--N", "100"], "--m = 10,x must be"),
    (["--m", "0", "--N", "100"], "--m = 0 must be"),
    (["--m", "", "--N", "100"], "--m =  must be"),
    (["--m", "2000000", "--N", "100000000"], "--m = 2000000 must be"),
    (["--m", "10", "--N", "11"], "--N = 11 must be"),
    (["--m", "10", "--N", "1.5e0"], "--N = 1.5e0 must be"),
    (["--m", "10", "--N", "100", "--tau-max", "-3"], "--tau-max = -3 must be"),
    (["--m", "10", "--N", "100", "--tau-max", "999999999999"], "tau_max = 999999999999 must lie in [0, 45454544]"),
    (["--m", "10", "--N", "100", "--csv", "/nonexistent-folder/x.csv"], "cannot write /nonexistent-folder/x.csv: the folder"),
]
for args, message in bad:
    r = run("markov", *args)
    lines = r.stderr.strip().splitlines()
    check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: " + message),
          f"{' '.join(args)} -> one ERROR line ({r.stderr.strip()})")
finish()
