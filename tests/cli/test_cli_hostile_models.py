#!/usr/bin/env python3
"""Issue 54: the attack harness on the newest surfaces (the Markov tree, the atlas's outputs, the tail's state paths,
the cantorus's list), each case classified as in test_cli_hostile.py (hostile.py: valid, clean error, crash, hang,
silent wrong) and the table printed; the test fails unless every crash, hang and silent-wrong cell is 0.  Categories:

  tree entry      absurd entries refused with core's words (item 2): alpha = 1e6 with b2 = 1e-3 gave P_1 = 3.7e3,
                  alpha = 1e300 with b2 = 1e-300 and b2 = 1e-320 overflowed w (null in the JSON, exit 0), b2 = 100 is
                  above the box's area, alpha = 1e-300 below one step; the docs' entry and no entry at all are valid,
                  and `--at 1e3` is the whole number 1000 (docs/cli.md's number rule)
  tree cost       a legal atlas of 1000 nesting chains finishes (it ran past 360 s); one of 20,000 is refused before
                  any work with its cost (it asked 6.4 GB per matrix power and was killed at 4 GiB) (item 3)
  all or nothing  `atlas` and `markov-tree` with --json on a roomy disk and --csv on a full one (/dev/full): one ERROR
                  and the JSON not written (item 4)
  state paths     `tail --checkpoint r.json` over a run file, `tail --out` over an atlas: refused, the file unchanged;
                  `tail --csv` with a name longer than the folder takes: refused before the tail runs (item 8)
  messages        `cantorus --convergents '1/6\\n'` and an output folder whose name holds a newline: one ERROR line
                  (item 5)

The nesting atlases are built here from a computed depth-0 atlas (the centre and its flux), never checked in."""
import copy, hashlib, json, os, shutil, tempfile, time

from clitest import check, finish, signed
from hostile import classify, invoke, print_table, problems, record

tmp = tempfile.mkdtemp(prefix="archipelago-hostile-models-")


def make_dir(name):
    d = os.path.join(tmp, name)
    os.makedirs(d, exist_ok=True)
    return d


