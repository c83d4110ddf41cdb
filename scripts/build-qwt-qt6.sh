#!/usr/bin/env bash
# Builds Qwt (>= 6.2, < 7) for Qt 6 from the upstream tarball of Debian's `qwt` source package, for systems
# that package Qwt only for Qt 5 (Debian 12 and 13).  Called by scripts/install-deps.sh; runs as any user.
#
#   bash scripts/build-qwt-qt6.sh        # prints the install prefix as the last line of stdout
#
# The prefix is ${ARCHIPELAGO_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/archipelago}/qwt-<first 16 hex digits of
# the tarball's SHA-256>: a second run finds it, checks it and takes seconds.  Steps:
#   1. the mirror: the first Debian archive in the system's own apt configuration (apt-get indextargets),
#      or ARCHIPELAGO_DEBIAN_MIRROR;
#   2. a private deb-src list for suite sid (trixie holds Qwt 6.1.4; ARCHIPELAGO_QWT_SUITES="s1 s2" tries others
#      in order) and private apt state in the cache directory; the
#      system's apt sources are never changed;
#   3. `apt-get source --print-uris qwt` gives the tarball's URL and SHA-256; apt-helper downloads it and
#      checks the hash (`apt-get source --download-only` fails because the .dsc answers 404);
#   4. qmake6 (must report Qt 6) builds the library only (no Designer plugin, examples, playground, tests,
#      polar plots, OpenGL canvas or pkg-config file) and installs it into a staging directory;
#   5. checks: the version is >= 6.2 and < 7, and libqwt.so links libQt6Widgets (readelf -d); only then is
#      the staging directory renamed to the prefix.
# When a step fails, the script says which one and why on stderr and exits with status 1.  If the archive
# cannot be reached but an earlier build passed its checks, that build is used (with a note).
set -euo pipefail

log() { echo "build-qwt-qt6: $*" >&2; }
step="start"
# The failure is also written to $ARCHIPELAGO_QWT_FAILURE_FILE when set (install-deps.sh repeats it later).
fail() {
  log "FAILED at step '$step': $*"
  [ -z "${ARCHIPELAGO_QWT_FAILURE_FILE:-}" ] || echo "build-qwt-qt6 failed at step '$step': $*" >"$ARCHIPELAGO_QWT_FAILURE_FILE"
  exit 1
}

cache="${ARCHIPELAGO_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/archipelago}"
mkdir -p "$cache" || fail "cannot create the cache directory $cache"
exec 9>"$cache/qwt-qt6.lock"
flock 9 || fail "cannot lock $cache/qwt-qt6.lock"

# A prefix passes when its stamp is there, its version is in range and the library links Qt 6 Widgets.
verify_prefix() {
  local prefix="$1" header="$1/include/qwt_global.h" lib="$1/lib/libqwt.so" version
  [ -f "$prefix/.archipelago-qwt-ok" ] || [ "${2:-}" = "fresh" ] || return 1
  [ -f "$header" ] && [ -e "$lib" ] || { log "no $header or $lib"; return 1; }
  version=$(sed -n 's/^#define QWT_VERSION_STR *"\([0-9.]*\)".*/\1/p' "$header")
  case "$version" in
    6.[2-9]*|6.[1-9][0-9]*) ;;
    *) log "Qwt version '$version' in $header is not >= 6.2 and < 7"; return 1 ;;
  esac
  local dynamic
  dynamic=$(readelf -d "$lib") || { log "readelf -d $lib failed"; return 1; }
  grep -q 'NEEDED.*\[libQt6Widgets\.so' <<<"$dynamic" || { log "$lib does not link libQt6Widgets"; return 1; }
  echo "$version"
}

current="$cache/qwt-qt6-current"   # symlink to the last prefix that passed its checks
use_previous() {
  local prefix version
  prefix=$(readlink -f "$current" 2>/dev/null) || return 1
  [ -d "$prefix" ] || return 1
  version=$(verify_prefix "$prefix") || return 1
  log "NOTE: $1; using the Qwt $version built earlier in $prefix"
  echo "$prefix"
  exit 0
}

