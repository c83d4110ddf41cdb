"""Portraits, b2, periodic orbits, island chains, the K scan and the Markov model from Python; references are
closed forms of the paper, not earlier output."""
import math

import numpy as np
import pytest

import archipelago as ap


@pytest.mark.parametrize("mode", ["density", "orbits", "stickiness"])
def test_portrait_every_mode(mode):
    r = ap.portrait(mode=mode, width=64, height=48, points=200000, orbits=16)
    assert r["points_iterated"] >= 200000
    key = {"density": "counts", "orbits": "labels", "stickiness": "mean_length"}[mode]
    assert r[key].shape == (48, 64)
    if mode == "density":
        assert r["counts"].sum() == r["points_binned"] > 0
    if mode == "stickiness":
        assert np.all(r["mean_length"] >= 0) and r["mean_length"].max() > 0


def test_stochastic_area_is_a_fraction_of_the_box():
    b = ap.stochastic_area(iterations=1 << 20, grid_bits=6, orbits=16)
    L = 0.5 - (-0.8)
    assert 0 < b["fraction"] < 1
    assert b["b2"] == pytest.approx(b["fraction"] * L * L, rel=1e-15)
    assert b["visited"].shape == (64, 64)
    assert b["visited"].sum() == b["boxes_visited"][-1]
    assert np.all(np.diff(b["boxes_visited"]) >= 0)  # the visited set only grows


def test_box_invariant_values():
    v = ap.box_invariant(0.1, -0.8, 0.5, 0.5, 100.0, 10.0)
    b2 = 0.5 * 1.3 ** 2
    assert v["b2_D"] == pytest.approx(b2 * 100, rel=1e-12)
    assert v["accelerator_factor"] == pytest.approx(8 / math.pi ** 2 * b2, rel=1e-12)  # section 6


def test_island_chain_of_an_orbit_near_the_central_island():
    K = 0.1
    # An orbit of Q (forward) close to the elliptic fixed point (-sqrt K, 0) turns at its linear rotation number:
    # trace DQ = 2 - 4 sqrt K = 2 cos(2 pi w0).
    o = ap.orbit(K, -0.8, 0.5, -math.sqrt(K) + 0.01, 0.0, steps=20000)
    c = ap.island_chain(K, o["x"], o["y"])
    w0 = math.acos(1 - 2 * math.sqrt(K)) / (2 * math.pi)
    assert c["period"] == 1
    assert abs(c["rotation_number"]) == pytest.approx(w0, rel=0.02)


def test_periodic_orbit_rotation_number_of_fixed_point():
    o = ap.periodic_orbit(0.1, 1, -0.31, 0.001)
    assert o["x"][0] == pytest.approx(-math.sqrt(0.1), abs=1e-15)
    assert o["closure"] < 1e-12


def test_k_scan_box_rule():
    xmin, xmax = ap.scan_box(0.1)
    assert xmin == pytest.approx(-2 * math.sqrt(0.1) - 0.2, rel=1e-15)
    assert xmax == pytest.approx(math.sqrt(0.1) + 0.2, rel=1e-15)
    assert ap.scan_values(0.0, 0.15, 0.05) == [0.0, 0.05, 0.1, 0.15]
    with pytest.raises(ValueError):
        ap.scan_box(-1)
    run = ap.start(K=0.1, xmin=xmin, xmax=xmax, T=2000, M=8, subsets=4)
    run.advance(threads=2)
    p = ap.scan_point(run, 0.5)
    assert p["blocks_done"] == p["blocks_total"] == 2000
    assert p["b2_D"] == pytest.approx(0.5 * (xmax - xmin) ** 2 * p["D"], rel=1e-12)


def test_markov_model_appendix_c():
    m, N = 20, 400
    r = ap.markov([m], N, tau_max=60)
    # One segment, h = 1 on T: epsilon(1) = (m - 1)/(N - m) exactly, C_is(tau) = (m - tau)/N, D_is = m^2/2N.
    assert r["epsilon"][1] == pytest.approx((m - 1) / (N - m), rel=1e-12)
    assert np.allclose(r["C_is"][:m + 1], (m - np.arange(m + 1)) / N, rtol=0, atol=1e-15)
    assert r["D_is"] == pytest.approx(m * m / (2 * N), rel=1e-15)
    assert r["D"] == pytest.approx(r["D_dmark"], rel=1e-12)
    with pytest.raises(ValueError):
        ap.markov([0], 10)
    with pytest.raises(ValueError):
        ap.markov([5], 3)
