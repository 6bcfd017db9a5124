#!/usr/bin/env bash
# One-time (idempotent) set-up on Debian 12 or 13: packages, LAMMPS source headers, build, install.
#   bash scripts/setup.sh              (as root, or with sudo available)
#   bash scripts/setup.sh --packages   (the Debian packages only: also those scripts/lammps2025.sh
#                                       needs to build LAMMPS 4 Feb 2025 from source)
# A second run changes nothing when the installed build is current (no reconfigure, no install).
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

# python3-dev: the PYTHON package of the LAMMPS that scripts/lammps2025.sh builds
PACKAGES="lammps liblammps-dev python3-lammps openmpi-bin libopenmpi-dev libeigen3-dev
  cmake make g++ libgtest-dev dpkg-dev xz-utils python3-dev
  python3-numpy python3-scipy python3-matplotlib python3-pytest"
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
  $SUDO apt-get install -y -qq $missing >/dev/null
fi
[ "${1:-}" = "--packages" ] && exit 0

# configure once (the build re-runs CMake itself when CMakeLists.txt or cmake/ change)
[ -f build/CMakeCache.txt ] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"
# install only when something installed would change: the stamp is newer than every built or
# copied file of the install, and every file the last install wrote is still there
stamp=build/tylmp-installed.stamp
current=0
if [ -f "$stamp" ] && [ -f build/install_manifest.txt ] &&
   [ -z "$(find build/python python analysis/tyanalysis -newer "$stamp" -print -quit)" ]; then
  current=1
  while read -r f; do [ -e "$f" ] || { current=0; break; }; done <build/install_manifest.txt
fi
if [ "$current" = 0 ]; then
  $SUDO cmake --install build >/dev/null
  touch "$stamp"
  echo "setup: tylmp built and installed ($(/usr/bin/python3 -c 'import tylmp; print(tylmp.library_path())'))"
else
  echo "setup: the installed tylmp is current ($(/usr/bin/python3 -c 'import tylmp; print(tylmp.library_path())'))"
fi
