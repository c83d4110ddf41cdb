#!/usr/bin/env python3
"""Compares the kernel benchmarks of two builds (e.g. before and after a change) as ratios measured in one run.

  python3 bench/compare-builds.py OLD/bench/kernel_benchmarks NEW/bench/kernel_benchmarks [ROUNDS] [FILTER]

Each benchmark of FILTER (default: the one-thread bare steps and pipelines of every kernel) runs in ROUNDS
(default 5) rounds; in each round the two binaries run it back to back, in alternating order (ABBA), so that a
slow period of a shared machine hits both alike.  Rates are per CPU second of the benchmark (process time),
which the co-tenants of a shared machine change less than wall time.  Printed: the median rate of each build and
the median of the per-round ratios new/old, with their [min-max]."""
import json, statistics, subprocess, sys, tempfile

old, new = sys.argv[1], sys.argv[2]
rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 5
pattern = sys.argv[4] if len(sys.argv) > 4 else r"^(bare_step/[a-z0-9]+/min|pipeline/[a-z0-9]+/q:[0-9]+/threads:1/)"

def names(binary):
    out = subprocess.run([binary, "--benchmark_list_tests", f"--benchmark_filter={pattern}"], capture_output=True,
                         text=True, check=True).stdout
    return [n for n in out.split() if n]

def rate(binary, name):
    with tempfile.NamedTemporaryFile(suffix=".json") as f:
        subprocess.run([binary, f"--benchmark_filter=^{name.replace('/', '/')}$", f"--benchmark_out={f.name}",
                        "--benchmark_out_format=json"], capture_output=True, check=True)
        b = json.load(open(f.name))["benchmarks"][0]
    # steps_per_iteration / cpu_time: steps of N^-1 per CPU second of the process (cpu_time is per iteration).
    unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
    return b["steps_per_iteration"] / (b["cpu_time"] * unit)

common = [n for n in names(new) if n in set(names(old))]
print(f"{len(common)} benchmarks, {rounds} rounds, ABBA order; rates in G steps of N^-1 per CPU second")
print(f"{'benchmark':64s} {'old':>8s} {'new':>8s}  new/old [min-max]")
for name in common:
    a, b, r = [], [], []
    for i in range(rounds):
        first, second = (old, new) if i % 2 == 0 else (new, old)
        x = rate(first, name)
        y = rate(second, name)
        ro, rn = (x, y) if first == old else (y, x)
        a.append(ro); b.append(rn); r.append(rn / ro)
    print(f"{name:64s} {statistics.median(a)/1e9:8.3f} {statistics.median(b)/1e9:8.3f}  "
          f"{statistics.median(r):.3f} [{min(r):.3f}-{max(r):.3f}]", flush=True)
