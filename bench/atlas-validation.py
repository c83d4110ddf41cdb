#!/usr/bin/env python3
"""The atlas (issue 38) against independent measurements: a benchmark, minutes to an hour on two cores; its output
is the validation table of docs/atlas.md.  Usage:

    PYTHONPATH=build/default/python python3 bench/atlas-validation.py [--atlas a.json] [--quick]

 1. Residence times against the orbits themselves.  By Kac's lemma (core/manifolds/KacCheck.hpp) the orbits that
    enter a chain's zone through its turnstile stay on average (zone − its invariant islands) / flux steps: the
    atlas's `residence`.  The Kac check starts orbits uniformly in the entry lobe — the visits of the run process
    (the trapping engine) enter exactly so (tests/core/manifolds/test_chain_flux_trapping.cpp ties the two for the
    chain of six) — and follows them with the plane map to T steps: ⟨min(τ, T)⟩.  The layer of a zone holds the
    zones of its chains, entered through their own, much smaller turnstiles and left only after ~10⁴–10⁶ steps: a
    sample of a few thousand visits sees them rarely, so its mean converges to the zone's *own* layer (the layer
    less its outermost child's layer, child zones being nested) / flux, and to the whole layer / flux only when
    T and the sample are large enough to see the rare deep visits.  Both are printed.
 2. The sum rule: the box's area L² less every island of the atlas (period × area, each island counted once: a
    chain's islands lie outside its parent's boundary circle) against b₂ (stochastic_area: the boxes of a
    2^g × 2^g grid the randomized orbits visit), for depth 0, 1, 2 and grids g = 10, 11, 12 (a box that an
    island's edge crosses counts as visited: b₂ is high by about half a box along every island's edge).
 3. Two more K: the top level of the atlas against `rotation` (the chain's name from a point inside its island)
    and `flux` run by hand at the chain's island.
"""
import argparse
import json
import math
import sys
import time

import archipelago as a

p = argparse.ArgumentParser()
p.add_argument("--atlas", help="an atlas of K = 0.1, depth 2 (archipelago-cli atlas --json); else computed here")
p.add_argument("--quick", action="store_true", help="fewer orbits and a shorter T (a smoke run)")
args = p.parse_args()
started = time.time()

if args.atlas:
    with open(args.atlas, encoding="utf-8") as f:
        atlas = json.load(f)
else:
    atlas = a.atlas(0.1, depth=2)
nodes = atlas["nodes"]
K = atlas["map"]["K"]
L = atlas["map"]["xmax"] - atlas["map"]["xmin"]
print(f"# atlas of K = {K}: {len(nodes)} islands, depth {atlas['request']['depth']}, {atlas['seconds']:.0f} s")


paper = [n for n in nodes if n["path"] == "6 > 138" and n["about_parent"] == "2/23"]
print(f"# the paper's example (section 6): the chain 1/6 about the centre and 2/23 about its island, period 138: "
      f"{'found' if paper else 'NOT FOUND'}" + (f", area {paper[0]['area']:.4g}, flux "
                                                f"{(paper[0]['flux'] or {}).get('flux_per_step')}" if paper else ""))
print(f"# levels: {sorted(set(n['level'] for n in nodes))}; islands per level: "
      f"{[sum(1 for n in nodes if n['level'] == l) for l in sorted(set(n['level'] for n in nodes))]}")


def flux_of(n):
    f = n.get("flux") or {}
    return f if f.get("found") else None


