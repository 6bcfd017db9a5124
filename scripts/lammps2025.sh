#!/usr/bin/env bash
# The modern test target on Debian 12: LAMMPS 4 Feb 2025 (Debian 13's source package) built
# from source with the packages this product uses, our library built against it, and the
# whole test suite run with that lmp and its Python module.
#
#   bash scripts/lammps2025.sh [pytest arguments]     (the whole suite, tests/, unless the
#                                                     arguments name test files)
#   TYLMP_LAMMPS2025_NO_TESTS=1 bash scripts/lammps2025.sh   (build only, no pytest)
#   TYLMP_TEST_HALF=2025 bash scripts/lammps2025.sh           (what scripts/test.sh runs: only the
#                                                     tests whose outcome can depend on the
#                                                     LAMMPS version, tests/lammps_halves.py)
#
# The LAMMPS build is installed under $TYLMP_CACHE (default ~/.cache/tylmp), in a directory
# named by the LAMMPS version and a hash of its configuration, and reused by later runs: a
# changed configuration builds anew. Our library is built in build-lammps2025/ (or
# $TYLMP_LAMMPS2025_BUILD_DIR) and the Python package with it installed with pip into a virtual
# environment in that LAMMPS prefix (tylmp/venv: also its `tyanalysis` command).
# The last line of output is the path of a wrapper that runs this lmp with the library and
# Python paths set: any deck with the two loader lines runs against 4 Feb 2025 through it.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"

LAMMPS_DATE=20250204                         # LAMMPS "4 Feb 2025"
DEB_SOURCE=lammps
DEB_UPSTREAM=20250204+dfsg.1                 # Debian 13 (trixie): lammps 20250204+dfsg.1-N
DEB_ORIG="lammps_$DEB_UPSTREAM.orig.tar.xz"
CACHE="${TYLMP_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tylmp}"
JOBS="${TYLMP_JOBS:-$(nproc)}"

# the LAMMPS configuration: GRANULAR (pair granular, gran/*, compute contact/atom), PYTHON
# (the deck loader lines), PLUGIN (plugin load), EXTRA-FIX (fix deform/pressure); MPI,
# smallbig integers and -O2 like Debian's package; a shared liblammps for the Python module
LAMMPS_CONFIG=(
  -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG"
  -DBUILD_SHARED_LIBS=ON -DBUILD_MPI=ON -DBUILD_OMP=OFF -DLAMMPS_SIZES=smallbig
  -DPKG_GRANULAR=ON -DPKG_PYTHON=ON -DPKG_PLUGIN=ON -DPKG_EXTRA-FIX=ON
  -DPython_EXECUTABLE=/usr/bin/python3
  -DWITH_JPEG=OFF -DWITH_PNG=OFF -DWITH_FFMPEG=OFF -DWITH_CURL=OFF
)
key="$(printf '%s\n' "$DEB_UPSTREAM" "${LAMMPS_CONFIG[@]}" | sha256sum | cut -c1-10)"
PREFIX="$CACHE/lammps-$LAMMPS_DATE-$key"
SRC="$CACHE/lammps-$LAMMPS_DATE-src"
log() { echo "lammps2025: $*" >&2; }

fetch_source() {
  # a private apt configuration with only the trixie deb-src entry: the system's sources
  # stay untouched, and apt checks the tarball against the signed Sources index
  local apt="$CACHE/apt-trixie"
  mkdir -p "$apt/lists/partial" "$apt/cache" "$apt/download"
  cat >"$apt/sources.list" <<'SRC'
deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian trixie main
SRC
  local opts=(-o "Dir::Etc::SourceList=$apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
              -o "Dir::State::Lists=$apt/lists" -o "Dir::Cache=$apt/cache"
              -o APT::Sandbox::User=root)
  if [ ! -f "$apt/download/$DEB_ORIG" ]; then
    apt-get "${opts[@]}" -qq update
    # any Debian revision of this upstream version: they share the orig tarball
    local version
    version="$(apt-cache "${opts[@]}" showsrc "$DEB_SOURCE" |
               awk -v u="$DEB_UPSTREAM" '/^Version: /{ if (index($2, u "-") == 1) { print $2; exit } }')"
    if [ -z "$version" ]; then
      log "trixie has no source package $DEB_SOURCE $DEB_UPSTREAM-* any more"; exit 1
    fi
    log "fetching the Debian source package $DEB_SOURCE=$version"
    # the orig tarball only (--tar-only): a mirror may lack the .dsc, and its 404 stopped the
    # tarball's download half-way. The tarball is checked against the SHA-256 of the signed
    # Sources index below.
    (cd "$apt/download" && apt-get "${opts[@]}" -qq source --download-only --tar-only \
       "$DEB_SOURCE=$version" >/dev/null 2>&1) || true
    local want
    # the SHA-256 of the tarball in the stanza of that version (showsrc takes a package name,
    # not name=version: it prints every version the index has)
    want="$(apt-cache "${opts[@]}" showsrc "$DEB_SOURCE" |
            awk -v f="$DEB_ORIG" -v v="$version" '/^Version: /{ver=$2} /^Checksums-Sha256:/{s=1;next}
                 /^[^ ]/{s=0} s && ver==v && $3==f && h=="" {h=$1} END {print h}')"
    if [ ! -f "$apt/download/$DEB_ORIG" ] || [ -z "$want" ] ||
       [ "$(sha256sum "$apt/download/$DEB_ORIG" | cut -d' ' -f1)" != "$want" ]; then
      rm -f "$apt/download/$DEB_ORIG"
      log "could not fetch and verify $DEB_ORIG"
      exit 1
    fi
  fi
  if [ ! -f "$SRC/.complete" ]; then
    log "extracting $DEB_ORIG"
    rm -rf "$SRC" "$SRC.tmp"
    mkdir -p "$SRC.tmp"
    tar -xf "$apt/download/$DEB_ORIG" -C "$SRC.tmp" --strip-components=1
    touch "$SRC.tmp/.complete"
    mv "$SRC.tmp" "$SRC"
  fi
}

