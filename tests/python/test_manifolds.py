"""Manifolds and flux from Python (issue 28): the same numbers as archipelago-cli (flux --json, manifold CSV), arrays
that make sense, bad input as ValueError, and Ctrl-C stops a long branch."""
import _thread
import json
import math
import resource
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import archipelago as ap


@pytest.mark.parametrize("K", [0.05, 0.1, 0.2])
def test_flux_equals_cli(cli, K):
    out = subprocess.run([cli, "flux", "--K", str(K), "--json"], capture_output=True, text=True, check=True, timeout=600)
    c = json.loads(out.stdout)
    p = ap.flux(K)
    for section in ("lobe_area", "zone_area"):
        for key in ("action", "action_text", "polygon", "polygon_error", "polygon_raw", "agreeing_digits"):
            assert p[section][key] == c[section][key], (section, key)
    assert p["homoclinic_points"] == c["homoclinic_points"]
    assert p["flux_per_step"] == c["flux_per_step"]
    assert abs(p["lobe_area"]["action"] - p["lobe_area"]["polygon"]) <= 1e-9 * p["lobe_area"]["action"]


def test_flux_boundaries():
    f = ap.flux(0.1)
    assert len(f["zone_boundary"]) == 1  # the fixed point's loop: one closed curve
    zone = f["zone_boundary"][0]
    x, y = zone["x"], zone["y"]
    # The shoelace area of the drawn zone is its area (2048 vertices per arc: chords miss ~1e-7 of it).
    area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))
    assert abs(area - f["zone_area"]["action"]) < 1e-6 * area
    for lobe in ("entry_lobe", "exit_lobe", "lobe_boundary"):
        lx, ly = f[lobe]["x"], f[lobe]["y"]
        a = 0.5 * abs(np.dot(lx, np.roll(ly, -1)) - np.dot(np.roll(lx, -1), ly))
        assert abs(a - f["flux_per_step"]) < 1e-5 * a, lobe


def test_manifold_equals_cli_csv(cli, tmp_path):
    out = tmp_path / "m.csv"
    subprocess.run([cli, "manifold", "--K", "0.1", "--branch", "stable", "--length", "2", "--out", str(out)],
                   check=True, capture_output=True, timeout=600)
    rows = np.loadtxt(out, delimiter=",", comments="#", skiprows=0, dtype=str)
    data = np.array([[float(v) for v in r] for r in rows[1:]])  # rows[0] is the header s,x,y
    m = ap.manifold(0.1, branch="stable", length=2)
    assert len(m["x"]) == len(data) == m["points"]
    assert np.allclose(m["s"], data[:, 0], rtol=0, atol=1e-15)
    assert np.allclose(m["x"], data[:, 1], rtol=0, atol=1e-15)
    assert np.allclose(m["y"], data[:, 2], rtol=0, atol=1e-15)


def test_manifold_arrays():
    m = ap.manifold(0.1, length=30)
    assert m["pieces"] > 1 and m["breaks"] > 0
    assert set(np.unique(m["piece"])) == set(range(m["pieces"]))
    assert np.all(np.diff(m["s"]) >= 0)
    assert np.all(np.hypot(m["x"], m["y"]) <= 3)  # the escape radius
    assert m["origin"] == pytest.approx((math.sqrt(0.1), 0.0), abs=1e-16)
    six = ap.manifold(0.1, period=6, near=(0.0157, 0), length=1)
    assert six["period"] == 6 and six["side"] == "outward"


