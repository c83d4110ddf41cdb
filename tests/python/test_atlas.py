"""The atlas from Python (issue 38): atlas() gives the tree of `archipelago-cli atlas --json` (the same numbers: both
format core's one JSON), its defaults are the request's, and bad input is a ValueError in core's words."""
import json
import subprocess

import pytest

import archipelago as ap


def test_atlas_equals_cli(cli):
    out = subprocess.run([cli, "atlas", "--K", "0.1", "--depth", "0", "--quiet", "--json", "/dev/stdout"],
                         capture_output=True, text=True, check=True, timeout=600)
    c = json.loads(out.stdout)
    p = ap.atlas(0.1, depth=0)
    for key in ("map", "request", "provenance"):
        assert p[key] == c[key], key
    strip = lambda nodes: [{k: v for k, v in n.items()} for n in nodes]
    assert strip(p["nodes"]) == strip(c["nodes"])
    assert p["nodes"][0]["boundary"]["found"] and p["nodes"][0]["area"] > 0


@pytest.mark.parametrize("kwargs, word", [({"depth": 99}, "depth"), ({"min_area": float("nan")}, "min area"),
                                          ({"max_period": 0}, "max period"), ({"scan_points": 1}, "scan points"),
                                          ({"threads": 100000}, "threads")])
def test_atlas_refuses_bad_input(kwargs, word):
    with pytest.raises(ValueError, match=word):
        ap.atlas(0.1, **kwargs)


def test_atlas_time_budget_and_resume():
    # A budget reached keeps the finished islands ('cancelled', 'stop_reason'); resume= continues to the end, the
    # same islands as an uninterrupted computation.
    part = ap.atlas(0.1, depth=1, max_period=40, scan_points=200, scan_steps=0, time_budget=1e-3)
    assert part["cancelled"] and "time budget" in part["stop_reason"]
    assert part["nodes"][0]["measured"] and not all(n["measured"] for n in part["nodes"])
    done = ap.atlas(0.1, depth=1, max_period=40, scan_points=200, scan_steps=0, resume=part)
    whole = ap.atlas(0.1, depth=1, max_period=40, scan_points=200, scan_steps=0)
    assert not done["cancelled"] and [n["path"] for n in done["nodes"]] == [n["path"] for n in whole["nodes"]]
    assert [n["area"] for n in done["nodes"]] == [n["area"] for n in whole["nodes"]]
    with pytest.raises(ValueError, match="depth"):
        ap.atlas(0.1, depth=2, max_period=40, scan_points=200, scan_steps=0, resume=part)
    with pytest.raises(ValueError, match="resume"):
        ap.atlas(0.1, depth=1, max_period=40, scan_points=200, scan_steps=0, resume={"format": "no"})