# Step 1: the Debian mirror, from the system's own apt configuration.
step="find the Debian mirror"
mirror="${ARCHIPELAGO_DEBIAN_MIRROR:-}"
if [ -z "$mirror" ]; then
  targets=$(apt-get indextargets --format '$(REPO_URI) $(ORIGIN) $(LABEL)' 'Identifier: Packages' 2>/dev/null || true)
  mirror=$(awk '$2 == "Debian" && $3 == "Debian" { print $1; exit }' <<<"$targets")
  # Without release information (apt-get update never ran): the first archive that is not the security one.
  [ -n "$mirror" ] || mirror=$(awk '$1 !~ /security/ && $1 ~ /debian/ { print $1; exit }' <<<"$targets")
fi
[ -n "$mirror" ] || fail "no Debian archive in the system's apt sources (set ARCHIPELAGO_DEBIAN_MIRROR=URL)"
mirror="${mirror%/}"

# Step 2: a private deb-src list and private apt state; the system's apt sources are untouched.
step="read the qwt source package index"
aptdir="$cache/apt"
mkdir -p "$aptdir/lists/partial" "$aptdir/cache/archives/partial"
keyring=/usr/share/keyrings/debian-archive-keyring.gpg
signed=""; [ -f "$keyring" ] && signed=" signed-by=$keyring"
apt_opts=(-q -o Dir::Etc::SourceList="$aptdir/sources.list" -o Dir::Etc::SourceParts=-
          -o Dir::State::Lists="$aptdir/lists" -o Dir::Cache="$aptdir/cache"
          -o Acquire::Check-Valid-Until=false -o APT::Get::List-Cleanup=false)
[ "$(id -u)" -eq 0 ] && apt_opts+=(-o APT::Sandbox::User=root)
# One suite at a time: the first whose qwt is >= 6.2 and < 7 wins.
url=""; why=""
for suite in ${ARCHIPELAGO_QWT_SUITES:-sid}; do
  echo "deb-src [check-valid-until=no$signed] $mirror $suite main" >"$aptdir/sources.list"
  log "reading the qwt source package of $suite from $mirror"
  if ! out=$(apt-get "${apt_opts[@]}" update 2>&1); then
    why="$why [$suite] apt-get update of the private deb-src list failed: $(grep -E '^(E|W):' <<<"$out" | head -n 2 | tr '\n' ' ')"
    continue
  fi
  if ! uris=$(apt-get "${apt_opts[@]}" source --print-uris qwt 2>&1); then
    why="$why [$suite] apt-get source --print-uris qwt failed: $(tail -n 2 <<<"$uris" | tr '\n' ' ')"
    continue
  fi
  # A line of --print-uris: 'URL' FILE SIZE SHA256:HEX
  read -r url file size hash < <(grep -E "^'[^']+/qwt_[0-9.]+\.orig\.tar\.[a-z0-9]+' " <<<"$uris" | head -n 1) || true
  if [ -z "${url:-}" ]; then
    why="$why [$suite] no qwt_*.orig.tar.* in the answer of apt-get source --print-uris qwt"; url=""; continue
  fi
  version="${file#qwt_}"; version="${version%%.orig.*}"
  case "$version" in
    6.[2-9]*|6.[1-9][0-9]*) break ;;
    *) why="$why [$suite] holds Qwt $version; Qt 6 needs Qwt >= 6.2 and < 7"; url="" ;;
  esac
done
if [ -z "$url" ]; then
  use_previous "the qwt source package could not be read:$why" || true
  fail "$why"
fi
url="${url//\'/}"
sha="${hash#SHA256:}"
[[ "$hash" == SHA256:* && "$sha" =~ ^[0-9a-f]{64}$ ]] || fail "no SHA-256 for $file (got '$hash')"

prefix="$cache/qwt-${sha:0:16}"
if v=$(verify_prefix "$prefix" 2>/dev/null); then
  ln -sfn "$(basename "$prefix")" "$current"
  log "Qwt $v for Qt 6 already built in $prefix"
  echo "$prefix"
  exit 0
fi

