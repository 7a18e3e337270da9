#!/usr/bin/env bash
# Installs what is missing, builds the host preset and runs every test (ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset host >/dev/null
cmake --build --preset host
ctest --preset host "$@"
