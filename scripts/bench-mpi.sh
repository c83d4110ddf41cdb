#!/usr/bin/env bash
# Measures archipelago-mpi's scaling on this machine (issue #15, item 7), in one run:
#   plain `archipelago-cli run --threads 2`, `archipelago-mpi` with 1 rank x 2 threads and with 2 ranks x 1 thread,
# on the same spec (1600 orbits, as the paper's runs), checks that the three run files agree (all but timing),
# prints the rates and their ratios (target: 2 ranks x 1 thread >= 0.95 x the single-process 2-thread rate), and
# projects the wall time of 1e14, 1e15 and 1e16 steps on N nodes of C cores at the measured per-core rate.
#   bash scripts/bench-mpi.sh [build-dir] [T]     (default: build/default, T = 4000000: 2.56e10 steps a run)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/default}"
T="${2:-4000000}"
cmake --build "$build" --target archipelago-cli archipelago-mpi >/dev/null
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export OMPI_MCA_plm_rsh_agent=false  # one node: no ssh
python3 - "$build/app/archipelago-cli" "$build/app/archipelago-mpi" "$dir" "$T" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, subprocess, sys, time
cli, mpi, dir, T, load = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5]
spec = ["--K", "0.1", "--xmin", "-0.8", "--xmax", "0.5", "--q", "4", "--M", "1600", "--T", str(T), "--quiet"]
steps = 1600 * 4 * T
root = ["--allow-run-as-root"]  # harmless as another user; needed as root
# --bind-to none for threads > 1: OpenMPI binds each rank to one core by default (2 threads would share it).
runs = [("archipelago-cli run, 2 threads", [cli, "run", *spec, "--threads", "2"]),
        ("archipelago-mpi 1 rank x 2 threads", ["mpirun", "-n", "1", "--bind-to", "none", *root, mpi, *spec, "--threads", "2"]),
        ("archipelago-mpi 2 ranks x 1 thread", ["mpirun", "-n", "2", "--bind-to", "core", *root, mpi, *spec, "--threads", "1"])]
rates, files = [], []
for i, (name, argv) in enumerate(runs):
    out = f"{dir}/run{i}.json"
    t = time.monotonic()
    subprocess.run(argv + ["--out", out], check=True)
    wall = time.monotonic() - t
    rates.append(steps / wall)
    files.append({k: v for k, v in json.load(open(out)).items() if k not in ("elapsedSeconds", "checksum", "kernel", "program")})
    print(f"{name:38s} {wall:7.2f} s wall (launch included)  {steps / wall:.3g} steps/s")
print(f"spec: M = 1600, q = 4, T = {T}: {steps:.3g} steps a run; load average before: {load}")
print("the three run files agree (all but timing):", all(f == files[0] for f in files))
print(f"ratio 1 rank x 2 threads / cli 2 threads:  {rates[1] / rates[0]:.3f}")
print(f"ratio 2 ranks x 1 thread / cli 2 threads:  {rates[2] / rates[0]:.3f}   (target >= 0.95)")
print(f"ratio 2 ranks x 1 thread / 1 rank x 2 thr: {rates[2] / rates[1]:.3f}")
per_core = rates[2] / 2
print(f"\nprojected wall time at {per_core:.3g} steps/s per core (2 ranks x 1 thread here), perfect scaling assumed:")
def fmt(s):
    for unit, n in (("d", 86400), ("h", 3600), ("min", 60)):
        if s >= n: return f"{s / n:.3g} {unit}"
    return f"{s:.3g} s"
print(f"| nodes x cores | {'| '.join(f'{s:>10s} ' for s in ('1e14 steps', '1e15 steps', '1e16 steps'))}|")
print("|---|---|---|---|")
for nodes, cores in [(1, 2), (1, 64), (10, 64), (100, 64), (1000, 64)]:
    print(f"| {nodes} x {cores} | " + " | ".join(f"{fmt(s / (per_core * nodes * cores)):>10s}" for s in (1e14, 1e15, 1e16)) + " |")
PY
