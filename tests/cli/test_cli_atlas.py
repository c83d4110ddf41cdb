"""cli.atlas (issue 38): `archipelago-cli atlas` at K = 0.1, depth 1 — the table, the JSON and the CSV agree and hold
the paper's chain of six (1/6 about the centre); every bad option is one ERROR line and exit status 1 with nothing
written; an output that cannot be written fails loudly."""
import csv, io, json, os, tempfile
from clitest import check, finish, run

with tempfile.TemporaryDirectory() as d:
    j, c = os.path.join(d, "a.json"), os.path.join(d, "a.csv")
    r = run("atlas", "--K", "0.1", "--depth", "1", "--max-period", "200", "--json", j, "--csv", c)
    check(r.returncode == 0, f"atlas exits 0 ({r.returncode}: {r.stderr[-300:]})")
    a = json.load(open(j))
    nodes = a["nodes"]
    check(a["format"] == "archipelago atlas" and a["map"]["K"] == 0.1 and a["request"]["depth"] == 1,
          "the JSON names its format, map and request")
    six = [n for n in nodes if n["parent"] == 0 and n["about_parent"] == "1/6"]
    check(len(six) == 1 and six[0]["period"] == 6, "the chain 1/6 of period 6 about the centre is in the tree")
    check(nodes[0]["boundary"]["found"] and 0 < nodes[0]["area"] < 1.69, f"the central island has an area ({nodes[0]['area']})")
    check(all(n["parent"] < i for i, n in enumerate(nodes)), "parents precede children")
    text = open(c).read()
    rows = list(csv.DictReader(io.StringIO("\n".join(l for l in text.splitlines() if not l.startswith("#")))))
    check(len(rows) == len(nodes), f"the CSV has one row per island ({len(rows)} vs {len(nodes)})")
    check(all((abs(float(row["area"]) - n["area"]) <= 1e-15 * n["area"]) if n["boundary"]["found"] else row["area"] == ""
              for row, n in zip(rows, nodes)),
          "the CSV's areas are the JSON's")
    check("# K: 0.1" in text and "# Software: archipelago" in text, "the CSV carries its provenance")
    check("6 " in r.stdout and "1/6" in r.stdout, "the table lists the chain of six")

    for args, word in [(["--depth", "9"], "depth"), (["--min-area", "nan"], "min-area"), (["--min-area", "-1"], "min area"),
                       (["--K", "1.5"], "K"), (["--max-period", "0"], "max period"), (["--scan-points", "2"], "scan points"),
                       (["--threads", "-3"], "threads"), (["--iterations", "1e30"], "iterations"),
                       (["--bisections", "99"], "bisections")]:
        out = os.path.join(d, "bad.json")
        r = run("atlas", *args, "--json", out)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 1 and len(lines) == 1 and "ERROR" in lines[0] and word in lines[0] and not os.path.exists(out),
              f"atlas {' '.join(args)}: one ERROR line naming {word!r}, nothing written ({r.returncode}: {r.stderr.strip()[:160]})")
    r = run("atlas", "--depth", "0", "--quiet", "--json", "/dev/full")
    check(r.returncode != 0 and "ERROR" in r.stderr, f"--json /dev/full fails loudly ({r.returncode})")

finish()
