#!/usr/bin/env bash
# Set up everything, then run the whole test suite (C++ core tests run inside pytest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
exec /usr/bin/python3 -m pytest tests -q -p no:cacheprovider "$@"
