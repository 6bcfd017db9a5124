#!/usr/bin/env bash
# One-time (idempotent) set-up on Debian 12 or 13: packages, LAMMPS source headers, build, and
# the Python package tylmp (with the library just built) installed with pip into a virtual
# environment, .venv in the repository ($TYLMP_VENV instead), made from /usr/bin/python3 with
# --system-site-packages so that it sees Debian's python3-lammps, numpy, scipy and matplotlib.
# Nothing is written into the system's Python. With .venv/bin first on PATH (`. .venv/bin/activate`)
# `tyanalysis` is a command and lmp's `python` command imports tylmp (LAMMPS's embedded Python
# finds the environment through the python3 on PATH).
#   bash scripts/setup.sh              (as root, or with sudo available: apt only)
#   bash scripts/setup.sh --packages   (the Debian packages only: also those scripts/lammps2025.sh
#                                       needs to build LAMMPS 4 Feb 2025 from source)
# A second run changes nothing when the installed package is current (no reconfigure, no pip).
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

# python3-dev: the PYTHON package of the LAMMPS that scripts/lammps2025.sh builds; clang: the
# second compiler of the core tests (tests/test_clang_build.py); clang-format: the style of
# plugin/ (.clang-format, scripts/format.sh, tests/test_format.py); libgmock-dev, libyaml-dev,
# pkg-config: LAMMPS's own pair-style tester built against that LAMMPS (tests/lammps_harness);
# python3-sphinx, python3-myst-parser and furo: the documentation site (docs/conf.py,
# tests/test_docs_site.py)
PACKAGES="lammps liblammps-dev python3-lammps openmpi-bin libopenmpi-dev libeigen3-dev
  cmake make g++ clang clang-format libgtest-dev libgmock-dev libyaml-dev pkg-config dpkg-dev
  xz-utils python3-dev
  python3-numpy python3-scipy python3-matplotlib python3-pytest
  python3-venv python3-setuptools python3-wheel
  python3-sphinx python3-myst-parser furo"
# LIGGGHTS 3.8 and the headers of exactly its library (Debian's patched ones) for the
# Thornton-Yin model in LIGGGHTS (cmake/Liggghts.cmake), where the release has them; apt-cache
# knows only what the package lists hold, so a machine without lists gets them first
if [ -z "$(find /var/lib/apt/lists -maxdepth 1 -name '*_Packages*' -print -quit 2>/dev/null)" ]; then
  $SUDO apt-get update -qq
fi
if apt-cache show libliggghts-dev >/dev/null 2>&1; then
  PACKAGES="$PACKAGES liggghts libliggghts-dev"
fi

# deb-src entry of this Debian release: CMake fetches the LAMMPS headers of the installed
# version with 'apt-get source' (bookworm: 29 Sep 2021, trixie: 4 Feb 2025)
. /etc/os-release
SRC_LIST=/etc/apt/sources.list.d/tylmp-deb-src.sources
need_update=0
if [ ! -f "$SRC_LIST" ] || ! grep -q "^Suites: ${VERSION_CODENAME}\$" "$SRC_LIST"; then
  $SUDO tee "$SRC_LIST" >/dev/null <<SRC
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: ${VERSION_CODENAME}
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  need_update=1
fi
missing=""
for p in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ] || [ "$need_update" = 1 ]; then
  $SUDO apt-get update -qq
fi
if [ -n "$missing" ]; then
  echo "setup: installing$missing"
  # without the recommended packages: on a fresh Debian 12 they are 331 more (ParaView, Qt,
  # LLVM's development files, LAMMPS's examples and manual, ...; 320 MB of the 680 MB to
  # download), none of which the product or its tests use (docs/developer.md)
  $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
# YADE, the independent engine of the cross-checks (tests/test_yade_crosscheck.py,
# bench/yade_*.py), without its recommended GUI packages
if ! dpkg-query -W -f='${Status}' yade 2>/dev/null | grep -q "install ok installed" &&
    apt-cache show yade >/dev/null 2>&1; then
  echo "setup: installing yade"
  $SUDO apt-get install -y -qq --no-install-recommends yade >/dev/null
fi
[ "${1:-}" = "--packages" ] && exit 0

# configure once (the build re-runs CMake itself when CMakeLists.txt or cmake/ change)
[ -f build/CMakeCache.txt ] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"

# the layout before the virtual environment: `cmake --install` put tylmp and tyanalysis into
# /usr/bin/python3's first site directory and the tyanalysis command into /usr/local/bin. A copy
# left there would be imported, stale, by an lmp run outside the environment: remove it
old_site="$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')"
if [ -f "$old_site/tyanalysis/cli.py" ] && [ -f "$old_site/tylmp/decks.py" ]; then
  echo "setup: removing the earlier install of tylmp and tyanalysis from $old_site"
  $SUDO rm -rf "$old_site/tylmp" "$old_site/tyanalysis"
  [ -f /usr/local/bin/tyanalysis ] && grep -q "from tyanalysis.cli import main" /usr/local/bin/tyanalysis &&
    $SUDO rm -f /usr/local/bin/tyanalysis
fi

# the virtual environment: made once; made anew when it no longer runs or no longer sees
# Debian's lammps module (a Python upgrade, or one made without --system-site-packages)
VENV="${TYLMP_VENV:-$PWD/.venv}"
if ! env -u PYTHONPATH "$VENV/bin/python" -c "import lammps" >/dev/null 2>&1; then
  echo "setup: creating the virtual environment $VENV (/usr/bin/python3 --system-site-packages)"
  /usr/bin/python3 -m venv --clear --system-site-packages "$VENV"
fi
# install only when something installed would change: the stamp is newer than every file of
# build/python (the package with the library and the decks) and the install is still there.
# Offline: setuptools, wheel and the requirements are Debian's, seen through the system site
stamp="$VENV/tylmp-installed.stamp"
where() { env -u PYTHONPATH "$VENV/bin/python" -c 'import tylmp; print(tylmp.library_path())'; }
if [ -f "$stamp" ] && [ -x "$VENV/bin/tyanalysis" ] &&
   [ -z "$(find build/python \( -name build -o -name __pycache__ -o -name '*.egg-info' \) -prune \
           -o -newer "$stamp" -print -quit)" ] &&
   env -u PYTHONPATH "$VENV/bin/python" -c "import tylmp.analysis" >/dev/null 2>&1; then
  echo "setup: the installed tylmp is current ($(where))"
else
  # pip builds in build/python: nothing of an earlier build may go into this one
  rm -rf build/python/build build/python/tylmp.egg-info
  env -u PYTHONPATH "$VENV/bin/python" -m pip install --quiet --no-build-isolation --no-index build/python
  # the programs of the build (build/bin/tyliggghts, when LIGGGHTS is there) into the same prefix
  cmake --install build --prefix "$VENV" >/dev/null
  touch "$stamp"
  echo "setup: tylmp built and installed ($(where))"
fi
echo "setup: '. $VENV/bin/activate' puts tyanalysis on PATH and tylmp before lmp's python command"
