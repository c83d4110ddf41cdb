#!/usr/bin/env bash
# Sets everything up on a fresh Debian 12 machine, builds with Qt 6 (Qt 5 when no Qwt for Qt 6 can be had:
# scripts/install-deps.sh says why), and starts the GUI with the paper's K = 0.1 preset.
# Extra arguments go to the application.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
mapfile -t qt_args <build/qt-cmake-args
cmake --preset default "${qt_args[@]}"
cmake --build --preset default --parallel "$(nproc)"
if [ -s build/qt-warning ]; then echo "run-gui: $(cat build/qt-warning)" >&2; fi
exec build/default/app/gui/archipelago "$@"
