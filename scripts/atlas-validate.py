#!/usr/bin/env python3
"""Independent check of the atlas's island areas (issue 50): the last invariant circle about an island of the quadratic
map  y' = y + 2(x^2 - K), x' = x + y'  (Karney 1983, eq. qu), found and measured by code that shares nothing with core.

For the central island (the elliptic fixed point (-sqrt K, 0)) and, with --chain p/q, for an island of the chain of
rotation p/q about it (its elliptic orbit found here by shooting along the symmetry lines and two-dimensional Newton in
float64): points of a symmetry line through the island's member c (y = 0, or y = K - x^2) are followed under Q^n in
float64 (numpy, vectorised over the points), and a point is taken as on an invariant circle about c when
  1. its rotation number about c (the weighted Birkhoff average of the angle's increments, weight exp(-1/(s(1-s))))
     agrees between two consecutive blocks of T iterates to --digits digits,
  2. no rational of denominator <= --qmax lies within 8 x that difference of it (an orbit of an island chain turns at a
     rational), and
  3. its orbit's polygon -- 2^14 points of its orbit under Q^n ordered by k w mod 1 -- has an area and a perimeter that
     agree with those of its first 2^13 points to --poly relative (a circle's converge as m^-2; a chain's orbit or a
     sticky chaotic orbit's do not).
The line is scanned outwards from c (--points points up to R), the outermost point passing all three is refined
against its outer neighbour, and then the stretch from it to the first point whose orbit leaves the island (farther
from c than R) is scanned again --zooms times, finer each time: circles beyond thin chains are found. The island's
area is the area of the outermost circle found (Green's theorem on its polygon), a lower estimate of the true area
by the band between it and the first escaping point, which is printed too.

Usage: /usr/bin/python3 scripts/atlas-validate.py --K 0.1 [--chain 1/6] [--json]     (numpy)
"""
import argparse, json, math, sys
import numpy as np


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--K', type=float, required=True)
    ap.add_argument('--chain', help='p/q: an island of the chain of rotation p/q about the centre, not the centre')
    ap.add_argument('--points', type=int, default=1500, help='points of the first scan')
    ap.add_argument('--T', type=int, default=6000, help='iterates of Q^n per block of the scan (the check: 4 x)')
    ap.add_argument('--digits', type=float, default=11.0)
    ap.add_argument('--qmax', type=int, default=4000)
    ap.add_argument('--poly', type=float, default=1e-6)
    ap.add_argument('--zooms', type=int, default=3)
    ap.add_argument('--json', action='store_true')
    return ap.parse_args(argv)


def line_point(K, line, x):
    return (x, 0.0 * x) if line == 2 else (x, K - x * x)


def advance(K, x, y, n):
    for _ in range(n):
        y = y + 2 * (x * x - K)
        x = x + y
    return x, y


def weights(T):
    s = (np.arange(T) + 0.5) / T
    w = np.exp(-1.0 / (s * (1.0 - s)))
    return w / w.sum()


def rotation(K, x, y, c, n, T, R):
    """Weighted Birkhoff averages of the turns about c per Q^n over two consecutive blocks of T iterates, vectorised:
    (w1, w2, escaped).  Escaped: the orbit went farther than R from c or overflowed."""
    x = np.array(x, dtype=float); y = np.array(y, dtype=float)
    w = weights(T)
    out = []
    escaped = np.zeros(x.shape, dtype=bool)
    th = np.arctan2(y - c[1], x - c[0])
    with np.errstate(all='ignore'):
        for _ in range(2):
            acc = np.zeros(x.shape)
            for k in range(T):
                x, y = advance(K, x, y, n)
                dx, dy = x - c[0], y - c[1]
                escaped |= ~(dx * dx + dy * dy <= R * R)
                x = np.where(escaped, c[0], x); y = np.where(escaped, c[1] + R / 2, y)
                t = np.arctan2(dy, dx)
                d = t - th
                d = (d + math.pi) % (2 * math.pi) - math.pi
                acc += w[k] * d
                th = t
            out.append(acc / (2 * math.pi))
    return out[0], out[1], escaped


def simplest(lo, hi, depth=0):
    """The rational of smallest denominator in [lo, hi], 0 <= lo <= hi (continued fractions): (p, q)."""
    fl = math.floor(lo)
    if lo == fl:
        return (fl, 1)
    if fl + 1 <= hi or depth > 60:
        return (fl + 1, 1)
    p, q = simplest(1.0 / (hi - fl), 1.0 / (lo - fl), depth + 1)  # x = fl + 1/y, y in [1/(hi-fl), 1/(lo-fl)]
    return (fl * p + q, p)


def smallest_denominator(lo, hi, qmax):
    p, q = simplest(lo, hi)
    return (p, q) if q <= qmax else None


