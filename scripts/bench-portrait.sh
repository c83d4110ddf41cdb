#!/usr/bin/env bash
# Measures the portrait renderer: 10^8 points of the exact map into a 1024 x 1024 density raster.
# Target (issue 6): <= 1 s on 2 cores, i.e. >= 1e8 points/s.  Prints the wall-clock rate, the rate per
# CPU-second (what 2 idle cores would give, x2, when the machine is shared) and the ratios to the target.
#   bash scripts/bench-portrait.sh [build-dir]     (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
cmake --build "$build" --target bench_portrait >/dev/null
times=$(mktemp)
out=$( { /usr/bin/env time -f "%U %S" -o "$times" "$build/tests/bench_portrait" --benchmark_format=json; } 2>/dev/null)
python3 - "$out" "$(cat "$times")" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, sys
b = json.loads(sys.argv[1])["benchmarks"][0]
user, system = map(float, sys.argv[2].split())
rate, seconds, threads = b["points/s"], b["real_time"] / 1000.0, int(b["threads"])
per_cpu = 1e8 / (user + system)
print(f"portrait density 1024x1024, 1e8 points, {threads} threads (load average {sys.argv[3]}):")
print(f"  wall {seconds:.3f} s = {rate:.3g} points/s; ratio to the 1e8 points/s target: {rate / 1e8:.2f}")
print(f"  cpu  {user + system:.3f} s = {per_cpu:.3g} points per CPU-second; on {threads} idle cores "
      f"~{per_cpu * threads:.3g} points/s, ratio {per_cpu * threads / 1e8:.2f}")
PY
rm -f "$times"