build_lammps() {
  [ -f "$PREFIX/.complete" ] && return 0
  fetch_source
  # installed in place; the .complete marker, written last, makes a half install count as none
  local bld="$PREFIX.build"
  log "building LAMMPS $LAMMPS_DATE into $PREFIX (once; later runs reuse it)"
  rm -rf "$PREFIX"
  cmake -S "$SRC/cmake" -B "$bld" "${LAMMPS_CONFIG[@]}" -DCMAKE_INSTALL_PREFIX="$PREFIX" \
    -DCMAKE_INSTALL_LIBDIR=lib >"$PREFIX.configure.log" 2>&1 ||
    { tail -30 "$PREFIX.configure.log" >&2; exit 1; }
  nice cmake --build "$bld" -j "$JOBS" >"$PREFIX.build.log" 2>&1 ||
    { tail -30 "$PREFIX.build.log" >&2; exit 1; }
  cmake --install "$bld" >/dev/null
  # the full source headers a plugin needs beyond the installed public ones (neigh_request.h,
  # fix_neigh_history.h, GRANULAR, EXTRA-FIX), the Python module, and the sources of LAMMPS's
  # pair-style tester (tests/lammps_harness)
  mkdir -p "$PREFIX/share/lammps-src"
  (cd "$SRC" && cp -r --parents src/*.h src/fmt src/GRANULAR/*.h src/EXTRA-FIX/*.h python/lammps \
     unittest/force-styles/*.cpp unittest/force-styles/*.h "$PREFIX/share/lammps-src/")
  printf '%s\n' "$DEB_UPSTREAM" "${LAMMPS_CONFIG[@]}" >"$PREFIX/tylmp-lammps-config.txt"
  touch "$PREFIX/.complete"
  rm -rf "$bld" "$SRC"         # the install holds all later runs need (headers included)
}

install_harness_sources() {
  # the sources of LAMMPS's pair-style tester (unittest/force-styles: test_pair_style.cpp and
  # its support files) for tests/lammps_harness: an install made before build_lammps kept them
  # gets them from the cached tarball (or the source tree, fetched again if need be)
  local dest="$PREFIX/share/lammps-src/unittest/force-styles"
  [ -f "$dest/test_pair_style.cpp" ] && return 0
  local tarball="$CACHE/apt-trixie/download/$DEB_ORIG" tmp="$PREFIX/share/lammps-src/unittest.tmp"
  rm -rf "$tmp"
  mkdir -p "$tmp"
  if [ -f "$tarball" ]; then
    tar -xf "$tarball" -C "$tmp" --strip-components=1 --wildcards \
      '*/unittest/force-styles/*.cpp' '*/unittest/force-styles/*.h'
  else
    fetch_source
    (cd "$SRC" && cp -r --parents unittest/force-styles/*.cpp unittest/force-styles/*.h "$tmp/")
    rm -rf "$SRC"
  fi
  mkdir -p "$(dirname "$dest")"
  mv "$tmp/unittest/force-styles" "$dest"
  rm -rf "$tmp"
}

install_python_module() {
  # the Python module of this LAMMPS, with the package metadata it checks its version against: without it, importlib finds the metadata
  # of Debian's python3-lammps (29 Sep 2021) and the module refuses this liblammps
  local py="$PREFIX/lib/python3/dist-packages"
  local meta="$py/lammps-${LAMMPS_DATE:0:4}.$((10#${LAMMPS_DATE:4:2})).$((10#${LAMMPS_DATE:6:2})).dist-info"
  [ -f "$meta/METADATA" ] && return 0
  rm -rf "$py/lammps"
  mkdir -p "$py" "$meta.tmp"
  cp -r "$PREFIX/share/lammps-src/python/lammps" "$py/"
  # the module loads liblammps.so from its own directory first: no LD_LIBRARY_PATH for Python
  # (which would hand Debian's /usr/bin/lmp this liblammps.so.0 too: the same soname)
  ln -s "$PREFIX/lib/liblammps.so" "$py/lammps/liblammps.so"
  printf 'Metadata-Version: 2.1\nName: lammps\nVersion: %s\n' "${meta##*/lammps-}" |
    sed 's/\.dist-info$//' >"$meta.tmp/METADATA"
  rm -rf "$meta"
  mv "$meta.tmp" "$meta"
}

