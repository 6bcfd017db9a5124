#!/usr/bin/env bash
# Set up everything, then run the test suite (C++ core tests run inside pytest) against each
# LAMMPS version: 29 Sep 2021 (Debian 12's lmp, this tree's build of tylmp), then 4 Feb 2025
# (built from Debian 13's source and cached by scripts/lammps2025.sh).
#   bash scripts/test.sh [pytest arguments]
#   TYLMP_TEST_LAMMPS=2021 bash scripts/test.sh     (one version only: 2021 or 2025)
# With both versions, each test runs where its outcome can depend on the version
# (tests/lammps_halves.py, docs/developer.md): a test that starts no LAMMPS only in the 29 Sep 2021
# half, one that runs both versions itself only in the 4 Feb 2025 half, every other one in both.
# With one version, every test runs against it.
set -euo pipefail
cd "$(dirname "$0")/.."
versions="${TYLMP_TEST_LAMMPS:-2021 2025}"
for v in $versions; do
  case "$v" in
    2021|2025) ;;
    *) echo "test: unknown TYLMP_TEST_LAMMPS entry '$v' (expected 2021 and/or 2025)" >&2; exit 2 ;;
  esac
done
split=0
case " $versions " in *" 2021 "*) case " $versions " in *" 2025 "*) split=1 ;; esac ;; esac
bash scripts/setup.sh

build2025=""
case " $versions " in
  *" 2025 "*)
    # LAMMPS 4 Feb 2025 and this tree's tylmp against it, built while the 29 Sep 2021 half runs
    # (that half needs neither: its tests that run both versions wait for the second half).
    # Most of the first half keeps one core busy, the build takes the other.
    log="$(mktemp "${TMPDIR:-/tmp}/tylmp-lammps2025-build.XXXXXX")"
    TYLMP_LAMMPS2025_NO_TESTS=1 TYLMP_TEST_HALF="$([ "$split" = 1 ] && echo 2025)" \
      bash scripts/lammps2025.sh >"$log" 2>&1 &
    build2025=$!
    echo "test: building LAMMPS 4 Feb 2025 and tylmp against it in the background (log: $log)" ;;
esac
trap '[ -n "$build2025" ] && kill "$build2025" 2>/dev/null' EXIT
wait_build2025() {
  [ -n "$build2025" ] || return 0
  if ! wait "$build2025"; then
    tail -40 "$log" >&2
    echo "test: the LAMMPS 4 Feb 2025 build failed (log: $log)" >&2
    return 1
  fi
  build2025=""
}

half() { if [ "$split" = 1 ]; then echo "$1"; fi; }
status=0
for v in $versions; do
  case "$v" in
    2021)
      echo "test: the suite against LAMMPS 29 Sep 2021 (Debian's lmp)"
      TYLMP_TEST_HALF="$(half 2021)" /usr/bin/python3 -m pytest tests -q -p no:cacheprovider "$@" ||
        status=1 ;;
    2025)
      wait_build2025 || { status=1; continue; }
      echo "test: the suite against LAMMPS 4 Feb 2025 (scripts/lammps2025.sh)"
      TYLMP_TEST_HALF="$(half 2025)" bash scripts/lammps2025.sh "$@" || status=1 ;;
  esac
done
wait_build2025 || status=1
exit "$status"
