"""cli.cantorus (issue 40): `archipelago-cli cantorus` prints and writes the MacKay-Meiss-Percival flux of the Birkhoff
orbits over a cantorus's convergents (core/manifolds/MmpFlux.hpp): the JSON's fluxes agree with the independent mpmath
values of scripts/mmp-periodic-action.py (K = the double 0.1, as the CLI reads it) to 20 digits, its limit is the last
term with the tail bound; bad options and a scan without the orbits are one ERROR line and nothing written."""
import json, os, subprocess, tempfile
from decimal import Decimal
from clitest import check, cli, finish, interrupt, run, wait_for_handler

# scripts/mmp-periodic-action.py --K 0.1000000000000000055511151231257827021181583404541015625 6/37 11/68 17/105
# (mpmath, 60 digits, its own scan and Newton; K = the double nearest 0.1, which the CLI's --K 0.1 is)
MPMATH = {
    (6, 37): Decimal("0.0000286089173938140822541795273986868059"),
    (11, 68): Decimal("0.0000142699554160688763123012540264006378"),
    (17, 105): Decimal("0.0000120763979653511064217539685229786004"),
}

with tempfile.TemporaryDirectory() as d:
    out = os.path.join(d, "c.json")
    r = run("cantorus", "--K", "0.1", "--convergents", "6/37,11/68,17/105", "--out", out)
    check(r.returncode == 0, f"cantorus exits 0 ({r.returncode}: {r.stderr[-300:]})")
    c = json.load(open(out))
    terms = c["terms"]
    check([(t["p"], t["q"]) for t in terms] == [(6, 37), (11, 68), (17, 105)], "one term per convergent, in order")
    for t in terms:
        ref = MPMATH[(t["p"], t["q"])]
        got = Decimal(t["flux_text"])
        check(abs(got - ref) <= Decimal("1e-20") * ref, f"{t['p']}/{t['q']}: {got} against mpmath {ref}")
        check(t["minimizing"]["residue"] < 0 < t["minimax"]["residue"] and t["birkhoff_orbits"] == 2,
              f"{t['p']}/{t['q']}: one orbit each side of R = 0")
    lim = c["limit"]
    d1 = terms[1]["flux"] - terms[0]["flux"]
    d2 = terms[2]["flux"] - terms[1]["flux"]
    ratio = abs(d2 / d1)
    check(lim is not None and lim["value"] == terms[2]["flux"] and abs(lim["ratio"] - ratio) <= 1e-9 * ratio
          and abs(lim["uncertainty"] - abs(d2) * ratio / (1 - ratio)) <= 1e-9 * lim["uncertainty"],
          f"the limit is the last term with the tail bound |d| r/(1 - r) ({lim})")
    # 5/31, 6/37, 11/68: differences -9.7e-6, -1.4e-5 (ratio 1.48): no limit, and why
    r = run("cantorus", "--convergents", "5/31,6/37,11/68", "--json")
    j = json.loads(r.stdout) if r.returncode == 0 else {}
    check(j.get("limit", 0) is None and "not converging" in j.get("limit_problem", ""),
          f"a growing difference gives no limit ({j.get('limit_problem')})")
    for f in ("flux_text", "plane_difference_text"):
        check(all(f in t for t in terms), f"each term has {f}")
    # the table names each term
    r = run("cantorus", "--convergents", "5/31,6/37")
    check(r.returncode == 0 and "5/31" in r.stdout and "6/37" in r.stdout and "limit: none" in r.stdout,
          f"the table: two terms and no limit ({r.stdout[-300:]})")
    # refusals: one ERROR line, nothing written
    for args, words in ((["--convergents", "5/31,x"], "not p/q"), (["--convergents", "2/12"], "lowest terms"),
                        (["--convergents", "5/31", "--inner", "0.3", "--outer", "0.2"], "0 < inner < outer"),
                        (["--convergents", "5/31", "--spacing", "0"], "spacing"),
                        (["--convergents", "5/31", "--inner", "0.05", "--outer", "0.15"], "0 well ordered")):
        bad = os.path.join(d, "bad.json")
        r = run("cantorus", *args, "--out", bad)
        lines = [l for l in r.stderr.splitlines() if l.strip()]
        check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR:") and words in lines[0]
              and not os.path.exists(bad), f"{args}: one ERROR line with '{words}' ({r.stderr[-300:]})")
    # Ctrl-C during a long scan (issue 54, item 5: SIGINT during 1/997 ended after 26 s with a message that was not one
    # line): the program's one stop (interruptToken) ends it at the scan's next chunk with one line, status 130, and
    # nothing written.  The signal is sent once the handler is installed (the event), never after a fixed wait.
    stopped = os.path.join(d, "stopped.json")
    p = subprocess.Popen([cli, "cantorus", "--convergents", "1/997", "--out", stopped], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    handled = wait_for_handler(p)
    out, err = interrupt(p, timeout=600)
    lines = [l for l in (err or "").splitlines() if l.strip()]
    check(handled and p.returncode == 130 and len(lines) == 1 and lines[0].startswith("interrupted:")
          and not os.path.exists(stopped), f"SIGINT: one line, status 130, nothing written ({p.returncode}: {err})")
finish()
