#!/usr/bin/env bash
# Sets everything up on a fresh Debian 12 machine, builds, and starts the GUI with the paper's K = 0.1 preset.
# Extra arguments go to the application.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset default
cmake --build --preset default --parallel "$(nproc)"
exec build/default/app/gui/archipelago "$@"
