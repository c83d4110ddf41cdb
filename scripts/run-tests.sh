#!/usr/bin/env bash
# Sets everything up on a fresh Debian 12 machine and runs the whole test suite, with Qt 6 (Qt 5 when no Qwt
# for Qt 6 can be had: scripts/install-deps.sh says why).
#   bash scripts/run-tests.sh            # the default (RelWithDebInfo) preset
#   bash scripts/run-tests.sh asan       # any preset of CMakePresets.json: dev, asan, tsan, qt5
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-default}"
if [ "$preset" = qt5 ]; then export ARCHIPELAGO_QT_MAJOR=5; fi
bash scripts/install-deps.sh
mapfile -t qt_args <build/qt-cmake-args
# A fallback to Qt 5 is repeated at the end, where it is seen.
if [ -s build/qt-warning ]; then trap 'echo "run-tests: $(cat build/qt-warning)" >&2' EXIT; fi
cmake --preset "$preset" "${qt_args[@]}"
cmake --build --preset "$preset" --parallel "$(nproc)"
ctest --preset "$preset" --parallel "$(nproc)" --timeout 1500
