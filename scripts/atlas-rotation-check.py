#!/usr/bin/env python3
"""Independent check of the p/q the atlas gives each chain about a chain's island (issue 50): the rotation of the
chain's orbit about its parent island's centre in the parent's return map M^n, recomputed from the atlas JSON with
code that shares nothing with core (its own map, its own Jacobian, its own angles; plain Python floats).

The map is Q (Karney 1983):  y' = y + 2(x^2 - K),  x' = x + y'.  For every node of the JSON whose parent is not the
centre (a chain of period n*q about an island of the parent's chain of period n):
  1. the parent's orbit c_0 ... c_(n-1) (elliptic fixed points of M^n, the islands' centres) is the parent's
     `centre` followed n - 1 steps, the chain's orbit its `centre` followed n q - 1 steps;
  2. about each member c_j of the parent whose cell holds the chain (each of the chain's points nearest it there is
     nearer c_j than any other member), the chain's point z_0 nearest c_j is followed with M^n for --steps times q
     steps (a point of the chain's own periodic orbit: its images stay in c_j's cell, q of them in turn);
  3. the angle of z_k - c_j is taken in the coordinates in which DM^n(c_j) is a rotation (its invariant quadratic
     form c x^2 + (d - a) x y - b y^2 of DM^n = [[a, b], [c, d]], made a circle by its Cholesky factor): the
     increments of an orbit about an elliptic point are nearest their mean there, while in (x, y) they spread over
     (-1/2, 1/2] turn about a long, thin island and fold (the island of six at K = 0.13 has residue 0.96);
  4. the increments, each taken in (-1/2, 1/2] turn, are summed (in the sense of the parent's `sense`, +1 clockwise):
     turns / steps is the rotation, p/q;
  5. independently of any unwrapping, the order of the q images by angle about c_j: z_k is the (k p mod q)-th from
     z_0 when the chain is p/q (the same in any linear coordinates); undecided when they are not well ordered or
     leave a gap of half a turn (q >= 3: they do not surround c_j).
The rotation about c_j is decided when every increment stays --margin clear of half a turn, the turns are a whole
number, the order is decided and the two agree.  A chain is AMBIGUOUS when it is decided about no member or two
members disagree, a MISMATCH when the decided p/q is not the atlas's `about_parent`; the exit status is 1 if any is.
The line printed for each chain gives the turns about the member nearest its `centre` and the p/q about each member
("-": undecided there).

Usage: python3 scripts/atlas-rotation-check.py atlas.json [--steps 1000] [--margin 0.05]
  e.g. archipelago-cli atlas --K 0.13 --depth 2 --max-period 150 --scan-steps 0 --json k013.json
       python3 scripts/atlas-rotation-check.py k013.json       (the chain "6 > 30": 2 turns in 5 steps of M^6, 2/5)
"""
import argparse
import json
import math
import sys
from fractions import Fraction


def step(K, x, y):
    y = y + 2.0 * (x * x - K)
    return x + y, y


def follow(K, p, count):
    x, y = p
    for _ in range(count):
        x, y = step(K, x, y)
    return x, y


def orbit(K, p, period):
    points = [tuple(p)]
    for _ in range(period - 1):
        points.append(step(K, *points[-1]))
    return points


def return_jacobian(K, c, n):
    """DM^n at c: the product of DM = [[1 + 4x, 1], [4x, 1]] along the orbit (x' = x + y', y' = y + 2(x^2 - K))."""
    a, b, cc, d = 1.0, 0.0, 0.0, 1.0
    x, y = c
    for _ in range(n):
        j11, j12, j21, j22 = 1.0 + 4.0 * x, 1.0, 4.0 * x, 1.0
        a, b, cc, d = j11 * a + j12 * cc, j11 * b + j12 * d, j21 * a + j22 * cc, j21 * b + j22 * d
        x, y = step(K, x, y)
    return a, b, cc, d


def normal_angle(K, c, n):
    """The angle about c in the coordinates in which DM^n(c) is a rotation (counter-clockwise, radians)."""
    a, b, cc, d = return_jacobian(K, c, n)
    s11, s12, s22 = cc, (d - a) / 2.0, -b  # the invariant quadratic form of [[a, b], [cc, d]]
    if s11 < 0:
        s11, s12, s22 = -s11, -s12, -s22
    det = s11 * s22 - s12 * s12
    if not (s11 > 0 and det > 0):
        raise ValueError(f"DM^{n} at {c} is not elliptic (trace {a + d})")
    l11 = math.sqrt(s11)
    l12 = s12 / l11
    l22 = math.sqrt(det) / l11

    def angle(p):
        u, v = p[0] - c[0], p[1] - c[1]
        return math.atan2(l22 * v, l11 * u + l12 * v)
    return angle