# Step 3: the tarball, its SHA-256 checked by apt-helper.
step="download $file"
tarball="$cache/$file"
if [ ! -f "$tarball" ] || ! echo "$sha  $tarball" | sha256sum -c --status; then
  rm -f "$tarball"
  log "downloading $url ($size bytes)"
  helper_opts=(); [ "$(id -u)" -eq 0 ] && helper_opts=(-o APT::Sandbox::User=root)
  /usr/lib/apt/apt-helper "${helper_opts[@]}" download-file "$url" "$tarball.part" "SHA256:$sha" >&2 \
    || fail "apt-helper could not download $url with SHA-256 $sha"
  mv "$tarball.part" "$tarball"
fi

# Step 4: build with qmake6 for Qt 6.
step="check qmake6"
command -v qmake6 >/dev/null || fail "qmake6 not found (Debian package qmake6)"
qt_version=$(qmake6 -query QT_VERSION) || fail "qmake6 -query QT_VERSION failed"
[[ "$qt_version" == 6.* ]] || fail "qmake6 reports Qt '$qt_version', not Qt 6"

step="unpack $file"
work="$cache/qwt-build-${sha:0:16}"
rm -rf "$work" "$prefix.staging"
mkdir -p "$work"
tar -xf "$tarball" -C "$work" || fail "tar could not unpack $tarball"
src=$(find "$work" -mindepth 2 -maxdepth 2 -name qwtconfig.pri -printf '%h\n' | head -n 1)
[ -n "$src" ] || fail "no qwtconfig.pri in $tarball"

step="configure qwtconfig.pri"
config="$src/qwtconfig.pri"
sed -i -E \
  -e "s|^([[:space:]]*QWT_INSTALL_PREFIX[[:space:]]*=).*|\1 $prefix|" \
  -e 's/^([[:space:]]*QWT_CONFIG[[:space:]]*\+=[[:space:]]*(QwtDesigner|QwtExamples|QwtPlayground|QwtTests|QwtPolar|QwtOpenGL|QwtPkgConfig))[[:space:]]*$/# \1/' \
  "$config"
for feature in QwtDesigner QwtExamples QwtPlayground QwtTests QwtPolar QwtOpenGL QwtPkgConfig; do
  if grep -Eq "^[[:space:]]*QWT_CONFIG[[:space:]]*\+=[[:space:]]*$feature[[:space:]]*$" "$config"; then
    fail "could not turn off $feature in $config"
  fi
done
grep -Eq "^[[:space:]]*QWT_INSTALL_PREFIX[[:space:]]*=[[:space:]]*$prefix$" "$config" \
  || fail "could not set QWT_INSTALL_PREFIX in $config"

step="build Qwt $version with qmake6 (Qt $qt_version)"
jobs=$(nproc)
log "building Qwt $version for Qt $qt_version in $work ($jobs jobs; a few minutes)"
started=$(date +%s)
( cd "$src" && qmake6 qwt.pro && nice make -j"$jobs" ) >"$work/build.log" 2>&1 \
  || fail "qmake6/make failed; the last lines of $work/build.log: $(tail -n 5 "$work/build.log" | tr '\n' ' ')"

step="install Qwt $version into a staging directory"
staging="$prefix.staging"
( cd "$src" && make install INSTALL_ROOT="$staging" ) >>"$work/build.log" 2>&1 \
  || fail "make install failed; see $work/build.log"
[ -d "$staging$prefix" ] || fail "make install put nothing under $staging$prefix"
rm -rf "$staging$prefix/doc"   # 37 MB of HTML and man pages; the headers document the API

step="check the built Qwt"
v=$(verify_prefix "$staging$prefix" fresh) || fail "the built library does not pass its checks (see above)"
[ "$v" = "$version" ] || fail "qwt_global.h says $v but the tarball is $version"
printf 'qwt %s\nsha256 %s\nqt %s\nsource %s\n' "$version" "$sha" "$qt_version" "$url" \
  >"$staging$prefix/.archipelago-qwt-ok"
rm -rf "$prefix"
mv "$staging$prefix" "$prefix"
rm -rf "$staging" "$work"
ln -sfn "$(basename "$prefix")" "$current"
log "built Qwt $version for Qt $qt_version in $(( $(date +%s) - started )) s: $prefix ($(du -sh "$prefix" | cut -f1))"
echo "$prefix"
