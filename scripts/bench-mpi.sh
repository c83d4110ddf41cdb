#!/usr/bin/env bash
# Measures archipelago-mpi's scaling on this machine (issue #15, target: 2 ranks x 1 thread >= 0.95 x the
# single-process 2-thread rate), in one run of this script:
#   plain `archipelago-cli run --threads 2`, `archipelago-mpi` with 1 rank x 2 threads and with 2 ranks x 1 thread,
# on the same spec (1600 orbits, as the paper's runs), the configurations alternated R times (the machine is shared
# and noisy); checks that every run file agrees with the first (all but timing); prints each configuration's
# median rate and the ratios of the medians, the ratio of each repeat (2 ranks x 1 thread against the cli run
# just before it, so that a slow drift of the machine's load cancels) and their median, and projects the wall time of 1e14, 1e15 and 1e16 steps on N nodes
# of C cores at the measured per-core rate.
#
# The rates are the programs' own compute rates, measured inside them, so that mpirun's start (~0.4 s), MPI_Init,
# reading and writing files are outside: archipelago-cli's run-file `elapsedSeconds` (its chunks' compute time,
# one session), archipelago-mpi's "compute:" line (rank 0's MPI_Wtime from the barrier after every rank's setup
# to the end of the last round, synchronisation between rounds included, and how long the ranks idled waiting
# for the slowest at the rounds' ends).  The wall rates (launch included)
# are printed beside them.
#   bash scripts/bench-mpi.sh [build-dir] [T] [R]   (default: build/default, T = 20000000: 1.28e11 steps a run,
#                                                    about 20 s; R = 3 repeats)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/default}"
T="${2:-20000000}"
R="${3:-3}"
cmake --build "$build" --target archipelago-cli archipelago-mpi >/dev/null
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export OMPI_MCA_plm_rsh_agent=false  # one node: no ssh
python3 - "$build/app/archipelago-cli" "$build/app/archipelago-mpi" "$dir" "$T" "$R" <<'PY'
import json, re, statistics, subprocess, sys, time
cli, mpi, dir, T, R = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
spec = ["--K", "0.1", "--xmin", "-0.8", "--xmax", "0.5", "--q", "4", "--M", "1600", "--T", str(T)]
steps = 1600 * 4 * T
root = ["--allow-run-as-root"]  # harmless as another user; needed as root
def load(): return open("/proc/loadavg").read().split()[0]
# --bind-to none for threads > 1: OpenMPI binds each rank to one core by default (2 threads would share it).
configs = [("archipelago-cli run, 2 threads", [cli, "run", *spec, "--threads", "2"]),
           ("archipelago-mpi 1 rank x 2 threads", ["mpirun", "-n", "1", "--bind-to", "none", *root, mpi, *spec, "--threads", "2"]),
           ("archipelago-mpi 2 ranks x 1 thread", ["mpirun", "-n", "2", "--bind-to", "core", *root, mpi, *spec, "--threads", "1"])]
rates = [[] for _ in configs]   # in-program compute rates
walls = [[] for _ in configs]   # launch-included rates
idle = [[] for _ in configs]    # archipelago-mpi: % of the compute time the ranks waited for the slowest
loads = [load()]
reference, agree = None, True
print(f"spec: M = 1600, q = 4, T = {T}: {steps:.3g} steps a run; {R} repeats, configurations alternated", flush=True)
for rep in range(R):
    for i, (name, argv) in enumerate(configs):
        out = f"{dir}/run.json"
        t = time.monotonic()
        r = subprocess.run(argv + ["--out", out], check=True, capture_output=True, text=True)
        wall = time.monotonic() - t
        content = json.load(open(out))
        if i == 0:
            seconds = content["elapsedSeconds"]
        else:
            m = re.search(r"^compute: (\S+) steps in (\S+) s.*idle (\S+)% ", r.stderr, re.M)
            assert m and float(m.group(1)) == steps, r.stderr
            seconds = float(m.group(2))
            idle[i].append(float(m.group(3)))
        rates[i].append(steps / seconds)
        walls[i].append(steps / wall)
        content = {k: v for k, v in content.items() if k not in ("elapsedSeconds", "checksum", "kernel", "program")}
        reference = reference or content
        agree = agree and content == reference
        loads.append(load())
        waited = f", ranks idle {idle[i][-1]:.2f}%" if i else ""
        print(f"  repeat {rep + 1}: {name:36s} compute {seconds:7.2f} s  {steps / seconds:.4g} steps/s   "
              f"(wall {wall:6.2f} s, {steps / wall:.4g} steps/s; load {loads[-1]}{waited})", flush=True)
med = [statistics.median(x) for x in rates]
wmed = [statistics.median(x) for x in walls]
print(f"load average (1 min) before and after each run: {' '.join(loads)}")
print("every run file agrees with the first (all but timing):", agree)
for (name, _), m, w in zip(configs, med, wmed):
    print(f"median {name:36s} {m:.4g} steps/s compute   ({w:.4g} steps/s wall)")
print(f"ratio 1 rank x 2 threads / cli 2 threads:  {med[1] / med[0]:.3f}   (wall: {wmed[1] / wmed[0]:.3f})")
print(f"ratio 2 ranks x 1 thread / cli 2 threads:  {med[2] / med[0]:.3f}   (wall: {wmed[2] / wmed[0]:.3f})   target >= 0.95")
print(f"2 ranks x 1 thread: the ranks idle, waiting for the slowest at the rounds' ends: "
      f"{' '.join(f'{x:.2f}%' for x in idle[2])} of the compute time")
print(f"ratio 2 ranks x 1 thread / 1 rank x 2 thr: {med[2] / med[1]:.3f}   (wall: {wmed[2] / wmed[1]:.3f})")
paired = [b / a for a, b in zip(rates[0], rates[2])]  # each against the cli run just before it: drift cancels
print("per repeat, 2 ranks x 1 thread / cli 2 threads:", " ".join(f"{x:.3f}" for x in paired),
      f"  median {statistics.median(paired):.3f}   (target >= 0.95)")
per_core = med[2] / 2
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
