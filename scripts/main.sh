#!/usr/bin/env bash
# Set up everything, then run the main job: axisymmetric compression at p = 100 kPa of the
# default (dense, quick-scale) specimen, and draw its figure (paper Figs 1-2).
#   bash scripts/main.sh [extra lmp arguments, e.g. -var scale paper]
# Outputs in the current directory: axisym.csv, axisym.png, tylmp_specimens/ (reused).
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
bash "$repo/scripts/setup.sh"
cd "$repo"
lmp -in inputs/axisym.in -log axisym.log "$@"
/usr/bin/python3 -m tyanalysis axisym axisym.csv --paper --out axisym.png
echo "main: wrote $repo/axisym.csv and $repo/axisym.png"
