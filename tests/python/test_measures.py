"""The orbit measures from Python (python/bind_measures.cpp) give the numbers of archipelago-cli `rotation` and
`indicator` for the same orbits, bit for bit; bad input raises ValueError; a progress callback can stop a map."""
import csv
import io
import json
import math
import subprocess

import numpy as np
import pytest

import archipelago as ap

P138 = (0.0360286533088399281481 + 1e-6, 0.0341809124510989600403)  # next to the elliptic period-138 orbit (§6)


@pytest.mark.parametrize("x, y", [P138, (-0.3, 0.0), (0.3, 0.3)])
def test_rotation_equals_cli_json(cli, x, y):
    out = subprocess.run([cli, "rotation", "--x", repr(x), "--y", repr(y), "--json"], capture_output=True, text=True,
                         check=True, timeout=1200).stdout
    assert ap.rotation(x, y) == json.loads(out)


def test_rotation_names_the_138_chain():
    r = ap.rotation(*P138)
    assert r["chain"]["period"] == 138 and r["chain"]["factors"] == [6, 23]
    assert r["chain"]["summary"].startswith("6 × 23 = 138, rotation 1/6 about the centre, 2/23 about its island")
    assert abs(r["rotation"] - 1 / 6) < 1e-13
    escaping = ap.rotation(0.3, 0.3)
    assert escaping["rotation"] is None and escaping["verdict"] == "escaping"


def test_indicator_equals_cli_npy(cli, tmp_path):
    view = (-0.4, 0.1, -0.2, 0.2)
    npy, verdicts = tmp_path / "r.npy", tmp_path / "v.npy"
    subprocess.run([cli, "indicator", "--kind", "rotation", f"--view={','.join(map(repr, view))}", "--size", "12x9",
                    "--iterations", "1000", "--npy", str(npy), "--verdicts", str(verdicts), "--quiet"],
                   check=True, timeout=1200)
    d = ap.indicator("rotation", view=view, width=12, height=9, iterations=1000, passes=3, kernel="scalar", threads=1)
    values = np.load(npy)
    assert d["values"].shape == (9, 12)
    assert np.array_equal(d["values"], values, equal_nan=True)
    assert np.array_equal(np.isnan(d["values"]), d["verdicts"] != 2)  # a number exactly for the regular orbits
    assert np.array_equal(d["verdicts"].astype(np.uint32), np.load(verdicts))
    assert d["metadata"]["kind"] == "rotation" and d["metadata"]["request"]["iterations"] == 1000


def test_profile_equals_cli_csv_and_orbit_measures(cli, tmp_path):
    path = tmp_path / "p.csv"
    subprocess.run([cli, "rotation", "--line=-0.31,0:0.25,0.05", "--points", "25", "--iterations", "1500", "--csv",
                    str(path), "--quiet"], check=True, timeout=1200)
    rows = list(csv.DictReader(io.StringIO("\n".join(l for l in path.read_text().splitlines() if not l.startswith("#")))))
    p = ap.rotation_profile((-0.31, 0.0), (0.25, 0.05), 25, iterations=1500)
    assert len(rows) == 25
    for i, row in enumerate(rows):
        assert (row["rotation"] == "") == math.isnan(p["rotation"][i])
        if row["rotation"]:
            assert float(row["rotation"]) == p["rotation"][i]
        assert ap.VERDICTS[int(p["verdict"][i])] == row["verdict"]
        assert row["rational"] == (f"{p['p'][i]}/{p['q'][i]}" if p["q"][i] else "")
    # The same starts (the grid points the profile printed) measured one by one.
    m = ap.orbit_measures("rotation", p["x"], p["y"], iterations=1500)
    assert np.array_equal(m["value"], p["rotation"], equal_nan=True)
    assert np.array_equal(m["verdict"], p["verdict"])


def test_bad_input_raises_value_error():
    with pytest.raises(ValueError, match=r"must lie in \(0, 1\)"):
        ap.rotation(-0.3, 0.0, K=1.5, xmin=-2.0)
    with pytest.raises(ValueError, match="must lie in the box"):
        ap.rotation(3.0, 0.0)
    with pytest.raises(ValueError, match="finite"):
        ap.rotation(float("nan"), 0.0)
    with pytest.raises(ValueError, match="kind must be one of"):
        ap.indicator("chaos")
    with pytest.raises(ValueError, match="raster size"):
        ap.indicator("dig", width=0)
    with pytest.raises(ValueError, match="view"):
        ap.indicator("dig", view=(-0.5, 2.0, 0.0, 0.1))
    with pytest.raises(ValueError, match="iterations"):
        ap.orbit_measures("fli", np.array([0.0]), np.array([0.0]), iterations=3)
    with pytest.raises(ValueError, match="same size"):
        ap.orbit_measures("fli", np.array([0.0, 1.0]), np.array([0.0]))
    with pytest.raises(ValueError, match="points = 0"):
        ap.rotation_profile((-0.3, 0.0), (0.1, 0.0), 0)


def test_an_exception_in_the_progress_callback_stops_the_map():
    calls = []

    def progress(d):
        calls.append(d["pixels_done"])
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        ap.indicator("dig", width=64, height=64, iterations=20000, passes=4, progress=progress)
    assert len(calls) == 1 and calls[0] < 64 * 64
