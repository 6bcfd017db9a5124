#!/usr/bin/env bash
# One-time (idempotent) set-up on Debian 12: packages, LAMMPS source headers, build, install.
#   bash scripts/setup.sh            (as root, or with sudo available)
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

PACKAGES="lammps liblammps-dev python3-lammps openmpi-bin libopenmpi-dev libeigen3-dev
  cmake make g++ libgtest-dev dpkg-dev xz-utils
  python3-numpy python3-matplotlib python3-pytest"

# deb-src entry: CMake fetches the LAMMPS headers of the installed version with 'apt-get source'
SRC_LIST=/etc/apt/sources.list.d/tylmp-deb-src.sources
need_update=0
if [ ! -f "$SRC_LIST" ]; then
  $SUDO tee "$SRC_LIST" >/dev/null <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
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

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"
$SUDO cmake --install build >/dev/null
echo "setup: tylmp built and installed ($(/usr/bin/python3 -c 'import tylmp; print(tylmp.library_path())'))"