def unwrapped_turns(K, c, z0, n, steps, sense):
    """Turns of M^n's images of z0 about c in `steps` steps (in `sense`, +1 clockwise), and the largest |increment|."""
    angle = normal_angle(K, c, n)
    z = z0
    previous = angle(z)
    total, largest = 0.0, 0.0
    for _ in range(steps):
        z = follow(K, z, n)
        now = angle(z)
        inc = math.remainder(now - previous, 2 * math.pi) / (2 * math.pi)
        largest = max(largest, abs(inc))
        total += inc
        previous = now
    return -sense * total, largest  # counter-clockwise angles: clockwise positive when sense = +1


def order_shift(images, c, sense):
    """The shift s of the images' order about c in `sense` (z_k is the (k s mod q)-th from z_0), or None."""
    q = len(images)
    start = math.atan2(images[0][1] - c[1], images[0][0] - c[0])
    angles = []
    for k, p in enumerate(images):
        a = -sense * (math.atan2(p[1] - c[1], p[0] - c[0]) - start)
        angles.append((a % (2 * math.pi), k))
    angles.sort()
    position = [0] * q
    for r, (_, k) in enumerate(angles):
        position[k] = r
    shift = position[1 % q]
    if any((position[(k + 1) % q] - position[k]) % q != shift for k in range(q)):
        return None
    gaps = [(angles[(r + 1) % q][0] - angles[r][0]) % (2 * math.pi) for r in range(q)]
    if q >= 3 and max(gaps) >= math.pi:
        return None
    return shift


def about_member(K, chain, members, m, n, q, steps, sense, margin):
    """About the parent's member m: the chain's images nearest it, their turns unwrapped (step 4) and their order
    (step 5); (p/q or None, turns, largest increment, shift or None).  None unless the images lie in m's cell, the
    increments stay clear of half a turn, the order is decided and the two agree."""
    near = min(range(len(chain)), key=lambda i: math.dist(chain[i], m))
    images = [chain[(near + k * n) % len(chain)] for k in range(q)]
    if any(min(members, key=lambda mm: math.dist(mm, p)) != m for p in images):
        return None, math.nan, math.nan, None
    turns, largest = unwrapped_turns(K, m, images[0], n, steps * q, sense)
    shift = order_shift(images, m, sense)
    whole = round(turns)
    if largest > 0.5 - margin or abs(turns - whole) > 1e-6 or shift is None:
        return None, turns, largest, shift
    rotation = Fraction(whole, steps * q)
    if rotation.denominator != q or (rotation.numerator - shift) % q:
        return None, turns, largest, shift
    return rotation, turns, largest, shift


def check(data, steps, margin):
    K = data['map']['K']
    nodes = data['nodes']
    bad = 0
    for node in nodes:
        parent_index = node.get('parent', -1)
        if parent_index is None or parent_index <= 0:
            continue  # the centre, or a chain about the centre
        parent = nodes[parent_index]
        n = parent['period']
        q = node['period'] // n
        sense = parent['sense']
        members = orbit(K, parent['centre'], n)
        chain = orbit(K, node['centre'], node['period'])
        results = [about_member(K, chain, members, m, n, q, steps, sense, margin) for m in members]
        nearest = min(range(n), key=lambda j: math.dist(members[j], chain[0]))
        decided = {r[0] for r in results if r[0] is not None}
        label = node.get('about_parent')
        if len(decided) != 1:
            verdict = 'AMBIGUOUS'
        elif label is None or Fraction(label) != next(iter(decided)):
            verdict = 'MISMATCH'
        else:
            verdict = 'ok'
        if verdict != 'ok':
            bad += 1
        _, turns, largest, _ = results[nearest]
        print(f"{node['path']:<12} atlas {label or '-':>6}  measured {' '.join(str(d) for d in sorted(decided)) or '?':>6}"
              f"  {verdict:<9}  about the nearest member: {turns:.6f} turns in {steps * q} steps of M^{n} (largest "
              f"increment {largest:.3f});  p/q about each member: "
              f"{' '.join('-' if r[0] is None else str(r[0]) for r in results)}")
    return bad


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('json', help='the atlas JSON (archipelago-cli atlas --json)')
    ap.add_argument('--steps', type=int, default=1000, help='periods of the chain followed (q steps of M^n each)')
    ap.add_argument('--margin', type=float, default=0.05, help='an increment within this of half a turn is ambiguous')
    args = ap.parse_args(argv)
    with open(args.json, encoding='utf-8') as f:
        data = json.load(f)
    return 1 if check(data, args.steps, args.margin) else 0


if __name__ == '__main__':
    sys.exit(main())
