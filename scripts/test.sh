#!/usr/bin/env bash
# Installs what is missing, builds the host preset and runs every test (ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --tests
cmake --preset host >/dev/null  # the preset sets DPCR_BUILD_TESTS=ON: configuring fails without Catch2
cmake --build --preset host
ctest --preset host "$@"
