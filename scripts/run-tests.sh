#!/usr/bin/env bash
# Sets everything up on a fresh Debian 12 machine and runs the whole test suite.
#   bash scripts/run-tests.sh            # the default (RelWithDebInfo) preset
#   bash scripts/run-tests.sh asan       # any preset of CMakePresets.json: dev, asan, tsan
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-default}"
bash scripts/install-deps.sh
cmake --preset "$preset"
cmake --build --preset "$preset" --parallel "$(nproc)"
ctest --preset "$preset" --parallel "$(nproc)" --timeout 1500
