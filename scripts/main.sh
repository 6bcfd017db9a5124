#!/usr/bin/env bash
# Set up everything, then run the main job: axisymmetric compression at p = 100 kPa of the
# default (dense, quick-scale) specimen, and draw its figure (paper Figs 1-2).
#   bash scripts/main.sh [extra lmp arguments, e.g. -var scale paper]
# Outputs in the current directory: axisym.csv, axisym.png, tylmp_specimens/ (reused).
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
bash "$repo/scripts/setup.sh"
cd "$repo"
# the virtual environment of setup.sh first on PATH: lmp's python command imports its tylmp, and
# tyanalysis is its command
export PATH="${TYLMP_VENV:-$repo/.venv}/bin:$PATH"
lmp -in inputs/axisym.in -log axisym.log "$@"
# the plotting command the deck printed last (it names N and the specimen), with the paper's values
plot="$(sed -n 's/^plot: tyanalysis //p' axisym.log | tail -n 1)"
[ -n "$plot" ] || { echo "main: the deck printed no plotting command (axisym.log)" >&2; exit 1; }
# shellcheck disable=SC2086  # the printed command's words
tyanalysis $plot --paper
echo "main: wrote $repo/axisym.csv and $repo/axisym.png"
