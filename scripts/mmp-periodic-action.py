#!/usr/bin/env python3
"""Independent check of core/manifolds/MmpFlux (issue 40): the MacKay-Meiss-Percival action difference
Delta W_{p/q} = |W(R > 0) - W(R < 0)| of the two Birkhoff (well-ordered) periodic orbits of type p/q about the centre
(-sqrt K, 0) of the quadratic map  y' = y + 2(x^2 - K), x' = x + y'  (Karney 1983, eq. qu), with
W = sum_k L(x_k, x_{k+1}),  L(x, x') = (x' - x)^2/2 + (2/3) x^3 - 2 K x.

Shares no code with core: the orbits are bracketed by a float64 scan (numpy) of the lines y = 0 and y = K - x^2 on both sides of the
centre (a symmetric orbit of this map has a point on one of them), each sign change of the half-period shooting function is kept when the float64 orbit has p
clockwise turns about the centre and is well ordered, and then refined by two-dimensional Newton on Q^q(z) - z in
mpmath (--dps digits, default 60), not by shooting along the line.  Prints p/q, both residues and Delta W.

About an island of a chain of period n instead (--about X,Y --stride n: a member of the chain's elliptic orbit): the
p/q orbits are orbits of period n*q whose every n-th point, from the one nearest (X, Y), turns p times about it (either
sense), is well ordered and follows the chain (its point nearest to the member m_a is followed by one nearest to
m_{a+1}); both lines are scanned within rmax of every member (an orbit about the islands may cross the lines at any of
them).

Usage: scripts/mmp-periodic-action.py [--K 0.1] [--K-long-double] [--dps 60] 1/6 5/31 6/37 11/68 17/105     (/usr/bin/python3: numpy, mpmath)
       scripts/mmp-periodic-action.py --K-long-double --about 0.0509024128,0.0974089444 --stride 6 --rmin 0.01 --rmax 0.05 1/12
"""
import argparse, math, sys
import numpy as np
import mpmath as mp

def parse():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--K', default='0.1')
    ap.add_argument('--K-long-double', action='store_true', help='K = the long double nearest --K (core: 0.1L)')
    ap.add_argument('--dps', type=int, default=60)
    ap.add_argument('--samples', type=int, default=400000, help='float64 scan points per side of the centre')
    ap.add_argument('--rmin', type=float, default=0.19)
    ap.add_argument('--rmax', type=float, default=0.44)
    ap.add_argument('--about', help='X,Y: a member of an island chain (default: the centre (-sqrt K, 0))')
    ap.add_argument('--stride', type=int, default=1, help="the chain's period n (with --about)")
    ap.add_argument('pq', nargs='+')
    return ap.parse_args()

def start(K, line, s):
    return (s, np.zeros_like(s)) if line == 2 else (s, K - s * s)

def shooting(K, line, s, q):
    """From (s, y_line(s)): the offset of the end of the half period from its target line, vectorised (float64).
    Line 2 is y = 0, line 1 is y = K - x^2 (the fixed lines of the map's two reversing involutions): even q goes back
    to the same line in q/2 steps, odd q from line 2 to line 1 in (q-1)/2 steps, from line 1 to line 2 in (q+1)/2."""
    x, y = start(K, line, s)
    x = x.copy(); y = y.copy()
    if q % 2 == 0: steps, target = q // 2, line
    elif line == 2: steps, target = (q - 1) // 2, 1
    else: steps, target = (q + 1) // 2, 2
    with np.errstate(all='ignore'):
        for _ in range(steps):
            y = y + 2 * (x * x - K)
            x = x + y
        return y if target == 2 else y - (K - x * x)

def orbit64(K, x, y, q):
    pts = []
    for _ in range(q):
        pts.append((x, y))
        y = y + 2 * (x * x - K); x = x + y
        if not (abs(x) < 1e3 and abs(y) < 1e3): return None
    return pts

def turns_and_order(pts, c, cy=0.0):
    """Clockwise turns about (c, cy), and whether the orbit is well ordered (every point moves the same number of places
    on in the clockwise order of the angles)."""
    q = len(pts)
    th = [math.atan2(py - cy, px - c) for px, py in pts]
    tot = 0.0
    for k in range(q):
        d = th[(k + 1) % q] - th[k]
        d = (d + math.pi) % (2 * math.pi) - math.pi
        tot -= d
    phi = [(-(t - th[0])) % (2 * math.pi) for t in th]
    order = sorted(range(q), key=lambda k: phi[k])
    pos = [0] * q
    for r, k in enumerate(order): pos[k] = r
    return round(tot / (2 * math.pi)), len({(pos[(k + 1) % q] - pos[k]) % q for k in range(q)}) == 1