def digest(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest() if os.path.isfile(path) else None


base = make_dir("base")
atlas = os.path.join(base, "a.json")
rc, _, err = invoke(["atlas", "--K", "0.1", "--depth", "0", "--quiet", "--json", atlas], timeout=1200)
check(rc == 0, f"a depth-0 atlas is computed ({err.strip()[:200]})")
centre = json.load(open(atlas))


def nesting_chains(n):
    """The depth-0 atlas with n chains about the centre whose zones nest: chain k has p/q = 1/(k + 6) (farther from
    the boundary rotation the farther out), layer l1 (n + 1 - k)/n (each state of area l1/n) and a flux of 10^-3 of
    that area; the centre's layer stays above l1."""
    a = copy.deepcopy(centre)
    # Unsigned, as atlas files before issue 54 were (still read, every rule but the checksum checked): Python cannot
    # sign a document of computed doubles as the C++ writer prints them (its shortest digits differ now and then).
    a.pop("format_version", None)
    a.pop("checksum", None)
    a["request"]["depth"] = 1
    c = a["nodes"][0]
    # The centre's boundary rotation below every 1/q (each chain then lies farther from it the farther out), and
    # positive: a chain turns about its parent in the sense of the parent's circles (issue 54's reader checks it).
    c["boundary"]["rotation"] = 1e-6
    l1 = 0.5 * c["flux"]["layer_area"]
    short = lambda v: float(f"{v:.12g}")  # consistent to 1e-12: the reader's rules allow 1e-9
    for k in range(1, n + 1):
        node = copy.deepcopy(c)
        q = k + 6
        layer = l1 * (n + 1 - k) / n
        node.update({"index": k, "parent": 0, "level": 1, "path": str(q), "period": q, "about_parent": f"1/{q}",
                     "children": [], "internal": [], "note": ""})
        node["boundary"]["rotation"] = 0.25
        # a small island (a copy of the centre's area times q would exceed the box: refused, issue 54)
        node.update({"area": 1e-6, "area_lower": 1e-6, "area_upper": 1e-6, "area_error": 0.0, "polygon_error": 0.0})
        layer, flux = short(layer), short(1e-3 * l1 / n)
        node["flux"].update({"flux_per_step": flux, "zone_area": short(layer * 1.01), "layer_area": layer,
                             "enclosed_islands_area": short(short(layer * 1.01) - layer),
                             "residence": short(layer / flux)})
        a["nodes"].append(node)
    c["children"] = list(range(1, n + 1))
    return a


def written(path, data):
    """`data` written to `path`, signed again when it is a signed document (the cases test the rules past it)."""
    with open(path, "w") as f:
        json.dump(signed(data) if isinstance(data, dict) and "format_version" in data else data, f)
    return path


# ------------------------------------------------------------------------------------------------ tree entry
def entry_cases():
    d = make_dir("entry")
    out = os.path.join(d, "m.json")
    results = []
    refused = [(["--alpha", "1e6", "--b2", "1e-3"], "P_1 = w S(1)"), (["--alpha", "1e300", "--b2", "1e-300"], "P_1 = w S(1)"),
               (["--alpha", "18.9043", "--b2", "1e-320"], "P_1 = w S(1)"), (["--alpha", "18.9043", "--b2", "100"], "b2 = 100 must lie in (0, 1.69"),
               (["--alpha", "1e-300", "--b2", "1.362484"], "alpha = 1e-300 must be finite and at least 1"),
               (["--alpha", "0.5", "--b2", "1.362484"], "alpha = 0.5")]
    for args, words in refused:
        rc, _, err = invoke(["markov-tree", "--atlas", atlas, *args, "--json", out, "--quiet"])
        outcome = classify(rc, err, True, lambda: False)
        if outcome == "clean error" and (words not in err or "--alpha" in err.split("ERROR: ")[-1][:20]):
            outcome = "silent wrong"  # refused, but not with core's words
        if os.path.exists(out):
            outcome = "silent wrong"
        results.append(("tree entry", " ".join(args), outcome, err.strip()[:200]))

    def valid_json(check_it):
        def ok():
            try:
                return check_it(json.load(open(out)))
            except (OSError, ValueError):
                return False
        return ok

    for args, check_it in [(["--alpha", "18.9043", "--b2", "1.362484"],
                            lambda m: m["entry"]["weight"] is not None and all(p is None or 0 <= p <= 1 for p in m["survival"]["P"][1:])),
                           ([], lambda m: m["entry"]["weight"] is None),
                           (["--at", "1e3"], lambda m: 1000 in m["survival"]["t"])]:
        if os.path.exists(out):
            os.remove(out)
        rc, _, err = invoke(["markov-tree", "--atlas", atlas, *args, "--json", out, "--quiet"])
        results.append(("tree entry", " ".join(args) or "(no entry)", classify(rc, err, False, valid_json(check_it)), err.strip()[:200]))
    return results


# ------------------------------------------------------------------------------------------------- tree cost
def cost_cases():
    d = make_dir("cost")
    results = []
    thousand = written(os.path.join(d, "a1000.json"), nesting_chains(1000))
    out = os.path.join(d, "m1000.json")
    started = time.monotonic()
    rc, _, err = invoke(["markov-tree", "--atlas", thousand, "--t-max", "1e6", "--per-decade", "5", "--json", out, "--quiet"],
                        timeout=1800)

    def finished():
        m = json.load(open(out))
        S = [s for s in m["survival"]["S"] if s is not None]
        return len(m["states"]) == 1001 and all(b <= a for a, b in zip(S, S[1:])) and \
            abs(m["mean_visit"] / m["residence"] - 1) < 1e-12
    results.append(("tree cost", "1000 nesting chains", classify(rc, err, False, finished), err.strip()[:200]))
    print(f"1000 nesting chains: {time.monotonic() - started:.1f} s")  # for the closing note, not a bound
    large = written(os.path.join(d, "a20000.json"), nesting_chains(20000))
    out = os.path.join(d, "m20000.json")
    rc, _, err = invoke(["markov-tree", "--atlas", large, "--json", out, "--quiet"], timeout=1800)
    outcome = classify(rc, err, True, lambda: False)
    if outcome == "clean error" and not ("markov tree states = 20001 must lie in" in err and " GB " in err):
        outcome = "silent wrong"  # refused, but without its cost
    if os.path.exists(out):
        outcome = "silent wrong"
    results.append(("tree cost", "20,000 nesting chains", outcome, err.strip()[:240]))
    return results


# ------------------------------------------------------------------------------------------- all or nothing
def all_or_nothing_cases():
    results = []
    if not os.path.exists("/dev/full"):
        print("all or nothing: skipped (no /dev/full)")
        return results
    for name, args in [("markov-tree", ["markov-tree", "--atlas", atlas, "--quiet"]),
                       ("atlas", ["atlas", "--K", "0.1", "--depth", "0", "--quiet"])]:
        d = make_dir("whole-" + name)
        full = os.path.join(d, "full.csv")
        os.symlink("/dev/full", full)
        out = os.path.join(d, "out.json")
        rc, _, err = invoke([*args, "--json", out, "--csv", full], timeout=1200)
        outcome = classify(rc, err, True, lambda: False)
        left = sorted(n for n in os.listdir(d) if n != "full.csv")
        if outcome == "clean error" and left:
            outcome = "silent wrong"  # the JSON written without its CSV, or debris
        results.append(("all or nothing", f"{name} --json (roomy) --csv (full)", outcome, f"{err.strip()[:160]} left: {left}"))
    return results


# ---------------------------------------------------------------------------------------------- state paths
TAIL = ["tail", "--first", "150", "--t-max", "1000", "--population", "20", "--replicas", "3", "--min-ancestors", "4",
        "--threads", "1", "--quiet"]


def state_path_cases():
    d = make_dir("state")
    results = []
    run_file = os.path.join(d, "r.json")
    rc, _, err = invoke(["run", "--T", "2000", "--M", "8", "--subsets", "2", "--q", "4", "--quiet", "--out", run_file])
    check(rc == 0, f"a run file to protect ({err.strip()[:160]})")
    kept_atlas = shutil.copy(atlas, os.path.join(d, "kept-atlas.json"))
    for label, args, protected in [("--checkpoint over a run file", ["--out", os.path.join(d, "t.json"), "--checkpoint", run_file], run_file),
                                   ("--out over an atlas", ["--out", kept_atlas], kept_atlas)]:
        before = digest(protected)
        rc, _, err = invoke([*TAIL, *args])
        outcome = classify(rc, err, True, lambda: False)
        if digest(protected) != before or os.path.exists(os.path.join(d, "t.json")):
            outcome = "silent wrong"  # the file replaced, or the tail written beside it
        results.append(("state paths", "tail " + label, outcome, err.strip()[:200]))
    # A tail file at --out is the state this command writes: overwritten, as before.
    again = os.path.join(d, "again.json")
    rc, _, err = invoke([*TAIL, "--out", again])
    rc, _, err = invoke([*TAIL, "--out", again])
    results.append(("state paths", "tail --out over a tail file", classify(rc, err, False, lambda: os.path.getsize(again) > 0), err.strip()[:200]))
    # A CSV name longer than the folder takes (255 bytes): refused before the tail runs, nothing written.
    long = make_dir("long")
    out = os.path.join(long, "n" * 250 + ".json")
    rc, _, err = invoke([*TAIL, "--out", out, "--csv", out + ".csv"])
    outcome = classify(rc, err, True, lambda: False)
    if outcome == "clean error" and (os.listdir(long) or "longer than" not in err):
        outcome = "silent wrong"
    results.append(("state paths", "tail --csv <a 259-byte name>", outcome, f"{err.strip()[:200]} left: {os.listdir(long)[:3]}"))
    return results


# --------------------------------------------------------------------------------------------------- messages
def message_cases():
    rc, _, err = invoke(["cantorus", "--K", "0.1", "--convergents", "1/6\n"])
    outcome = classify(rc, err, True, lambda: False)
    results = [("messages", "cantorus --convergents '1/6\\n'", outcome, err.strip()[:200])]
    # An output folder whose name holds a newline (that does not exist): the message quotes it on one line.
    out = os.path.join(make_dir("messages"), "new\nline", "m.json")
    rc, _, err = invoke(["markov-tree", "--atlas", atlas, "--json", out, "--quiet"])
    results.append(("messages", "markov-tree --json <a folder 'new\\nline'>", classify(rc, err, True, lambda: False),
                    err.strip()[:200]))
    return results


# ------------------------------------------------------------------------------------------------------- main
started = time.monotonic()
for case in [*entry_cases(), *all_or_nothing_cases(), *state_path_cases(), *message_cases(), *cost_cases()]:
    record(*case)
print_table(started)
if not problems:
    shutil.rmtree(tmp, ignore_errors=True)
finish()