def polygon(K, x, y, c, n, omega, m):
    xs = np.empty(m); ys = np.empty(m)
    for k in range(m):
        xs[k], ys[k] = x, y
        x, y = advance(K, x, y, n)
        if not (abs(x) < 10 and abs(y) < 10):
            return None
    def measure(count):
        key = (np.arange(count) * omega) % 1.0
        o = np.argsort(key)
        px, py = xs[:count][o] - xs[0], ys[:count][o] - ys[0]
        qx, qy = np.roll(px, -1), np.roll(py, -1)
        area = abs(np.sum(px * qy - qx * py)) / 2
        perimeter = np.sum(np.hypot(qx - px, qy - py))
        return area, perimeter
    return measure(m // 2), measure(m)


def verified(K, line, xs, c, n, R, args):
    """The circles among the candidate points xs (outermost first), by the three tests at 4 T: (index, info) of the
    first that passes, or None."""
    x, y = line_point(K, line, np.asarray(xs, dtype=float))
    w1, w2, esc = rotation(K, x, y, c, n, 4 * args.T, R)
    for i in range(len(xs)):
        diff = abs(w1[i] - w2[i])
        if esc[i] or (diff != 0 and -math.log10(diff) < args.digits):
            continue
        om = abs(w2[i]); delta = max(8 * diff, 1e-15)
        if smallest_denominator(max(om - delta, 0.0), om + delta, args.qmax) is not None:
            continue
        pg = polygon(K, float(x[i]), float(y[i]), c, n, om, 1 << 14)
        if pg is None:
            continue
        (a1, p1), (a2, p2) = pg
        if abs(a2 - a1) > args.poly * a2 or abs(p2 - p1) > 10 * args.poly * p2:
            continue
        return i, {'area': a2, 'polygon_change': abs(a2 - a1), 'rotation': om}
    return None


def classify(K, line, xs, c, n, R, args):
    """Per point: 'circle' candidate (regular, not rational), 'escape', or 'other'."""
    x, y = line_point(K, line, xs)
    w1, w2, esc = rotation(K, x, y, c, n, args.T, R)
    diff = np.abs(w1 - w2)
    kind = []
    for i in range(len(xs)):
        if esc[i]:
            kind.append('escape'); continue
        if diff[i] != 0 and -math.log10(diff[i]) < args.digits - 2:
            kind.append('other'); continue
        om = abs(w2[i]); delta = max(8 * diff[i], 1e-15)
        kind.append('other' if smallest_denominator(max(om - delta, 0), om + delta, args.qmax) else 'circle')
    return kind


def last_circle(K, line, c, n, direction, R, args, escape):
    """The outermost verified circle on one ray (radius = offset in x from c, up to R), zooming into the stretch
    between it and the first point whose orbit goes farther than `escape` from c; with that point's offset (the
    boundary lies between)."""
    R, scan = escape, R
    lo, hi, npts = 0.0, scan, args.points
    best, outer = None, None
    for zoom in range(args.zooms + 1):
        rs = lo + (hi - lo) * np.arange(1, npts + 1) / npts
        xs = c[0] + direction * rs
        kind = classify(K, line, xs, c, n, R, args)
        fe = next((i for i, k in enumerate(kind) if k == 'escape'), None)
        limit = fe if fe is not None else npts
        cands = [i for i in range(limit - 1, -1, -1) if kind[i] == 'circle']
        for b in range(0, len(cands), 16):
            v = verified(K, line, [xs[i] for i in cands[b:b + 16]], c, n, R, args)
            if v:
                i = cands[b + v[0]]
                if best is None or rs[i] > best[0]:
                    best = (rs[i], v[1])
                break
        if best is None:
            return None
        if fe is not None:
            outer = rs[fe] if outer is None else min(outer, rs[fe])
        if outer is None or outer - best[0] < 1e-12:
            break
        lo, hi, npts = best[0], outer, max(200, args.points // 3)
    return {'radius': best[0], 'first_escape': outer, **best[1]}


def symmetric_orbit(K, p, q, c):
    """An elliptic symmetric periodic orbit of rotation p/q about c: shooting along both lines, float64 scan of
    sign changes of the half-period offset, 2-D Newton on Q^q(z) - z, kept when it turns p times about c and is
    stable (|trace| < 2)."""
    found = []
    for line in (2, 1):
        for side in (-1, 1):
            s = c[0] + side * np.linspace(1e-4, 2 * math.sqrt(K), 200001)
            x, y = line_point(K, line, s)
            x = x.copy(); y = y.copy()
            if q % 2 == 0: steps, target = q // 2, line
            elif line == 2: steps, target = (q - 1) // 2, 1
            else: steps, target = (q + 1) // 2, 2
            with np.errstate(all='ignore'):
                for _ in range(steps):
                    y = y + 2 * (x * x - K); x = x + y
                f = y if target == 2 else y - (K - x * x)
            idx = np.nonzero(np.isfinite(f[:-1]) & np.isfinite(f[1:]) & (np.sign(f[:-1]) != np.sign(f[1:])))[0]
            for i in idx:
                z = refine(K, line, s[i], s[i + 1], q)
                if z is None:
                    continue
                orb, tr = z
                turns = turns_about(orb, c)
                if abs(turns - p) < 1e-6 and abs(tr) < 2:
                    found.append((orb, tr, line))
    return found


def refine(K, line, a, b, q):
    """Bisection of the shooting offset on [a, b] then Newton on Q^q - id; the orbit and the trace of DQ^q."""
    def off(s):
        x, y = line_point(K, line, s)
        if q % 2 == 0: steps, target = q // 2, line
        elif line == 2: steps, target = (q - 1) // 2, 1
        else: steps, target = (q + 1) // 2, 2
        for _ in range(steps):
            y = y + 2 * (x * x - K); x = x + y
            if abs(x) > 1e6: return float('nan')
        return y if target == 2 else y - (K - x * x)
    fa, fb = off(a), off(b)
    if not (np.isfinite(fa) and np.isfinite(fb)) or np.sign(fa) == np.sign(fb):
        return None
    for _ in range(80):
        m = (a + b) / 2
        fm = off(m)
        if not np.isfinite(fm): return None
        if np.sign(fm) == np.sign(fa): a, fa = m, fm
        else: b, fb = m, fm
    x, y = line_point(K, line, (a + b) / 2)
    x, y = float(x), float(y)
    for _ in range(8):
        X, Y, J = x, y, np.eye(2)
        for _ in range(q):
            Jstep = np.array([[1 + 4 * X, 1.0], [4 * X, 1.0]])
            Y = Y + 2 * (X * X - K); X = X + Y
            J = Jstep @ J
        F = np.array([X - x, Y - y])
        if not np.all(np.isfinite(F)): return None
        try:
            dz = np.linalg.solve(J - np.eye(2), -F)
        except np.linalg.LinAlgError:
            return None
        x, y = x + dz[0], y + dz[1]
        if np.hypot(*dz) < 1e-15: break
    pts = []
    X, Y, J = x, y, np.eye(2)
    for _ in range(q):
        pts.append((X, Y))
        J = np.array([[1 + 4 * X, 1.0], [4 * X, 1.0]]) @ J
        Y = Y + 2 * (X * X - K); X = X + Y
    if math.hypot(X - x, Y - y) > 1e-9: return None
    return pts, float(np.trace(J))


def turns_about(pts, c):
    tot = 0.0
    for i in range(len(pts)):
        a, b = pts[i], pts[(i + 1) % len(pts)]
        d = math.atan2(b[1] - c[1], b[0] - c[0]) - math.atan2(a[1] - c[1], a[0] - c[0])
        d = (d + math.pi) % (2 * math.pi) - math.pi
        tot += d
    return abs(tot) / (2 * math.pi)


def main(argv=None):
    args = parse(argv)
    K = args.K
    centre = (-math.sqrt(K), 0.0)
    if args.chain:
        p, q = (int(v) for v in args.chain.split('/'))
        orbits = symmetric_orbit(K, p, q, centre)
        if not orbits:
            print(f'atlas-validate: ERROR: no elliptic symmetric orbit of rotation {p}/{q} about the centre at K = {K}',
                  file=sys.stderr)
            return 1
        pts, trace, _ = orbits[0]
        # every member on a symmetry line: the island is measured about the one on a line, along that line
        n = q
        members = []
        for (mx, my) in pts:
            for line in (2, 1):
                off = my if line == 2 else my - (K - mx * mx)
                if abs(off) < 1e-9:
                    members.append((mx, my, line))
        spacing = min(math.hypot(a[0] - b[0], a[1] - b[1]) for i, a in enumerate(pts) for b in pts[i + 1:])
        R, escape = spacing / 2, spacing  # scanned to half the spacing; no island reaches the next member
        what = {'island': f'{p}/{q}', 'period': q, 'residue': (2 - trace) / 4}
    else:
        members = [(centre[0], 0.0, 2), (centre[0], K - centre[0] ** 2, 1)]
        n, R = 1, 2 * math.sqrt(K)
        escape = R  # the hyperbolic fixed point (sqrt K, 0) is 2 sqrt K from the centre
        what = {'island': 'centre', 'period': 1}
    results = []
    for (mx, my, line) in members:
        for direction in (1, -1):
            r = last_circle(K, line, (mx, my), n, direction, R, args, escape)
            if r:
                r.update({'line': f'S{line}', 'direction': direction, 'member': [mx, my]})
                results.append(r)
    if not results:
        print('atlas-validate: ERROR: no invariant circle found', file=sys.stderr)
        return 1
    best = max(results, key=lambda r: r['area'])
    out = {'K': K, **what, 'area': best['area'], 'polygon_change': best['polygon_change'],
           'rotation': best['rotation'], 'rays': results}
    if args.json:
        print(json.dumps(out, indent=1))
    else:
        print(f"K = {K}  {what['island']}: area {best['area']:.9g} (polygon change {best['polygon_change']:.1e}), "
              f"boundary rotation {best['rotation']:.12f}")
        for r in results:
            print(f"  {r['line']} {r['direction']:+d}: circle at {r['radius']:.9f} area {r['area']:.9g}, "
                  f"first escape {r['first_escape']}")
    return 0


if __name__ == '__main__':
    sys.exit(main())