def newton(K, x0, y0, q):
    """Q^q(z) = z by Newton's method in mpmath with the exact Jacobian of Q^q."""
    x, y = mp.mpf(x0), mp.mpf(y0)
    for _ in range(100):
        a, b, cc, d = mp.mpf(1), mp.mpf(0), mp.mpf(0), mp.mpf(1)
        u, v = x, y
        for _ in range(q):
            g1 = 4 * u
            a, b, cc, d = (1 + g1) * a + cc, (1 + g1) * b + d, g1 * a + cc, g1 * b + d
            v = v + 2 * (u * u - K); u = u + v
        fx, fy = u - x, v - y
        m11, m12, m21, m22 = a - 1, b, cc, d - 1
        det = m11 * m22 - m12 * m21
        dx = -(m22 * fx - m12 * fy) / det
        dy = -(-m21 * fx + m11 * fy) / det
        x, y = x + dx, y + dy
        if abs(dx) + abs(dy) < mp.mpf(10) ** (-(mp.mp.dps - 8)): break
    else:
        raise RuntimeError('Newton did not converge')
    return x, y, (2 - (a + d)) / 4

def action(K, x, y, q):
    W, pts = mp.mpf(0), []
    for _ in range(q):
        x1 = x + (y + 2 * (x * x - K))
        W += (x1 - x) ** 2 / 2 + 2 * x ** 3 / 3 - 2 * K * x
        y = x1 - x; x = x1
    return W, x, y

def main():
    a = parse()
    mp.mp.dps = a.dps
    # --K-long-double: K is the x87 long double nearest the decimal (64-bit significand), as core's 0.1L is
    K = mp.mpf(a.K)
    if a.K_long_double:
        e = mp.floor(mp.log(K, 2)); K = mp.nint(K * mp.mpf(2) ** (63 - e)) / mp.mpf(2) ** (63 - e)
    K64 = float(a.K); c, cy = -math.sqrt(K64), 0.0
    n = a.stride
    if a.about: c, cy = map(float, a.about.split(','))
    members = orbit64(K64, c, cy, n)  # the chain m_0 ... m_{n-1}: an orbit kept must follow it (each point's nearest
                                      # member followed by the next one's)
    def follows(pts):
        if n == 1: return True
        near = [min(range(n), key=lambda k: math.hypot(px - members[k][0], py - members[k][1])) for px, py in pts]
        return all(near[(i + 1) % len(near)] == (near[i] + 1) % n for i in range(len(near)))
    for text in a.pq:
        p, q0 = map(int, text.split('/'))
        q = n * q0
        found = {}
        if n == 1:
            # on line 1 the abscissa offset u = x - c gives a distance |u| sqrt(1 + (2 sqrt K - u)^2): scan u over the
            # same range (a superset of the radii wanted, as that factor is >= 1)
            ranges = [(line, c + sign * np.linspace(a.rmin / (1 if line == 2 else 1.5), a.rmax, a.samples))
                      for line, sign in ((2, 1), (2, -1), (1, 1), (1, -1))]
        else:
            # about a chain's islands: both lines wherever they pass any island within rmin ... rmax of its member
            ranges = []
            for mx, my in members:
                for line in (1, 2):
                    s = np.linspace(mx - a.rmax, mx + a.rmax, a.samples)
                    xs, ys = start(K64, line, s)
                    d = np.hypot(xs - mx, ys - my)
                    if np.any((d >= a.rmin) & (d <= a.rmax)): ranges.append((line, s))
        for line, s in ranges:
            f = shooting(K64, line, s, q)
            ok = np.isfinite(f[:-1]) & np.isfinite(f[1:]) & (np.sign(f[:-1]) != np.sign(f[1:]))
            for i in np.nonzero(ok)[0]:
                lo, hi, flo = s[i], s[i + 1], f[i]
                for _ in range(80):
                    m = (lo + hi) / 2
                    fm = shooting(K64, line, np.array([m]), q)[0]
                    if np.sign(fm) == np.sign(flo): lo, flo = m, fm
                    else: hi = m
                x0, y0 = start(K64, line, np.array([(lo + hi) / 2]))
                pts = orbit64(K64, float(x0[0]), float(y0[0]), q)
                if pts is None: continue
                j = min(range(n), key=lambda k: math.hypot(pts[k][0] - c, pts[k][1] - cy))
                turns, ordered = turns_and_order(pts[j::n], c, cy)
                if abs(turns) != p if n > 1 else turns != p: continue
                if not ordered or not follows(pts): continue
                try: x, y, R = newton(K, pts[0][0], pts[0][1], q)
                except (RuntimeError, ZeroDivisionError): continue
                W, xe, ye = action(K, x, y, q)
                closure = abs(xe - x) + abs(ye - y)
                found.setdefault(mp.nstr(W, 25), (R, W, closure, x))
        orbits = list(found.values())
        neg = [o for o in orbits if o[0] < 0]; pos = [o for o in orbits if o[0] > 0]
        if len(neg) != 1 or len(pos) != 1:
            print(text, 'not one orbit with R < 0 and one with R > 0:', [mp.nstr(o[0], 6) for o in orbits]); continue
        dW = pos[0][1] - neg[0][1]
        print('%s R(min) = %s R(minimax) = %s W(R<0) = %s W(R>0) = %s DeltaW = %s closure %s' % (
            text, mp.nstr(neg[0][0], 10), mp.nstr(pos[0][0], 10), mp.nstr(neg[0][1], 40), mp.nstr(pos[0][1], 40),
            mp.nstr(abs(dW), 36), mp.nstr(max(neg[0][2], pos[0][2]), 3)))

if __name__ == '__main__':
    main()
