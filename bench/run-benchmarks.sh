#!/usr/bin/env bash
# Builds the benchmarks (Release, no GUI, no tests) and prints the kernel speeds of issue 4 as ratios.
#
#   bench/run-benchmarks.sh [build-dir] [extra Google Benchmark options…]
#
# Every rate is shown twice: per wall-clock second (what a user gets) and per CPU second of the process (what
# the code does; the two differ when the machine is shared — compare the load average printed first).
# The raw results are kept in <build-dir>/kernel_benchmarks.json.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build-bench}"
shift || true

cmake -S "$here/.." -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DARCHIPELAGO_BUILD_GUI=OFF \
  -DARCHIPELAGO_BUILD_TESTS=OFF -DARCHIPELAGO_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$build" --target kernel_benchmarks -j2 >/dev/null

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)   CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
"$build/bench/kernel_benchmarks" --benchmark_out="$build/kernel_benchmarks.json" --benchmark_out_format=json \
  --benchmark_format=console "$@" >&2
echo "load average after:  $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$build/kernel_benchmarks.json" <<'PY'
import json, re, sys

scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
wall, cpu = {}, {}
for b in json.load(open(sys.argv[1]))["benchmarks"]:
    if b.get("run_type") != "iteration":
        continue
    name = re.sub(r"/(min_time|real_time|process_time).*$", "", b["run_name"])
    steps = b["steps_per_iteration"]
    wall[name] = steps / (b["real_time"] * scale[b["time_unit"]])
    cpu[name] = steps / (b["cpu_time"] * scale[b["time_unit"]])

def g(x): return f"{x / 1e9:7.3f} G/s"
def ratio(a, b, table):
    return table[a] / table[b] if a in table and b in table else float("nan")

print("\n== Bare step of N^-1 (48 orbits, 1 thread) ==       wall          per CPU second")
for n in [k for k in wall if k.startswith("bare_step/")] + ["naive_double"]:
    if n in wall:
        print(f"  {n:28s} {g(wall[n])}   {g(cpu[n])}")
for a, b in [("bare_step/avx512ifma", "bare_step/scalar"), ("bare_step/avx512ifma", "naive_double"),
             ("bare_step/scalar", "naive_double"), ("bare_step/avx2", "bare_step/scalar")]:
    print(f"  {a} / {b}: {ratio(a, b, wall):6.2f}x wall, {ratio(a, b, cpu):6.2f}x CPU")

print("\n== Trapping pipeline (runTrapping, K = 0.1 box, M = 256) ==")
print("  kernel       q  threads        wall      per CPU s   of bare step (1 thr)   2 thr / 1 thr (wall)")
kernels = sorted({n.split("/")[1] for n in wall if n.startswith("pipeline/")},
                 key=["avx512ifma", "avx2", "scalar"].index)
for k in kernels:
    for q in (1, 16, 100):
        for t in (1, 2):
            n = f"pipeline/{k}/q:{q}/threads:{t}"
            if n not in wall:
                continue
            frac_w = wall[n] / t / wall.get(f"bare_step/{k}", float("nan"))
            frac_c = cpu[n] / cpu.get(f"bare_step/{k}", float("nan"))
            scal = ratio(f"pipeline/{k}/q:{q}/threads:2", f"pipeline/{k}/q:{q}/threads:1", wall) if t == 2 else None
            print(f"  {k:11s} {q:3d}  {t:7d}  {g(wall[n])}  {g(cpu[n])}   {100 * frac_w:5.1f}% wall {100 * frac_c:5.1f}% CPU"
                  + (f"   {scal:5.2f}x" if scal else ""))
print("\n== Path ratios (pipeline, 1 thread) ==")
for q in (1, 16, 100):
    for a, b in [("avx2", "scalar"), ("avx512ifma", "scalar"), ("avx512ifma", "avx2")]:
        na, nb = f"pipeline/{a}/q:{q}/threads:1", f"pipeline/{b}/q:{q}/threads:1"
        if na in wall and nb in wall:
            print(f"  q={q:3d}  {a:10s} / {b:10s}: {ratio(na, nb, wall):6.2f}x wall, {ratio(na, nb, cpu):6.2f}x CPU")
PY