build_tylmp() {
  # our library against that LAMMPS, in its own build tree, and the Python package with it
  # (build/python) installed with pip into a virtual environment beside that LAMMPS (not into
  # the system's Python, nor into the .venv of scripts/setup.sh, which has the 29 Sep 2021 build)
  # The 4 Feb 2025 half of scripts/test.sh (TYLMP_TEST_HALF=2025) skips the core tests (they
  # start no LAMMPS: the 29 Sep 2021 half runs them, tests/lammps_halves.py), so its build
  # leaves them out: half of the build's compile time
  local core_tests=ON
  [ "${TYLMP_TEST_HALF:-}" = 2025 ] && core_tests=OFF
  cmake -S "$repo" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release \
    -DLAMMPS_SOURCE_DIR="$PREFIX/share/lammps-src" -DLAMMPS_DIR="$PREFIX/lib/cmake/LAMMPS" \
    -DCMAKE_INSTALL_PREFIX="$PREFIX/tylmp" -DTYLMP_BUILD_TESTS="$core_tests" >/dev/null
  nice cmake --build "$BUILD" -j "$JOBS" >/dev/null
  if ! "$VENV/bin/python" -c "import numpy" >/dev/null 2>&1; then
    /usr/bin/python3 -m venv --clear --system-site-packages "$VENV"
  fi
  rm -rf "$BUILD/python/build" "$BUILD/python/tylmp.egg-info"
  "$VENV/bin/python" -m pip install --quiet --no-build-isolation --no-index "$BUILD/python"
  cmake --install "$BUILD" --prefix "$VENV" >/dev/null
}

write_wrapper() {
  # lmp of this build with its liblammps, its Python module and the tylmp package of the
  # environment above: both on PYTHONPATH after any PYTHONPATH of the caller (so that a
  # development build there comes first), the LAMMPS module before Debian's of 29 Sep 2021
  local site
  site="$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_path("purelib"))')"
  mkdir -p "$PREFIX/tylmp/bin"
  cat >"$PREFIX/tylmp/bin/lmp.tmp" <<WRAP
#!/bin/sh
# LAMMPS $LAMMPS_DATE with tylmp, written by $repo/scripts/lammps2025.sh
export LD_LIBRARY_PATH="$PREFIX/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
export PYTHONPATH="\${PYTHONPATH:+\$PYTHONPATH:}$PREFIX/lib/python3/dist-packages:$site"
exec "$PREFIX/bin/lmp" "\$@"
WRAP
  chmod +x "$PREFIX/tylmp/bin/lmp.tmp"
  mv "$PREFIX/tylmp/bin/lmp.tmp" "$PREFIX/tylmp/bin/lmp"
}

BUILD="${TYLMP_LAMMPS2025_BUILD_DIR:-$repo/build-lammps2025}"
VENV="$PREFIX/tylmp/venv"
bash "$repo/scripts/setup.sh" --packages          # compilers, MPI, python3-dev, Eigen, GoogleTest
build_lammps
install_harness_sources
install_python_module
build_tylmp
write_wrapper
WRAPPER="$PREFIX/tylmp/bin/lmp"
log "LAMMPS $("$WRAPPER" -h | sed -n 's/^Large-scale.*Simulator - \(.*\)$/\1/p') with tylmp: $WRAPPER"

selection=(tests)
for arg in "$@"; do
  case "$arg" in tests*) selection=() ;; esac
done
if [ -z "${TYLMP_LAMMPS2025_NO_TESTS:-}" ]; then
  # the suite as against Debian's lmp: `lmp` from PATH (the wrapper), /usr/bin/python3 with this
  # LAMMPS's Python module (and its liblammps), and our library from $BUILD (tests/conftest.py)
  log "running the test suite against LAMMPS $LAMMPS_DATE"
  (cd "$repo" &&
   PATH="$PREFIX/tylmp/bin:$PATH" PYTHONPATH="$PREFIX/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}" \
   TYLMP_BUILD_DIR="$BUILD" TYLMP_LAMMPS2025_WRAPPER="$PREFIX/tylmp/bin/lmp" \
   /usr/bin/python3 -m pytest "${selection[@]}" "$@" -q -p no:cacheprovider) || status=$?
fi
echo "$WRAPPER"
exit "${status:-0}"
