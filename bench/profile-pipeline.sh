#!/usr/bin/env bash
# Where the AVX-512 IFMA trapping pipeline spends its time, per q: samples `perf record` takes in the block kernel
# (advanceGroup<Avx512Ifma, V>), split into the inner loop of q steps and the per-block work around it, the latter
# grouped by basic block and labelled by the instructions it contains (zone test, wrap test, segment ends, event
# binning, draw refresh).  For issue 30: run it on each CPU whose figures differ (docs/performance.md).
#
#   bench/profile-pipeline.sh [build-dir] [q …]        default build-bench, q = 100 16 1
#
# Needs `perf` (linux-perf) and the kernel_benchmarks target (built here like run-benchmarks.sh does).  The event is
# `cycles` where the CPU's counters are visible, else `cpu-clock` (a timer: guests often expose no counters); both
# give a time profile.  Samples skid by an instruction or a few, so shares of basic blocks mean something, shares of
# single instructions less.  One benchmark per q runs for ~2 s on one thread; nothing else is timed.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$here/../build-bench"
if [[ $# -gt 0 ]]; then build="$1"; shift; fi
qs=("$@")
[[ ${#qs[@]} -gt 0 ]] || qs=(100 16 1)
command -v perf >/dev/null || { echo "ERROR: perf not found (apt-get install linux-perf)" >&2; exit 1; }
cmake -S "$here/.." -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DARCHIPELAGO_BUILD_GUI=OFF \
  -DARCHIPELAGO_BUILD_TESTS=OFF -DARCHIPELAGO_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$build" --target kernel_benchmarks -j2 >/dev/null
event=cycles
if ! perf stat -e cycles true >/dev/null 2>&1 || perf stat -e cycles true 2>&1 | grep -q "not supported"; then
  event=cpu-clock
fi
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
echo "$(date -u '+%F %H:%M UTC')   load average: $(cut -d' ' -f1-3 /proc/loadavg)   event: $event   CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
for q in "${qs[@]}"; do
  if ! perf record -q -e "$event" -F 4000 -o "$out/q$q.data" -- "$build/bench/kernel_benchmarks" \
    --benchmark_filter="^pipeline/avx512ifma/q:$q/threads:1/" --benchmark_min_time=2 >"$out/q$q.log" 2>&1; then
    echo "ERROR: perf record failed at q = $q:" >&2
    tail -5 "$out/q$q.log" >&2
    exit 1
  fi
  symbol=$(perf report -i "$out/q$q.data" --stdio --sort symbol 2>/dev/null | grep -o 'archipelago::(anonymous namespace)::advanceGroup<archipelago::(anonymous namespace)::Avx512Ifma, [0-9]*>' | head -1)
  if [[ -z "$symbol" ]]; then echo "q = $q: no samples in the IFMA block kernel (is avx512ifma supported?)"; continue; fi
  share=$(perf report -i "$out/q$q.data" --stdio --sort symbol 2>/dev/null | grep -F "$symbol" | head -1 | awk '{print $1}')
  perf annotate -i "$out/q$q.data" --stdio --no-source -s "$symbol" 2>/dev/null >"$out/q$q.txt"
  python3 - "$out/q$q.txt" "$q" "$share" <<'PY'
import re, sys
rows = []
for line in open(sys.argv[1]):
    m = re.match(r"\s+([0-9.]+) :\s+([0-9a-f]+):\s+(\S+)\s*(.*)", line)
    if m:
        rows.append((int(m.group(2), 16), float(m.group(1)), m.group(3), m.group(4)))
rows.sort()
total = sum(p for _, p, _, _ in rows) or 1.0
jump = re.compile(r"^j[a-z]+$")
def target(ops):
    m = re.match(r"([0-9a-f]+)\b", ops)
    return int(m.group(1), 16) if m else None
# The inner loop of q steps: the shortest backward jump whose body holds at least three vpmadd52huq (one step of
# one vector) and no other backward jump.
best = None
for i, (a, _, ins, ops) in enumerate(rows):
    t = target(ops) if jump.match(ins) else None
    if t is None or t > a:
        continue
    body = [r for r in rows if t <= r[0] <= a]
    madds = sum(r[2] == "vpmadd52huq" for r in body)
    inner_jumps = sum(1 for r in body[:-1] if jump.match(r[2]) and (target(r[3]) or a + 1) <= r[0])
    if madds >= 3 and inner_jumps == 0 and (best is None or a - t < best[1] - best[0]):
        best = (t, a, madds)
if best is None:
    print(f"q = {sys.argv[2]}: inner loop not found"); sys.exit()
t, a, madds = best
inner = sum(p for x, p, _, _ in rows if t <= x <= a)
print(f"\nq = {sys.argv[2]}: the block kernel has {sys.argv[3]} of all samples; within it:")
print(f"  {100 * inner / total:5.1f} %  inner loop of q steps ({madds // 3} vectors of 8 orbits, "
      f"{sum(1 for x, _, _, _ in rows if t <= x <= a)} instructions, {t:x}-{a:x})")
# The rest, by basic block (split at jumps and jump targets), labelled by what it contains.
cuts = {t, a + 1}
for x, _, ins, ops in rows:
    if jump.match(ins):
        cuts.add(x + 1)
        if target(ops) is not None:
            cuts.add(target(ops))
blocks, cur = [], []
for r in rows:
    if r[0] in cuts and cur:
        blocks.append(cur); cur = []
    cur.append(r)
if cur:
    blocks.append(cur)
def label(b):
    ins = " ".join(r[2] + " " + r[3] for r in b)
    if "vpmullq" in ins: return "draw refresh (mix64: vpmullq)"
    if "vpcompressq" in ins: return "segment ends: tags, one-block counts, event compress"
    if "vptestmq" in ins: return "wrap test after the q steps"
    if "vpcmpleuq" in ins: return "zone test (X <= Xr) and masked draw add"  # atMost; below/atLeast are lt/nlt
    if "popcnt" in ins or "kmov" in ins: return "segment ends: masks and counts"
    if re.search(r"(add|inc)q?\s+\$0x1,0x[0-9a-f]+\(%rsp,%r[a-z0-9]+,8\)", ins): return "event binning"
    if "vpternlogq" in ins or "vpmadd52huq" in ins: return "steps outside the inner loop"
    return "other bookkeeping"
grouped = {}
for b in blocks:
    if t <= b[0][0] <= a:
        continue
    p = sum(r[1] for r in b)
    if p > 0:
        grouped.setdefault(label(b), []).append((p, b[0][0]))
for name, parts in sorted(grouped.items(), key=lambda kv: -sum(p for p, _ in kv[1])):
    s = sum(p for p, _ in parts)
    if 100 * s / total >= 0.3:
        print(f"  {100 * s / total:5.1f} %  {name} ({len(parts)} basic blocks)")
PY
done
