#!/usr/bin/env python3
"""Issue 50: the atlas's central island at a K nobody tuned it for (K = 0.07, the box of the K scan's rule) against
an independent computation of its last invariant circle (scripts/atlas-validate.py: float64 numpy, its own map,
rotation numbers, rational test and polygon; nothing shared with core).  The atlas's interval [area_lower,
area_upper] must hold the independent area, area +- area_error must hold the interval, and the boundary's rotation
must name no rational of small denominator.

Usage: test_atlas_validation.py ARCHIPELAGO_CLI scripts/atlas-validate.py"""
import json, math, os, subprocess, sys, tempfile
from fractions import Fraction

K = 0.07


def main():
    cli, script = sys.argv[1], sys.argv[2]
    reference = json.loads(subprocess.run(
        [sys.executable, script, '--K', str(K), '--points', '1000', '--T', '4000', '--zooms', '3', '--json'],
        check=True, capture_output=True, text=True).stdout)
    xmin, xmax = -2 * math.sqrt(K) - 0.2, math.sqrt(K) + 0.2
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, 'atlas.json')
        # depth 1 with no chain followed (max period 1): the centre scanned finely, as in a depth-1 atlas
        subprocess.run([cli, 'atlas', '--K', str(K), '--xmin', repr(xmin), '--xmax', repr(xmax), '--depth', '1',
                        '--max-period', '1', '--quiet', '--json', out], check=True)
        with open(out) as f:
            atlas = json.load(f)
    c = atlas['nodes'][0]
    truth = reference['area']
    print(f"K = {K}: atlas [{c['area_lower']:.9g}, {c['area_upper']:.9g}] (circle {c['area']:.9g}, polygon "
          f"{c['polygon_error']:.1e}), independent {truth:.9g} (boundary rotation {reference['rotation']:.10f})")
    failures = []
    if not (c['area_lower'] <= truth <= c['area_upper']):
        failures.append(f"the interval [{c['area_lower']}, {c['area_upper']}] does not hold {truth}")
    if not (c['area'] - c['area_error'] <= c['area_lower'] and c['area_upper'] <= c['area'] + c['area_error']):
        failures.append("area +- area_error does not hold the interval")
    if not (c['area_upper'] - c['area_lower'] < 0.1 * c['area']):
        failures.append("the interval is wider than a tenth of the area: no bound worth printing")
    w = c['boundary']['rotation']
    q = Fraction(w).limit_denominator(200)
    if abs(w - q) < 1e-9:
        failures.append(f"the boundary's rotation {w} is {q}: a chain's orbit, not a circle")
    for f in failures:
        print('FAIL: ' + f)
    print(f"{4 - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
