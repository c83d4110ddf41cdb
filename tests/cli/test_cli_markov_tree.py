"""cli.markov_tree (issue 40): `archipelago-cli markov-tree` on an atlas the test computes (K = 0.1, depth 1, periods
up to 40): every state's area is the atlas file's layer less the layers inside it, every rate the file's flux over
that area, the mean visit the atlas's residence of the loop (Kac), P_t = alpha flux / b2 S(t); the CSV is the JSON's
survival with its provenance; one flux edited in the atlas file changes exactly the two rates through that barrier;
bad options and bad atlases are one ERROR line and nothing written; --tail sets the model against a tail sampler's
levels (ratio, reach) and refuses a tail of another map; issue 50: inner separatrices are states of their own,
--without and --levels leave barriers out, and --tail gives the ablation."""
import csv, io, json, os, tempfile
from clitest import check, finish, run, signed

with tempfile.TemporaryDirectory() as d:
    atlas = os.path.join(d, "a.json")
    # 1000 points a side (--scan-steps 0), two thirds of the default scan's time: the centre and the five chains with a
    # flux that the default finds too (not its island 29, which has no flux and so no state here).
    r = run("atlas", "--K", "0.1", "--depth", "1", "--max-period", "40", "--scan-steps", "0", "--quiet", "--json", atlas,
            timeout=1800)  # a hang bound: the atlas takes about a minute
    check(r.returncode == 0, f"atlas exits 0 ({r.returncode}: {r.stderr[-300:]})")
    a = json.load(open(atlas))
    nodes = a["nodes"]
    j, c = os.path.join(d, "m.json"), os.path.join(d, "m.csv")
    r = run("markov-tree", "--atlas", atlas, "--alpha", "18.9043", "--b2", "1.362484", "--t-max", "1e6",
            "--at", "1008,2160", "--json", j, "--csv", c, "--without", "inner,cantori")
    check(r.returncode == 0, f"markov-tree exits 0 ({r.returncode}: {r.stderr[-300:]})")
    m = json.load(open(j))
    check(m["format"] == "archipelago markov tree" and m["map"]["K"] == 0.1, "the JSON names its format and map")
    layer = {i: n["flux"]["layer_area"] for i, n in enumerate(nodes) if n["flux"]["found"]}
    flux = {i: n["flux"]["flux_per_step"] for i, n in enumerate(nodes) if n["flux"]["found"]}
    states = m["states"]
    check(len(states) == len(layer), f"without inner separatrices and cantori, one state per chain with a flux ({len(states)} vs {len(layer)})")
    # The chains about the centre nest: the outermost (largest zone) opens onto the top state, each next one onto it.
    kids = sorted((i for i in layer if i > 0), key=lambda i: -nodes[i]["flux"]["zone_area"])
    chain = [0] + kids
    expected_area = {n: layer[n] - (layer[chain[k + 1]] if k + 1 < len(chain) else 0) for k, n in enumerate(chain)}
    by_node = {s["node"]: i for i, s in enumerate(states)}
    check(all(abs(states[by_node[n]]["area"] - A) <= 1e-14 * A for n, A in expected_area.items()),
          "each state's area is its layer less the next inner layer (the file's numbers)")
    check(all(states[by_node[chain[k + 1]]]["container"] == by_node[chain[k]] for k in range(len(chain) - 1)),
          "each chain's state opens onto the next outer one")
    ok = True
    for rate in m["rates"]:
        A = states[rate["from"]]["area"]
        ok &= abs(rate["per_step"] - flux[rate["flux_node"]] / A) <= 1e-14 * rate["per_step"] and rate["source"] != ""
    check(ok, "every rate is the file's flux of its barrier / the area it leaves, with its source")
    residence = nodes[0]["flux"]["residence"]
    check(abs(m["mean_visit"] - residence) <= 1e-9 * residence, f"mean visit {m['mean_visit']} = the loop's residence {residence} (Kac)")
    w = 18.9043 * flux[0] / 1.362484
    check(abs(m["entry"]["weight"] - w) <= 1e-14 * w, "entry weight = alpha flux / b2")
    S, P, t = m["survival"]["S"], m["survival"]["P"], m["survival"]["t"]
    check(1008 in t and 2160 in t and t[-1] == 1000000, "the grid holds --at and ends at --t-max")
    check(all(abs(p - w * s) <= 1e-14 * w * s for p, s in zip(P, S) if s), "P = w S")
    check(all(abs(sum(lv[i] or 0 for lv in m["survival"]["levels"]) - S[i]) <= 1e-12 * S[i] for i in range(len(t)) if S[i]),
          "the levels' shares add up to S")
    text = open(c).read()
    rows = list(csv.DictReader(io.StringIO("\n".join(l for l in text.splitlines() if not l.startswith("#")))))
    check(len(rows) == len(t) and all(abs(float(row["S"]) - s) <= 1e-11 * s for row, s in zip(rows, S) if s),
          "the CSV's S is the JSON's")
    check("# K: 0.1" in text and "# Software: archipelago" in text and "# Atlas: " + atlas in text,
          "the CSV carries its provenance and the atlas it was built from")

    # Issue 50: with every barrier (the default), each chain whose inner separatrix has a layer gets a second state
    # inside it, opening onto the chain's own; every state's area is its barrier's layer less the layers of the
    # states that open onto it (the file's numbers), the mean visit still the loop's residence (Kac).
    jf = os.path.join(d, "full.json")
    r = run("markov-tree", "--atlas", atlas, "--json", jf, "--quiet")
    check(r.returncode == 0, f"markov-tree with every barrier exits 0 ({r.returncode}: {r.stderr[-300:]})")
    full = json.load(open(jf))["states"]
    inner = {i: n["flux"]["inner"]["layer_area"] for i, n in enumerate(nodes)
             if i in layer and "layer_area" in n["flux"].get("inner", {})}
    check(len(inner) >= 3 and len(full) == len(layer) + len(inner),
          f"one more state per chain with an inner layer ({len(full)} = {len(layer)} + {len(inner)})")
    own = [layer[s["node"]] if s["barrier"] == "outer separatrix" else inner.get(s["node"], -1) for s in full]
    ok = all(s["barrier"] in ("outer separatrix", "inner separatrix") for s in full)
    for k, s in enumerate(full):
        inside = [i for i, x in enumerate(full) if x["container"] == k]
        ok &= abs(s["area"] - (own[k] - sum(own[i] for i in inside))) <= 1e-13 * own[k] and s["subtracted"] == inside
        if s["barrier"] == "inner separatrix":
            ok &= full[s["container"]]["node"] == s["node"] and full[s["container"]]["barrier"] == "outer separatrix"
    check(ok, "each state's area is its layer less its children's; an inner state opens onto its chain's outer one")
    check(abs(json.load(open(jf))["mean_visit"] - residence) <= 1e-9 * residence, "with every barrier the mean visit is still the loop's residence")
    r = run("markov-tree", "--atlas", atlas, "--without", "inner,other", "--json", os.path.join(d, "no.json"))
    check(r.returncode != 0 and r.stderr.count("\n") == 1 and "--without: 'other'" in r.stderr
          and not os.path.exists(os.path.join(d, "no.json")), f"--without other is one ERROR line ({r.stderr!r})")
    r = run("markov-tree", "--atlas", atlas, "--levels", "0", "--json", os.path.join(d, "l0.json"), "--quiet")
    l0 = json.load(open(os.path.join(d, "l0.json")))
    check(r.returncode == 0 and len(l0["states"]) == 1 and len(l0["lumped"]) == len(nodes) - 1,
          "--levels 0: the centre's state alone, every chain lumped into it")

    # One flux edited: the two rates through that barrier change, no other.
    edited = os.path.join(d, "edited.json")
    target = kids[1]
    f = a["nodes"][target]["flux"]
    f["flux_per_step"] *= 3
    f["residence"] = f["layer_area"] / f["flux_per_step"]  # kept consistent, and the file signed again
    json.dump(signed(a), open(edited, "w"))
    j2 = os.path.join(d, "m2.json")
    r = run("markov-tree", "--atlas", edited, "--t-max", "1e6", "--json", j2, "--quiet", "--without", "inner,cantori")
    m2 = json.load(open(j2))
    changed = [x["flux_node"] for x, y in zip(m["rates"], m2["rates"]) if x["per_step"] != y["per_step"]]
    check(r.returncode == 0 and changed == [target, target], f"editing the flux of node {target} changes its two rates ({changed})")
    check(m2["entry"]["weight"] is None and m2["survival"]["P"][0] is None, "without --alpha and --b2 there is no P_t")

    stopped = os.path.join(d, "stopped.json")
    s = json.load(open(atlas))
    s["cancelled"], s["stop_reason"] = True, "stopped"
    json.dump(signed(s), open(stopped, "w"))
    for args, word in [(["--alpha", "18.9"], "alpha and b2 go together"), (["--alpha", "-1", "--b2", "1.3"], "alpha"),
                       (["--t-max", "0"], "t-max"), (["--at", "12,x"], "--at"), (["--per-decade", "0"], "per decade"),
                       (["--at", "9223372036854775807"], "2^62")]:
        out = os.path.join(d, "bad.json")
        r = run("markov-tree", "--atlas", atlas, *args, "--json", out)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 1 and len(lines) == 1 and "ERROR" in lines[0] and word in lines[0] and not os.path.exists(out),
              f"markov-tree {' '.join(args)}: one ERROR line naming {word!r}, nothing written ({r.returncode}: {r.stderr.strip()[:160]})")
    for path, word in [(stopped, "stopped before its end"), (os.path.join(d, "none.json"), "none.json"),
                       (c, "--atlas " + c)]:
        out = os.path.join(d, "bad.json")
        r = run("markov-tree", "--atlas", path, "--json", out)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 1 and len(lines) == 1 and word in lines[0] and not os.path.exists(out),
              f"atlas {os.path.basename(path)}: one ERROR line naming {word!r} ({r.returncode}: {r.stderr.strip()[:200]})")
    # Against a tail of the atlas's map (--tail): each level's model is w S(t) and its ratio model / measured; the
    # reach is the last level whose ratio is within a factor 3; a tail of another map, a tail without
    # alpha and b2 and a file that is no tail are one ERROR line each.
    tail = os.path.join(d, "t.json")
    r = run("tail", "--population", "40", "--replicas", "2", "--t-max", "2e4", "--quiet", "--out", tail)
    check(r.returncode == 0, f"a small tail exits 0 ({r.returncode}: {r.stderr[-300:]})")
    levels = [l for l in json.load(open(tail))["levels"] if l["reliable"] and l["P"] > 0 and l["t"] >= 1000]
    jt = os.path.join(d, "mt.json")
    r = run("markov-tree", "--atlas", atlas, "--alpha", "18.9043", "--b2", "1.362484", "--tail", tail,
            "--at", ",".join(str(l["t"]) for l in levels), "--json", jt)
    check(r.returncode == 0 and "against the tail" in r.stdout, f"markov-tree --tail exits 0 with its table ({r.returncode}: {r.stderr[-300:]})")
    mt = json.load(open(jt))
    comp, surv = mt.get("comparison", {}), mt["survival"]
    Sat = dict(zip(surv["t"], surv["S"]))
    lv = comp.get("levels", [])
    check(len(lv) == len(levels) > 0 and all(x["t"] == l["t"] and x["measured"] == l["P"] for x, l in zip(lv, levels)),
          f"one comparison per reliable level from 10^3 ({len(lv)} of {len(levels)})")
    check(all(abs(x["model"] - w * Sat[int(x["t"])]) <= 1e-12 * x["model"] and
              abs(x["ratio"] - x["model"] / x["measured"]) <= 1e-12 * x["ratio"] for x in lv),
          "each level's model is w S(t), its ratio model / measured")
    reach = max([x["t"] for x in lv if 1 / 3 <= x["ratio"] <= 3], default=0)
    check(comp.get("factor") == 3 and comp.get("reach") == reach and comp.get("tail") == tail,
          f"the reach is the last level within a factor 3 ({comp.get('reach')} vs {reach})")
    # The ablation (issue 50): every barrier, none of the inner ones, no cantori, outer only, level 0 alone — each
    # with its reach; the first is the comparison's own.
    ab = mt.get("ablation", [])
    check([x["variant"] for x in ab] == ["every barrier", "no inner separatrices", "no cantori",
                                         "outer separatrices only", "levels <= 0"]
          and ab[0]["reach"] == comp.get("reach") and all(len(x["ratio"]) == len(lv) for x in ab)
          and "# ablation" in r.stdout, f"the ablation's five variants, the first the comparison ({[x.get('variant') for x in ab]})")
    other = os.path.join(d, "t15.json")
    r = run("tail", "--K", "0.15", "--xmin=-0.9746", "--xmax", "0.5873", "--population", "20", "--replicas", "2",
            "--t-max", "2e3", "--quiet", "--out", other)
    notail = os.path.join(d, "notail.json")
    json.dump(json.load(open(atlas)), open(notail, "w"))
    for args, word in [(["--tail", other, "--alpha", "18.9", "--b2", "1.3"], "the tail is of K = 0.15"),
                       (["--tail", tail], "needs alpha and b2"),
                       (["--tail", notail, "--alpha", "18.9", "--b2", "1.3"], "--tail " + notail)]:
        out = os.path.join(d, "bad.json")
        r = run("markov-tree", "--atlas", atlas, *args, "--json", out)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 1 and len(lines) == 1 and word in lines[0] and not os.path.exists(out),
              f"markov-tree {' '.join(args[:2])}: one ERROR line naming {word!r} ({r.returncode}: {r.stderr.strip()[:200]})")

    r = run("markov-tree", "--atlas", atlas, "--csv", "/nonexistent-folder/x.csv")
    check(r.returncode == 1 and "cannot write" in r.stderr, f"an unwritable --csv fails loudly ({r.stderr.strip()[:120]})")
finish()