# 1. Residence times.
print("\n## 1. Mean residence per visit: the atlas against orbits entering through the turnstile (Kac check)")
samples, T = (1000, 20000) if args.quick else (2000, 1000000)
print(f"# {samples} orbits from each entry lobe, followed to T = {T} steps (plane map)")
print("| island | level | flux | layer | own layer | atlas: layer/flux | own layer/flux | orbits: <min(tau,T)> | still inside at T |")
print("|---|---|---|---|---|---|---|---|---|")
for i, n in enumerate(nodes):
    f = flux_of(n)
    if f is None or n["level"] > 2:
        continue
    kids = [nodes[c] for c in n["children"] if flux_of(nodes[c])]
    # Nested zones: the outermost child's zone holds the others'; its layer is the part of ours behind a child barrier.
    deepest = max((flux_of(c)["layer_area"] for c in kids), default=0.0)
    own = f["layer_area"] - deepest
    if i == 0:
        r = a.flux(K, kac=True, kac_samples=samples, kac_zone_samples=1, kac_steps=T)
    else:
        r = a.flux(K, period=n["period"], near=tuple(n["centre"]), radius=1e-3, kac=True, kac_samples=samples,
                   kac_zone_samples=1, kac_steps=T)
    k = r["kac"]
    assert abs(r["flux_per_step"] - f["flux_per_step"]) <= 1e-9 * f["flux_per_step"], "flux differs from the atlas's"
    print(f"| {n['path']} | {n['level']} | {f['flux_per_step']:.4g} | {f['layer_area']:.4g} | {own:.4g} | "
          f"{f['residence']:.4g} | {own / f['flux_per_step']:.4g} | {k['mean_residence']:.4g} ± "
          f"{k['mean_residence_error']:.2g} | {k['still_inside']} of {k['entry_orbits']} |", flush=True)

# 2. The sum rule.
print("\n## 2. Sum rule: box area less the islands against b2")
islands_by_depth = {}
for d in range(atlas["request"]["depth"] + 1):
    islands_by_depth[d] = sum(n["period"] * n["area"] for n in nodes if n["level"] <= d and n.get("area") is not None
                              and (n.get("boundary") or {}).get("found"))
for d, s in islands_by_depth.items():
    print(f"# depth {d}: islands {s:.6f}, L^2 - islands = {L * L - s:.6f}")
iters = 1 << (28 if args.quick else 31)
print(f"| grid | iterations | b2 (area) | L^2 - islands (depth {max(islands_by_depth)}) | difference | half a box along the edges |")
print("|---|---|---|---|---|---|")
deepest_sum = islands_by_depth[max(islands_by_depth)]
for g in (10, 11) if args.quick else (10, 11, 12):
    b = a.stochastic_area(K, atlas["map"]["xmin"], atlas["map"]["xmax"], iterations=iters, grid_bits=g)
    area = b["b2"]
    # The edge band: each island's boundary is ~ 2 sqrt(pi area) long; half a box of width L/2^g along it.
    edges = sum(n["period"] * 2 * math.sqrt(math.pi * n["area"]) for n in nodes
                if n.get("area") is not None and (n.get("boundary") or {}).get("found")) * 0.5 * L / 2 ** g
    print(f"| {2 ** g} | {iters} | {area:.6f} | {L * L - deepest_sum:.6f} | {area - (L * L - deepest_sum):+.6f} | "
          f"{edges:.6f} |", flush=True)

# 3. Two more K.
print("\n## 3. The top level at two more K, against rotation and flux by hand")
print("| K | chain | p/q | island area | atlas flux | flux by hand | rotation's name of a point inside the island |")
print("|---|---|---|---|---|---|---|")
for K2 in (0.05, 0.2):
    t2 = a.atlas(K2, depth=1, max_period=200)
    for n in t2["nodes"][1:]:
        f = flux_of(n)
        hand = a.flux(K2, period=n["period"], near=tuple(n["centre"]), radius=1e-3) if f else None
        if (n.get("boundary") or {}).get("found"):
            # a point halfway between the centre and the boundary circle: inside the island
            (bx, by), (cx, cy) = n["boundary"]["point"], n["centre"]
            name = a.rotation((cx + bx) / 2, (cy + by) / 2, K2)["chain"]["summary"]
        else:
            name = "(no boundary circle measured)"
        print(f"| {K2} | {n['path']} | {n['about_parent']} | {n.get('area') or float('nan'):.4g} | "
              f"{f['flux_per_step'] if f else float('nan'):.6g} | "
              f"{hand['flux_per_step'] if hand else float('nan'):.6g} | {name} |", flush=True)
print(f"\n# {time.time() - started:.0f} s")
