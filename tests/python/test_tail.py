"""The tail sampler from Python (python/bind_tail.cpp): the numbers and files of `archipelago-cli tail` bit for bit,
Ctrl-C stops it with a resumable file, bad input raises ValueError/TypeError, files OSError."""
import _thread
import json
import subprocess
import threading

import numpy as np
import pytest

import archipelago as ap

SMALL = dict(first=150, t_max=4000, population=20, replicas=3, min_ancestors=4, seed=5)
CLI_SMALL = ["--first", "150", "--t-max", "4000", "--population", "20", "--replicas", "3", "--min-ancestors", "4",
             "--seed", "5"]


def test_tail_is_the_cli_bit_for_bit(tmp_path, cli):
    r = ap.tail(**SMALL, out=tmp_path / "py.json")
    subprocess.run([cli, "tail", *CLI_SMALL, "--out", str(tmp_path / "cli.json"), "--quiet"], check=True)
    doc = json.load(open(tmp_path / "cli.json"))
    assert [L["t"] for L in doc["levels"]] == list(r["t"])
    assert [L["P"] for L in doc["levels"]] == list(r["P"])  # exact: the same numbers
    assert [L["ancestors"] for L in doc["levels"]] == list(r["ancestors"])
    assert [L["reliable"] for L in doc["levels"]] == list(r["reliable"])
    assert doc["steps"] == r["total_steps"]
    py = json.load(open(tmp_path / "py.json"))
    assert py["state"] == doc["state"] and py["levels"] == doc["levels"]
    assert r["finished"] and r["t"].dtype == np.float64 and r["reliable"].dtype == np.bool_
    assert np.all(np.diff(r["P"]) <= 0) and r["P"][0] > 0
    e = r["exponents"]
    assert len(e["gamma"]) == len(e["t"]) and np.all(e["t_from"] < e["t_to"])
    loaded = ap.load_tail(tmp_path / "py.json")
    assert np.array_equal(loaded["P"], r["P"]) and np.array_equal(loaded["steps"], r["steps"])


def test_slices_merge_to_the_whole_run(tmp_path):
    whole = ap.tail(**SMALL, out=tmp_path / "whole.json")
    parts = [tmp_path / f"s{i}.json" for i in range(3)]
    for i in (1, 0, 2):
        part = ap.tail(**SMALL, slice=(i, 3), out=parts[i])
        assert part["finished"] and part["total_steps"] < whole["total_steps"]
    merged = ap.merge_tails(parts, tmp_path / "merged.json")
    assert np.array_equal(merged["P"], whole["P"]) and merged["total_steps"] == whole["total_steps"]
    a, b = json.load(open(tmp_path / "whole.json")), json.load(open(tmp_path / "merged.json"))
    assert a["state"] == b["state"]
    with pytest.raises(ValueError, match="no slice holds replica 0|in no slice"):
        ap.merge_tails(parts[1:], tmp_path / "x.json")
    with pytest.raises(ValueError, match="every slice needs a replica"):
        ap.tail(**SMALL, slice=(0, 4))
    with pytest.raises(TypeError, match="slice must be a tuple"):
        ap.tail(**SMALL, slice=[0, 2])


def test_keyboard_interrupt_leaves_a_resumable_file(tmp_path):
    calls = []

    def progress(d):
        calls.append(d["level"])
        if len(calls) == 5:  # as Ctrl-C would, from another thread
            threading.Thread(target=_thread.interrupt_main).start()
            threading.Event().wait(0.05)

    path = tmp_path / "part.json"
    with pytest.raises(KeyboardInterrupt):
        ap.tail(**SMALL, out=path, progress=progress)
    part = ap.load_tail(path)
    assert not part["finished"]
    resumed = ap.tail_resume(path)
    whole = ap.tail(**SMALL)
    assert resumed["finished"] and np.array_equal(resumed["P"], whole["P"])
    assert resumed["total_steps"] == whole["total_steps"]
    with pytest.raises(ValueError, match="already finished"):
        ap.tail_resume(path)


def test_bad_input(tmp_path):
    with pytest.raises(ValueError, match="population = 1 must lie in"):
        ap.tail(population=1)
    with pytest.raises(ValueError, match="t_max"):
        ap.tail(t_max=float("nan"))
    with pytest.raises(ValueError, match="t_max"):
        ap.tail(t_max=2.5)
    with pytest.raises(ValueError, match="first = 100000000 must lie in"):
        ap.tail(first=1e8, t_max=1e7)
    with pytest.raises(ValueError, match="epsilon = 0"):
        ap.tail(epsilon=0)
    with pytest.raises(ValueError, match="clones"):
        ap.tail(clones="magic")
    with pytest.raises(ValueError, match="Xr"):
        ap.tail(Xr=2.0)
    with pytest.raises(TypeError):
        ap.tail(population="many")
    with pytest.raises(TypeError):
        ap.tail(replicas=True)
    with pytest.raises(TypeError):
        ap.tail(out=None, **{"first": [1]})
    with pytest.raises(OSError):
        ap.load_tail(tmp_path / "missing.json")
    bad = tmp_path / "edited.json"
    r = ap.tail(**SMALL, out=bad)
    bad.write_text(bad.read_text().replace('"population": 20', '"population": 21', 1))
    with pytest.raises(OSError, match="checksum"):
        ap.load_tail(bad)
    with pytest.raises(OSError):
        ap.tail(**SMALL, out=tmp_path / "no-such-folder" / "t.json")
    assert r["finished"]


# Issue 54, item 8: a tail that cannot start (no level between first and t_max) raised RuntimeError, not ValueError.
def test_a_tail_that_cannot_start_is_a_value_error_Issue54():
    with pytest.raises(ValueError):
        ap.tail(first=10**7, t_max=10**7, threads=1)
