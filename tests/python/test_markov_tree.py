"""The Markov tree from Python (issue 40): markov_tree() gives the dict of `archipelago-cli markov-tree --json` (both
format core's one JSON) from an atlas dict or an atlas file, and bad input is a ValueError in core's words."""
import _thread
import copy
import json
import subprocess
import threading

import pytest

import archipelago as ap


@pytest.fixture(scope="module")
def atlas_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("tree") / "a.json"
    a = ap.atlas(0.1, depth=1, max_period=40)
    path.write_text(json.dumps(a))
    return path


def test_markov_tree_equals_cli(cli, atlas_file):
    out = subprocess.run([cli, "markov-tree", "--atlas", str(atlas_file), "--alpha", "18.9", "--b2", "1.36",
                          "--t-max", "1e6", "--quiet", "--json", "/dev/stdout"],
                         capture_output=True, text=True, check=True, timeout=600)
    c = json.loads(out.stdout)
    p = ap.markov_tree(atlas_file, alpha=18.9, b2=1.36, t_max=1e6)
    for key in ("states", "rates", "lumped", "survival", "exponents", "entry", "mean_visit"):
        assert p[key] == c[key], key
    d = ap.markov_tree(json.loads(atlas_file.read_text()), alpha=18.9, b2=1.36, t_max=1e6)
    assert d["survival"] == c["survival"]
    assert abs(p["mean_visit"] - p["residence"]) <= 1e-9 * p["residence"]


@pytest.mark.parametrize("kwargs, word", [({"alpha": 18.9}, "alpha and b2 go together"), ({"t_max": 0}, "t-max"),
                                          ({"per_decade": 0}, "per decade")])
def test_markov_tree_refuses_bad_input(atlas_file, kwargs, word):
    with pytest.raises(ValueError, match=word):
        ap.markov_tree(atlas_file, **kwargs)


def test_markov_tree_refuses_a_stopped_atlas(atlas_file):
    a = json.loads(atlas_file.read_text())
    a["cancelled"], a["stop_reason"] = True, "stopped"
    a.pop("format_version"), a.pop("checksum")  # edited: read as an unsigned file (a signed one is refused whole)
    with pytest.raises(ValueError, match="stopped before its end"):
        ap.markov_tree(a)
    with pytest.raises(ValueError, match="atlas"):
        ap.markov_tree(42)


def test_markov_tree_against_a_tail_equals_cli(cli, atlas_file, tmp_path):
    tail = tmp_path / "t.json"
    subprocess.run([cli, "tail", "--population", "40", "--replicas", "2", "--t-max", "2e4", "--quiet", "--out", str(tail)],
                   capture_output=True, text=True, check=True, timeout=600)
    out = subprocess.run([cli, "markov-tree", "--atlas", str(atlas_file), "--alpha", "18.9", "--b2", "1.36",
                          "--tail", str(tail), "--quiet", "--json", "/dev/stdout"],
                         capture_output=True, text=True, check=True, timeout=600)
    c = json.loads(out.stdout)["comparison"]
    p = ap.markov_tree(atlas_file, alpha=18.9, b2=1.36, tail=tail)["comparison"]
    assert p["levels"] == c["levels"] and p["reach"] == c["reach"] and len(p["levels"]) > 0
    with pytest.raises(ValueError, match="needs alpha and b2"):
        ap.markov_tree(atlas_file, tail=tail)
    with pytest.raises(ValueError, match="tail"):
        ap.markov_tree(atlas_file, alpha=18.9, b2=1.36, tail=atlas_file)
    with pytest.raises(ValueError, match="tail must be the path"):
        ap.markov_tree(atlas_file, alpha=18.9, b2=1.36, tail=42)


# Issue 54, item 2 (and the GUI's finding 6 of issue 53): absurd entries were taken (alpha = 1e6 with b2 = 1e-3 gave
# P_1 = 3.7e3; b2 = 1e-320 overflowed w to null; b2 = 100 is above the box's area; alpha = 1e-300 is below a step).
@pytest.mark.parametrize("alpha, b2, word", [(1e6, 1e-3, r"P_1 = w S\(1\)"), (1e300, 1e-300, r"P_1 = w S\(1\)"),
                                             (18.9, 1e-320, r"P_1 = w S\(1\)"), (18.9, 100, r"b2 = 100 must lie in \(0, 1.69"),
                                             (1e-300, 1.36, "alpha = 1e-300 must be finite and at least 1")])
def test_markov_tree_refuses_an_impossible_entry_Issue54(atlas_file, alpha, b2, word):
    with pytest.raises(ValueError, match=word):
        ap.markov_tree(atlas_file, alpha=alpha, b2=b2)


def _nesting_chains(atlas, n):
    """`atlas` (depth 0: the centre and its flux) with n chains about the centre whose zones nest (p/q = 1/(k + 6)
    about a boundary rotation below them; each state of area l1/n and a flux of 10^-3 of it): tests/cli/test_cli_hostile_models.py's."""
    a = copy.deepcopy(atlas)
    a.pop("format_version", None), a.pop("checksum", None)  # an unsigned file, as cli.hostile_models' (it says why)
    a["request"]["depth"] = 1
    c = a["nodes"][0]
    c["boundary"]["rotation"] = 1e-6  # positive (the chains turn in its sense) and below every 1/q
    l1 = 0.5 * c["flux"]["layer_area"]
    short = lambda v: float(f"{v:.12g}")
    for k in range(1, n + 1):
        node, q, layer = copy.deepcopy(c), k + 6, short(l1 * (n + 1 - k) / n)
        flux = short(1e-3 * l1 / n)
        node.update({"index": k, "parent": 0, "level": 1, "path": str(q), "period": q, "about_parent": f"1/{q}",
                     "children": [], "internal": [], "note": "", "area": 1e-6, "area_lower": 1e-6,
                     "area_upper": 1e-6, "area_error": 0.0, "polygon_error": 0.0})
        node["flux"].update({"flux_per_step": flux, "zone_area": short(layer * 1.01), "layer_area": layer,
                             "enclosed_islands_area": short(short(layer * 1.01) - layer),
                             "residence": short(layer / flux)})
        a["nodes"].append(node)
    c["children"] = list(range(1, n + 1))
    return a


# Issue 54, item 3: markov_tree ignored Ctrl-C for two minutes on a large atlas (the GIL held, no stop).  A tree near
# the limit of states takes a minute or more on any machine (about 10 n^3 operations); Ctrl-C 0.5 s into it must end the call itself, not
# arrive after it returned (then `finished` would be set: the signal's handler runs at the next check of the loop).
def test_markov_tree_stops_on_ctrl_c_Issue54():
    atlas = _nesting_chains(ap.atlas(0.1, depth=0), 2000)  # within the limit of states, 2048
    finished = False
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            ap.markov_tree(atlas, t_max=1e3, per_decade=1)
            finished = True
    finally:
        timer.cancel()
    assert not finished


def test_markov_tree_refuses_a_tree_past_its_cost_Issue54():
    with pytest.raises(ValueError, match=r"markov tree states = 20001 must lie in .* GB "):
        ap.markov_tree(_nesting_chains(ap.atlas(0.1, depth=0), 20000))


# Issue 54, item 5: a dict nested 100,000 deep raised RecursionError from json.dumps, not ValueError.
def test_a_deeply_nested_dict_is_a_value_error_Issue54():
    deep = {}
    for _ in range(100000):
        deep = {"a": deep}
    with pytest.raises(ValueError, match="nested too deeply"):
        ap.atlas(0.1, depth=0, resume=deep)
    with pytest.raises(ValueError, match="nested too deeply"):
        ap.markov_tree(deep)