@pytest.mark.parametrize("kwargs, message", [
    (dict(K=float("nan")), "K = nan"),
    (dict(K=-1.0), "(0, 1]"),
    (dict(K=0.1, length=-1.0), "length = -1"),
    (dict(K=0.1, branch="up"), "branch 'up'"),
    (dict(K=0.1, side="left"), "side 'left'"),
    (dict(K=0.1, period=6), "guess"),
    (dict(K=0.1, period=6, near=(float("inf"), 0)), "near must be two finite numbers"),
    (dict(K=0.1, view=(0, 1)), "view must be"),
    (dict(K=0.1, box=(-0.8, 0.2)), "outside the box"),
])
def test_manifold_bad_input(kwargs, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        ap.manifold(**kwargs)


def test_flux_bad_input():
    with pytest.raises(ValueError, match="K = 2"):
        ap.flux(2.0)
    with pytest.raises(ValueError, match="entry samples = 0"):
        ap.flux(0.1, kac=True, kac_samples=0)


# Issue 36 class 4: --spacing 1e-17 (down to 1e-300) recursed for hours, 1e-16 ran to max_points; 10^8 points
# took ~12 GB unchecked.  Refused before work: the bound each exceeds (MemoryError under a 4 GiB address space).
@pytest.mark.parametrize("spacing", [1e-17, 1e-16, 1e-300])
def test_manifold_spacing_below_the_points_precision_is_refused_Issue36(spacing):
    with pytest.raises(ValueError, match=r"spacing = .* must lie in \[1e-14, 1\]"):
        ap.manifold(0.1, length=1, spacing=spacing)


def test_manifold_points_beyond_the_memory_are_refused_Issue36():
    code = """
import archipelago as ap, time
t = time.monotonic()
try:
    ap.manifold(0.1, length=1e6, spacing=1e-9, max_points=10 ** 8)
    print("no error")
except MemoryError as e:
    print("MemoryError", round(time.monotonic() - t, 2), str(e)[:120])
"""
    limit = 4 << 30
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=1200,
                       preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (limit, limit)))
    assert r.stdout.startswith("MemoryError") and "needs about" in r.stdout, r.stdout + r.stderr
    assert float(r.stdout.split()[1]) < 5  # before the work (which would take minutes)


# Issue 36 class 7: "lobe not resolved" and "no orbit found" were bare RuntimeErrors: now archipelago.NotFoundError,
# a ValueError (the input was in range, but has no answer).
def test_no_answer_is_not_found_error_Issue36():
    assert issubclass(ap.NotFoundError, ValueError)
    with pytest.raises(ap.NotFoundError, match="not resolved by __float128"):
        ap.flux(3e-4)
    with pytest.raises(ap.NotFoundError, match="no hyperbolic periodic orbit of period 7"):
        ap.manifold(0.1, period=7, near=(-0.3, 0.0), radius=1e-6, length=1)


def test_kac_from_python():
    k = ap.flux(0.2, kac=True, kac_samples=1500, kac_zone_samples=1500, kac_steps=1000, threads=2)["kac"]
    assert k["inconsistent_orbits"] == 0
    assert abs(k["discrepancy_sigmas"]) < 4


def test_ctrl_c_stops_a_long_branch():
    def interrupt():
        time.sleep(0.3)
        _thread.interrupt_main()

    threading.Thread(target=interrupt).start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        ap.manifold(0.1, length=1e6, spacing=1e-5, domains=10000, max_points=100_000_000, box=(-0.8, 0.5))
    assert time.monotonic() - t0 < 30


def test_cantorus_equals_cli(cli):
    """cantorus() is the dict of `archipelago-cli cantorus --json` (issue 40: the MacKay-Meiss-Percival flux)."""
    import json, subprocess
    out = subprocess.run([cli, "cantorus", "--convergents", "6/37,11/68,17/105", "--json"], capture_output=True,
                         text=True, check=True, timeout=600)
    c = json.loads(out.stdout)
    p = ap.cantorus(0.1, convergents=[(6, 37), (11, 68), (17, 105)])
    c.pop("seconds", None)
    assert p == c
    assert p["limit"]["value"] == p["terms"][-1]["flux"]
    with pytest.raises(ValueError, match="lowest terms"):
        ap.cantorus(0.1, convergents=[(2, 12)])
