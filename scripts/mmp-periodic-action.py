#!/usr/bin/env python3
"""Exploratory (issue 40, deliverable D, not in core): the MacKay-Meiss-Percival action difference
Delta W = W(hyperbolic) - W(elliptic) of a chain's own period-n orbits (the atlas's points refined by Newton in mpmath,
L = (x' - x)^2/2 + 2(x^3/3 - K x)) against the atlas's turnstile flux.  Usage: scripts/mmp-periodic-action.py a.json
(K = 0.1).  Needs mpmath (/usr/bin/python3 has it)."""
import json, mpmath as mp
mp.mp.dps = 40
K = mp.mpf('0.1')
def step(x, y):
    y = y + 2*(x*x - K); x = x + y; return x, y
def orbit(p, n):
    pts=[p]
    for _ in range(n-1): pts.append(step(*pts[-1]))
    return pts
def refine(x, y, n):
    f = lambda x, y: [a - b for a, b in zip(orbit_end(x, y, n), (x, y))]
    return mp.findroot(lambda x, y: f(x, y), (mp.mpf(x), mp.mpf(y)))
def orbit_end(x, y, n):
    for _ in range(n): x, y = step(x, y)
    return x, y
def action(x, y, n):
    W = 0
    for _ in range(n):
        x1, y1 = step(x, y)
        W += (x1 - x)**2/2 + 2*(x**3/3 - K*x)
        x, y = x1, y1
    return W
import sys
a = json.load(open(sys.argv[1]))
for i in (1, 2, 3, 5, 6, 7):
    nd = a['nodes'][i]; n = nd['period']
    e = refine(*nd['centre'], n); h = refine(*nd['flux']['partner']['point'], n)
    We, Wh = action(e[0], e[1], n), action(h[0], h[1], n)
    print(nd['path'], n, 'W_h - W_e =', mp.nstr(Wh - We, 12), ' turnstile flux =', nd['flux']['flux_per_step'],
          ' ratio', mp.nstr((Wh - We)/nd['flux']['flux_per_step'], 8))
