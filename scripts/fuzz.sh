#!/usr/bin/env bash
# Fuzzes the readers of untrusted input with libFuzzer (clang, ASan + UBSan): run files, run specs, CLI numbers, sessions, run manifests, tail files and their state behind a valid checksum.
#   bash scripts/fuzz.sh [SECONDS]     # each target for SECONDS (default 300); findings in build/fuzz/findings/
# A crash leaves its reproducer in build/fuzz/findings/<target>/; copy it into tests/fuzz/corpus/<target>/
# once fixed, so that the ordinary test suite replays it for ever (fuzz.corpus.<target>).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-300}"
bash scripts/install-deps.sh
cmake --preset fuzz
cmake --build --preset fuzz --parallel "$(nproc)"
status=0
for target in runfile runspec numbers session manifest tail tail_state; do
  work="build/fuzz/findings/$target"
  mkdir -p "$work/corpus" "$work/artifacts"
  cp -n tests/fuzz/corpus/"$target"/* "$work/corpus/" 2>/dev/null || true
  echo "== fuzz_$target for $seconds s"
  if ! "build/fuzz/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -max_len=65536 -artifact_prefix="$work/artifacts/" -print_final_stats=1 "$work/corpus"; then
    echo "fuzz_$target FOUND A FAILURE: reproducers in $work/artifacts" >&2
    status=1
  fi
done
exit $status
