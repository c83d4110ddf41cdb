#!/usr/bin/env bash
# GUI soak (issue #13): the real window under Xvfb at 1280×800, driven at random for MINUTES (default 30):
# keys, clicks, wheel zooms, drags, runs, pauses, stops, exports, run files, presets, bad field values, the
# periodic-orbit dialog; dialogs answered at random.  Fails on a crash, a hang (a watchdog inside sees the GUI
# thread stop for 20 s) or a run stuck in pausing/stopping for a minute; prints resident memory and the live heap every minute and their growth after the first minute.
#   bash scripts/gui-soak.sh [MINUTES] [SEED]
set -euo pipefail
cd "$(dirname "$0")/.."
minutes="${1:-30}"
seed="${2:-1}"
if [ ! -f build/default/CMakeCache.txt ]; then
  bash scripts/install-deps.sh
  mapfile -t qt_args <build/qt-cmake-args
  cmake --preset default "${qt_args[@]}"
fi
cmake --build build/default --target gui_soak --parallel "$(nproc)"
command -v xvfb-run >/dev/null || { echo "gui-soak: xvfb-run is missing (apt-get install xvfb)" >&2; exit 1; }
log="build/gui-soak-$(date +%Y%m%d-%H%M%S).log"
set +e
xvfb-run -a -s "-screen 0 1280x800x24" build/default/tests/gui/gui_soak --minutes "$minutes" --seed "$seed" 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
set -e
if [ "$status" -ne 0 ]; then
  echo "gui-soak: FAILED (exit status $status); log: $log" >&2
  exit 1
fi
growth=$(sed -n 's/.*; RSS .* growth after minute 1 \([-0-9.]*\) MiB; heap.*/\1/p' "$log" | tail -1)
heap=$(sed -n 's/.*heap growth after minute 1 \([-0-9.]*\) MiB.*/\1/p' "$log" | tail -1)
echo "gui-soak: passed; growth after the first minute: resident ${growth} MiB (limit 100), live heap ${heap} MiB; log: $log"
awk -v g="$growth" 'BEGIN { exit !(g < 100) }' || { echo "gui-soak: memory grew by ${growth} MiB" >&2; exit 1; }
