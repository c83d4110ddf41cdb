"""The tail sampler over K from Python (python/bind_tail_scan.cpp): archipelago-cli tail-scan's job, the same files
and summary bit for bit; bad input raises ValueError/TypeError."""
import csv
import subprocess

import numpy as np
import pytest

import archipelago as ap

SMALL = dict(t_max=3e4, first=100, population=40, replicas=4, min_ancestors=4, threads=2)
CLI_SMALL = ["--t-max", "3e4", "--first", "100", "--population", "40", "--replicas", "4", "--min-ancestors", "4",
             "--threads", "2"]


def test_tail_scan_is_the_cli_bit_for_bit(tmp_path, cli):
    r = ap.tail_scan(K=[0.1, 0.15], directory=tmp_path / "py", **SMALL)
    subprocess.run([cli, "tail-scan", "--K", "0.1,0.15", *CLI_SMALL, "--dir", str(tmp_path / "cli"), "--csv",
                    str(tmp_path / "cli" / "s"), "--quiet"], check=True)
    assert list(r["K"]) == [0.1, 0.15]
    assert r["P"].shape == (2, len(r["t"])) and r["gamma"].shape == (2, len(r["t_from"]))
    assert r["reliable"].dtype == np.bool_
    rows = list(csv.DictReader(open(tmp_path / "cli" / "s_P.csv")))
    assert [float(x["P"]) for x in rows] == list(r["P"].ravel())  # exact: the same numbers
    rows = list(csv.DictReader(open(tmp_path / "cli" / "s_average.csv")))
    assert [float(x["gamma_mean"]) for x in rows] == list(r["gamma_mean"])
    assert [int(x["K_count"]) for x in rows] == list(r["K_count"])
    assert list(r["K_count"]) == [2] * len(r["t_from"])
    assert np.allclose(r["gamma_mean"], r["gamma"].mean(axis=0), rtol=1e-15, atol=0)
    again = ap.tail_scan(K="0.1,0.15", directory=tmp_path / "py", **SMALL)  # every K reused: the same summary
    assert all(np.array_equal(again[k], r[k], equal_nan=True) for k in ("P", "gamma", "gamma_error", "gamma_spread"))


def test_a_k_out_of_reach_is_listed_apart(tmp_path):
    # K = 1.3: no segment lasts 10^3 steps (docs/tail.md): its first level is out of reach, and the scan goes on.
    r = ap.tail_scan(K=[0.1, 1.3], directory=tmp_path, t_max=1e4, population=40, replicas=4, min_ancestors=4,
                     threads=2)
    assert list(r["K"]) == [0.1] and r["P"].shape[0] == 1
    assert list(r["out_of_reach_K"]) == [1.3]
    assert r["out_of_reach_reason"][0].endswith("give a lower first level")
    with pytest.raises(ValueError, match="no K of the scan reached its first level; K = 1.3: only .* [(]first[)]"):
        ap.tail_scan(K=[1.3], directory=tmp_path / "alone", t_max=1e4, population=40, replicas=4, threads=2)


def test_tail_scan_tasks_wait_for_each_other(tmp_path):
    r = ap.tail_scan(K=[0.1, 0.15], directory=tmp_path, task="1/2", **SMALL)
    assert list(r["waiting_for"]) == [0.1] and "gamma" not in r


@pytest.mark.parametrize("kwargs, error, words", [
    (dict(K="nan"), ValueError, "K: "),
    (dict(K=[0.1, 0.1]), ValueError, "twice"),
    (dict(K=0.1), TypeError, "sequence"),
    (dict(task="3/2"), ValueError, "task '3/2' must be I/N"),
    (dict(checkpoint_interval=-1), ValueError, "checkpoint_interval"),
    (dict(t_max=-5), ValueError, "t_max"),
])
def test_tail_scan_bad_input(tmp_path, kwargs, error, words):
    args = dict(SMALL, K=[0.1, 0.15], directory=tmp_path / "d")
    args.update(kwargs)
    with pytest.raises(error, match=words):
        ap.tail_scan(**args)
    assert not (tmp_path / "d").exists() or not any((tmp_path / "d").iterdir())


def test_a_box_that_cuts_the_island_is_a_warning(tmp_path):
    with pytest.warns(RuntimeWarning, match="K = 0.1: the box does not hold the central island"):
        r = ap.tail_scan(K=[0.1], directory=tmp_path, Xr=0.3, t_max=300, first=100, population=10, replicas=2)
    assert list(r["K"]) == [0.1]
