#!/usr/bin/env bash
# The exponent atlas of issue 55: the long runs behind docs/tail.md's "The exponent atlas" (hours on two cores; a
# benchmark, never CI, which runs a two-K scan to 10⁴ in cli.tail_scan).  Every stage is a tail-scan folder: a stage
# stopped (Ctrl-C, kill -9, the end of a batch job) resumes where it stood when the script runs again, and a finished
# one is reused (its summary printed again, the same bytes).
#
#   bench/tail-scan-atlas.sh [out-dir] [stage…]      stages: e8 (21 K to 10⁸), e9 (5 K to 10⁹), hi (21 K of
#                                                    0.3 … 1.3 to 10⁸), all (default: the three)
#   ARCHIPELAGO_CLI=build/default/app/archipelago-cli bench/tail-scan-atlas.sh /scratch/atlas e8
#
# Sizes: N = 800 walkers, R = 16 replicas (with N = 200, R = 4 several K lose their lineages before 10⁵ steps);
# the defaults' first level (1008 steps), q = 16, seed 1.  Stage hi runs the rest of the paper's section 5 range,
# K = 0.3 … 1.3 by 0.05 (the cheap K first): where the first level is out of reach (K = 0.3, 0.55 … 0.7, 1.2, 1.3) the
# pilot says so within seconds, the K's file keeps it, and the summary lists it apart (docs/tail.md).
# On a cluster: the same commands with `archipelago-mpi tail-scan` or `--task I/N` (docs/cluster/tail-scan-array.sbatch).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cli="${ARCHIPELAGO_CLI:-$here/../build/default/app/archipelago-cli}"
out="${1:-tail-scan-atlas}"
[[ $# -gt 0 ]] && shift
stages=("$@")
[[ ${#stages[@]} -eq 0 ]] && stages=(all)
mkdir -p "$out"

run_stage() {  # name, K list, t-max
  local name=$1 K=$2 tmax=$3 start
  start=$(date +%s)
  echo "== $name: K = $K to t = $tmax ($(date -u '+%F %H:%M UTC'), load $(cut -d' ' -f1-3 /proc/loadavg))"
  "$cli" tail-scan --K "$K" --dir "$out/$name" --population 800 --replicas 16 --t-max "$tmax" \
    --checkpoint-interval 300 --csv "$out/$name/summary" | tee "$out/$name.txt"
  echo "== $name: $(($(date +%s) - start)) s of wall time"
}

# K = 0.3:1.3:0.05, those whose stage 0 is long (P(1008) below 10⁻⁶) last.
hi_K=0.35,0.4,0.45,0.5,0.55,0.6,0.65,0.75,0.8,0.85,0.9,0.95,1,1.05,1.1,1.2,1.3,0.3,0.7,1.15,1.25

for stage in "${stages[@]}"; do
  case "$stage" in
    e8) run_stage e8 0.05:0.25:0.01 1e8 ;;
    e9) run_stage e9 0.05,0.1,0.15,0.2,0.25 1e9 ;;
    hi) run_stage hi "$hi_K" 1e8 ;;
    all) run_stage e8 0.05:0.25:0.01 1e8; run_stage e9 0.05,0.1,0.15,0.2,0.25 1e9; run_stage hi "$hi_K" 1e8 ;;
    *) echo "unknown stage '$stage': e8, e9, hi or all" >&2; exit 2 ;;
  esac
done
