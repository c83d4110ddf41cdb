#!/usr/bin/env bash
# Installs every Debian package Archipelago needs to build, test and run, Qt 6 and Qt 5 both, and makes a
# Qwt for Qt 6 available:
#   * the packaged one (libqwt-qt6-dev) when the system has it;
#   * otherwise one built from Debian's qwt source package by scripts/build-qwt-qt6.sh (a few minutes the
#     first time, cached in ~/.cache/archipelago, seconds afterwards).
# Writes the CMake arguments for that choice to build/qt-cmake-args (read by run-tests.sh and run-gui.sh).
# If no Qwt for Qt 6 can be had, it says which step failed and why, and chooses Qt 5 with a warning
# (build/qt-warning); with ARCHIPELAGO_REQUIRE_QT6=1 (CI) that is an error instead.
# ARCHIPELAGO_QT_MAJOR=5 chooses Qt 5 without building anything.
# Idempotent and non-interactive: safe to re-run. Needs root (or sudo) for apt-get only.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git
  qtbase5-dev qtbase5-dev-tools libqt5svg5-dev libqwt-qt5-dev
  qt6-base-dev qt6-base-dev-tools qt6-svg-dev qmake6 bzip2 binutils
  libgomp1 nlohmann-json3-dev libcli11-dev zlib1g-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  libsimde-dev  # core_tests: the AVX-512F kernel compiled on SIMDe, bit-identity tests on CPUs without AVX-512 (issue 41)
  xvfb xauth python3
  clang libclang-rt-14-dev libomp-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib  # the Python module (python/), its tests, examples/
  libopenmpi-dev openmpi-bin  # archipelago-mpi and its tests (issue #15); optional, CMake skips it without MPI
  slurm-wlm munge  # slurm.guide: the cluster guide's batch scripts on a one-node Slurm of the test's own (issue 31)
  python3-nbclient python3-ipykernel  # examples/*.ipynb executed by a test (issue 31)
  help2man appstream desktop-file-utils  # cmake --install: man pages; the metainfo and desktop entry validated
  python3-yaml  # install.citation reads CITATION.cff (issue 42)
  dpkg-dev lintian file  # the Debian package: cpack's DEB generator (dpkg-shlibdeps, file), checked by lintian (issue 42)
  ccache  # .ci/run: its Qt 5 build reuses the Qt 6 build's objects of core and the CLI (optional elsewhere)
  locales  # localedef: the tests write and read files under a decimal-comma locale (issue #23)
  imagemagick  # scripts/gui-screenshots.sh: convert makes the docs/images screenshots 256-colour PNGs
)

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

want_qt="${ARCHIPELAGO_QT_MAJOR:-6}"
# A Qwt for Qt 6 packaged by the distribution (Debian 14, Ubuntu) is preferred to building one.
packaged_qwt6=no
if [ "$want_qt" = 6 ] && grep -q 'Candidate: [0-9]' <<<"$(apt-cache policy libqwt-qt6-dev 2>/dev/null)"; then
  packages+=(libqwt-qt6-dev)
  packaged_qwt6=yes
fi

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
else
  echo "install-deps: installing ${missing[*]}"
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The Qt choice, as CMake arguments for build/qt-cmake-args.
mkdir -p build
rm -f build/qt-warning build/qwt-qt6-failure
export ARCHIPELAGO_QWT_FAILURE_FILE="$PWD/build/qwt-qt6-failure"
args=()
if [ "$want_qt" = 5 ]; then
  echo "install-deps: Qt 5 chosen by ARCHIPELAGO_QT_MAJOR=5"
  args=(-DARCHIPELAGO_QT_MAJOR=5)
elif [ "$packaged_qwt6" = yes ]; then
  echo "install-deps: Qt 6 with the packaged Qwt (libqwt-qt6-dev)"
  args=(-DARCHIPELAGO_QT_MAJOR=6 -DQWT_ROOT=)
elif prefix=$(bash scripts/build-qwt-qt6.sh | tail -n 1) && [ -n "$prefix" ]; then
  echo "install-deps: Qt 6 with the Qwt in $prefix"
  args=(-DARCHIPELAGO_QT_MAJOR=6 "-DQWT_ROOT=$prefix")
else
  if [ "${ARCHIPELAGO_REQUIRE_QT6:-0}" = 1 ]; then
    echo "install-deps: ERROR: no Qwt for Qt 6 (see above) and ARCHIPELAGO_REQUIRE_QT6=1" >&2
    exit 1
  fi
  reason="build-qwt-qt6.sh failed"
  [ -s build/qwt-qt6-failure ] && reason=$(cat build/qwt-qt6-failure)
  warning="WARNING: building with Qt 5, not Qt 6, because no Qwt for Qt 6 could be had: $reason"
  echo "install-deps: $warning" >&2
  echo "$warning" >build/qt-warning
  args=(-DARCHIPELAGO_QT_MAJOR=5)
fi
printf '%s\n' "${args[@]}" >build/qt-cmake-args
