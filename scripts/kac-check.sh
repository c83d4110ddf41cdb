#!/usr/bin/env bash
# The Kac check at full size (issue 28, docs/manifolds.md): for K = 0.05, 0.1, 0.2, the mean residence time of orbits
# started uniformly in the entry lobe of the fixed point's resonance zone against the zone's transit area divided by
# the flux, both at the horizon T, with their errors.  The unit tests run a small version (tests/core/manifolds).
#
#   scripts/kac-check.sh [build-dir] [samples] [T] [threads]      (defaults: build/default 100000 100000 0)
#
# Cost: the zone's points inside the regular islands never leave and run all T steps: about
# samples · T · (island fraction) steps of the plane map per K (9e9 at K = 0.05 with the defaults; a few minutes on
# two cores).  The JSON of each K is kept in <build-dir>/kac-check/.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build/default}"
samples="${2:-100000}"
steps="${3:-100000}"
threads="${4:-0}"
cli="$build/app/archipelago-cli"
[[ -x "$cli" ]] || { echo "ERROR: $cli not found (build the target archipelago-cli)" >&2; exit 1; }
out="$build/kac-check"
mkdir -p "$out"
echo "$(date -u '+%F %H:%M UTC')  samples $samples (entry lobe) + $samples (zone), T = $steps, load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-5s %-13s %-22s %-22s %-8s %-10s %-10s %s\n' K flux "<min(tau,T)> (entry)" "area(T)/flux (zone)" sigmas "trapped>T" "islands" seconds
for K in 0.05 0.1 0.2; do
  "$cli" flux --K "$K" --kac --kac-samples "$samples" --kac-zone-samples "$samples" --kac-steps "$steps" \
    --threads "$threads" --json --out "$out/kac-K$K.json" > /dev/null
  python3 - "$out/kac-K$K.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
k = d["kac"]
print(f"{d['K']:<5g} {d['lobe_area']['action']:<13.6e} "
      f"{k['mean_residence']:>9.2f} +- {k['mean_residence_error']:<8.2f} "
      f"{k['transit_area_over_flux']:>9.2f} +- {k['transit_area_over_flux_error']:<8.2f} "
      f"{k['discrepancy_sigmas']:<8.2f} {k['still_inside'] / k['entry_orbits']:<10.2e} {k['island_area']:<10.5f} {k['seconds']:.1f}")
PY
done
