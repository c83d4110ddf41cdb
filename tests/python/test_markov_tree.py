"""The Markov tree from Python (issue 40): markov_tree() gives the dict of `archipelago-cli markov-tree --json` (both
format core's one JSON) from an atlas dict or an atlas file, and bad input is a ValueError in core's words."""
import json
import subprocess

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
