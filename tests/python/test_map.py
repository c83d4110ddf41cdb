"""The exact map from Python: coefficients, N and N^-1 as inverses, J, the fixed point (appendix B)."""
import math

import numpy as np
import pytest

import archipelago as ap


def test_coefficients_follow_appendix_b():
    c = ap.coefficients(0.1, -0.8, 0.5)
    L = 0.5 - (-0.8)  # in double, as docs/design.md, "Arithmetic contract", orders it
    # A = round(2L 2^(52-m)), B = round(-4 xmin 2^(52-m)), computed independently here.
    assert c["m"] == 2  # a = 2.6 < 4, b = 3.2 < 4
    assert c["A"] == math.floor(2 * L * 2 ** 50 + 0.5)  # llround: halves away from 0
    assert c["B"] == math.floor(3.2 * 2 ** 50 + 0.5)


def test_forward_and_backward_are_inverse():
    f = ap.orbit(0.1, -0.8, 0.5, -0.5, 0.1, steps=1000)
    b = ap.orbit(0.1, -0.8, 0.5, X0=int(f["X"][-1]), Y0=int(f["Y"][-1]), steps=1000, backward=True)
    assert np.array_equal(b["X"][::-1], f["X"]) and np.array_equal(b["Y"][::-1], f["Y"])


def test_elliptic_fixed_point_stays_put():
    K = 0.1
    o = ap.orbit(K, -0.8, 0.5, -math.sqrt(K), 0.0, steps=10)
    assert np.max(np.abs(o["x"] + math.sqrt(K))) < 1e-14
    assert np.max(np.abs(o["y"])) < 1e-14


def test_involution_squares_to_one():
    o = ap.orbit(0.1, -0.8, 0.5, -0.5, 0.1, steps=100)
    X, Y = ap.involution(o["X"], o["Y"])
    X2, Y2 = ap.involution(X, Y)
    assert np.array_equal(X2, o["X"]) and np.array_equal(Y2, o["Y"])


def test_periodic_orbit_of_period_one_has_paper_residue():
    # The elliptic fixed point (-sqrt K, 0): trace DQ = 2 - 4 sqrt K, so R = sqrt K.
    o = ap.periodic_orbit(0.1, 1, -0.3, 0.0)
    assert o["residue"] == pytest.approx(math.sqrt(0.1), rel=1e-12)
    assert o["stable"]


def test_theory_and_statistics_shapes():
    t = np.array([1.0, 10.0, 100.0])
    s = ap.segment_shape(t, 0.1)
    assert s.shape == (3,) and np.all(np.isfinite(s))
    with pytest.raises(ValueError, match="t = nan"):
        ap.segment_shape(np.array([1.0, np.nan]), 0.1)
    with pytest.raises(ValueError, match="t = -1"):
        ap.correlation_shape(-1.0, 0.1)
    with pytest.raises(ValueError, match="K = inf"):
        ap.segment_shape(1.0, np.inf)
