#!/usr/bin/env bash
# The GUI's screenshots in docs/images, made by the application itself (--screenshot) on a virtual screen:
# the first screen at 1280×800 and 1920×1080, each chaos-indicator mode, the manifolds layer with its turnstile and
# a deep zoom into its tangle, and the Statistics tab after a run (issues 25, 27, 28).  Look at them before
# committing: only a person can judge a picture.
#   bash scripts/gui-screenshots.sh [OUT_DIR]        (default docs/images; APP=… for another build;
#                                                     ONLY=REGEX makes only the shots whose name matches)
set -euo pipefail
cd "$(dirname "$0")/.."
app="${APP:-build/default/app/gui/archipelago}"
cli="${CLI:-build/default/app/archipelago-cli}"
out="${1:-docs/images}"
command -v xvfb-run >/dev/null || { echo "gui-screenshots: xvfb-run is missing (apt-get install xvfb)" >&2; exit 1; }
mkdir -p "$out"
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
chmod 700 "$home"

# shot SCREEN NAME SECONDS ARGS…: the window filling a SCREEN (less a title bar) after SECONDS.
shot() {
  local screen="$1" name="$2" seconds="$3"
  shift 3
  [[ -z "${ONLY:-}" || "$name" =~ $ONLY ]] || return 0
  local w="${screen%x*}" h="${screen#*x}"
  XDG_CONFIG_HOME="$home/config" XDG_DATA_HOME="$home/data" XDG_RUNTIME_DIR="$home" \
    xvfb-run -a -s "-screen 0 ${screen}x24" "$app" -qwindowgeometry "${w}x$((h - 30))+0+0" \
    --preset "K = 0.1, under a minute" --after "$seconds" --screenshot "$home/$name.png" "$@" >/dev/null
  # 256 colours: a few hundred kB per screen, the portraits' detail kept.
  convert "$home/$name.png" -colors 256 "PNG8:$out/$name.png"
  echo "wrote $out/$name.png"
}

shot 1280x800 gui-first-screen-1280x800 15 --run
shot 1920x1080 gui-first-screen-1920x1080 15 --run
for kind in dig rotation fli megno lyapunov; do
  shot 1280x800 "gui-indicator-$kind-1280x800" 40 --mode "$kind"
done
shot 1280x800 gui-manifolds-1280x800 10 --manifolds
# The folds of the tangle about the central island, then a view 0.014 wide at the first homoclinic point h of
# (√K, 0), with the entry lobe: the manifolds refined in the view.
shot 1280x800 gui-manifolds-zoom-1280x800 10 --manifolds --view=-0.80,-0.40,-0.46,0.14
shot 1280x800 gui-manifolds-tangle-1280x800 10 --manifolds --view=-0.688,-0.674,-0.371,-0.357
shot 1280x800 gui-statistics-1280x800 40 --run --tab Statistics
# Issue 37: a view 6.4·10⁻⁹ wide about x = −0.15 (findings 2 and 18: the axes name the reference once, the ticks
# are offsets); an orbit selected at the full view, its chain's centres ringed (finding 9) and the Orbits page's
# steps, N⁻¹ and typed start (finding 15).  The statistics shot above shows P_t's legend (finding 5), the first
# screen the Run page following the run (finding 1).
shot 1280x800 gui-deep-axes-1280x800 10 --view=-0.1500000032,-0.1499999968,-0.0000000025,0.0000000025
shot 1280x800 gui-orbit-chain-1280x800 10 --orbit=0.0609,0.0974
# Issue 37, the rest: a grid of 4 × 3 orbits launched at once from the Orbits page, each measured and listed
# (finding 15); the periodic orbit a Shift+click at (0.06, 0.0974) finds, its chain named in the status bar (16); the
# rotation profile from the centre's island into one of the six islands, its plateau labelled 1/6 (17); and the
# Statistics tab of a finished run file (K = 0.1, q = 4, 16 × 200 000 blocks) with the tail's γ_P and verdict under
# the summary, as `archipelago-cli stats` prints them (19).
shot 1280x800 gui-orbit-grid-1280x800 20 --orbits=-0.25,-0.05,0.05,0.1,4,3
shot 1280x800 gui-periodic-click-1280x800 15 --periodic=0.06,0.0974
shot 1280x800 gui-profile-plateaus-1280x800 25 --profile=-0.25,0,0.06,0.0974
# … and a profile across that island about its own centre (the period-6 orbit's member found there): the rotation of
# Q⁶, its plateau the chain of 23 islands about it (17).
shot 1280x800 gui-profile-island-1280x800 30 --periodic=0.06,0.0974 --profile=0.035,0.0974,0.075,0.0974 --view=0.0,0.1,0.06,0.14
if [[ -z "${ONLY:-}" || gui-statistics-tail-1280x800 =~ $ONLY ]]; then
  "$cli" run --K 0.1 --q 4 --T 200000 --M 16 --subsets 8 --seed 3 --out "$home/k01-q4.json" --quiet
  shot 1280x800 gui-statistics-tail-1280x800 20 --tab Statistics "$home/k01-q4.json"
fi
