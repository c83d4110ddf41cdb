#!/usr/bin/env python3
"""The constants of the orbit measures' portable atan (core/measures/MeasureMath.inl, issue 41), recomputed.

atan u / u is interpolated in w = u^2 at the 8 Chebyshev nodes of [0, tan^2(pi/16)] (a near-minimax polynomial of
degree 7 in w), at 60 significant digits (mpmath), and the coefficients rounded to double; the script prints them
as C hexadecimal literals with the largest error of u * P(u^2) against atan u over the range, the rounded
coefficients used as they are.  It also prints the table of angle offsets (kAngleOffsetHi/Lo: alpha, pi/2 - alpha,
pi - alpha, pi/2 + alpha for alpha = 0, atan(kTanPi8), pi/4, each split into a double and its rounding error) and
the thresholds tan(pi/16), tan(3 pi/16).  Needs python3-mpmath.

Usage: scripts/atan-coefficients.py [TERMS]     (TERMS: 8, the value MeasureMath.inl uses)
"""
import sys

import mpmath as mp

mp.mp.dps = 60


def hexd(x: float) -> str:
    return float.hex(x)


def main() -> int:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 8
    top = mp.tan(mp.pi / 16) ** 2

    def f(w):  # atan(u)/u, u = sqrt(w)
        if w == 0:
            return mp.mpf(1)
        u = mp.sqrt(w)
        return mp.atan(u) / u

    nodes = [top / 2 * (1 + mp.cos(mp.pi * (2 * k + 1) / (2 * n))) for k in range(n)]
    c = mp.lu_solve(mp.matrix([[x ** j for j in range(n)] for x in nodes]), mp.matrix([f(x) for x in nodes]))
    coefficients = [float(c[j]) for j in range(n)]
    worst = max(abs(sum(mp.mpf(coefficients[j]) * w ** j for j in range(n)) - f(w)) * mp.sqrt(w)
                for w in (top * i / 4000 for i in range(4001)))
    print(f"// {n} terms; |u P(u^2) - atan u| <= {mp.nstr(worst, 3)} for |u| <= tan(pi/16)")
    print("kAtanCoefficients = {" + ", ".join(hexd(x) for x in coefficients) + "}")
    tau = mp.mpf(float.fromhex("0x1.a827999fcef32p-2"))  # kTanPi8, tan(pi/8) rounded to double
    # atan2Portable's offsets K at index j + 4 swapped + 8 (c < 0): alpha, pi/2 - alpha, pi - alpha, pi/2 + alpha
    # for alpha = 0, atan(kTanPi8), pi/4 (j = 0, 1, 2; j = 3 repeats j = 2), each a double and its rounding error.
    alphas = [mp.mpf(0), mp.atan(tau), mp.pi / 4, mp.pi / 4]
    his, los = [], []
    for c_negative in (0, 1):
        for swapped in (0, 1):
            for alpha in alphas:
                k = {(0, 0): alpha, (1, 0): mp.pi / 2 - alpha, (0, 1): mp.pi - alpha, (1, 1): mp.pi / 2 + alpha}
                value = k[(swapped, c_negative)]
                his.append(float(value))
                los.append(float(value - mp.mpf(his[-1])))
    print("kAngleOffsetHi = {" + ", ".join(hexd(x) for x in his) + "}")
    print("kAngleOffsetLo = {" + ", ".join(hexd(x) for x in los) + "}")
    print(f"kTanPi16 = {hexd(float(mp.tan(mp.pi / 16)))}, kTan3Pi16 = {hexd(float(mp.tan(3 * mp.pi / 16)))}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
