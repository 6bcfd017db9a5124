#!/usr/bin/env bash
# Set up everything, then run the whole test suite (C++ core tests run inside pytest) against
# each LAMMPS version: 29 Sep 2021 (Debian 12's lmp, this tree's build of tylmp), then
# 4 Feb 2025 (built from Debian 13's source and cached by scripts/lammps2025.sh).
#   bash scripts/test.sh [pytest arguments]
#   TYLMP_TEST_LAMMPS=2021 bash scripts/test.sh     (one version only: 2021 or 2025)
set -euo pipefail
cd "$(dirname "$0")/.."
versions="${TYLMP_TEST_LAMMPS:-2021 2025}"
bash scripts/setup.sh
case " $versions " in
  *" 2025 "*)    # both builds first: the cross-version tests of either half run both LAMMPS,
                 # each with this tree's build of tylmp (not one left from an earlier run)
    TYLMP_LAMMPS2025_NO_TESTS=1 bash scripts/lammps2025.sh >/dev/null ;;
esac
status=0
for v in $versions; do
  case "$v" in
    2021)
      echo "test: the suite against LAMMPS 29 Sep 2021 (Debian's lmp)"
      /usr/bin/python3 -m pytest tests -q -p no:cacheprovider "$@" || status=1 ;;
    2025)
      echo "test: the suite against LAMMPS 4 Feb 2025 (scripts/lammps2025.sh)"
      bash scripts/lammps2025.sh "$@" || status=1 ;;
    *) echo "test: unknown TYLMP_TEST_LAMMPS entry '$v' (expected 2021 and/or 2025)" >&2; exit 2 ;;
  esac
done
exit "$status"
