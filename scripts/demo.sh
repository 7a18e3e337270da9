#!/usr/bin/env bash
# Installs what is missing (host apps only), builds dpcr-sim, and maps the built-in simulated
# apartment (a 35-minute vacuum run). Outputs: out/apartment/{map.pgm,map.yaml,map.png,trajectory.tum,ground_truth.tum,metrics.json}
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --host
# Only what the demo runs: tests off (no Catch2 needed), one target. scripts/test.sh turns them back on.
cmake --preset host -DDPCR_BUILD_TESTS=OFF >/dev/null
cmake --build --preset host --target dpcr-sim
./build/host/host_sim/apps/dpcr-sim --world apartment --minutes 35 --seed 1 --out out/apartment "$@"
echo "outputs: $(pwd)/out/apartment/ (map.png to look at, metrics.json for the figures)"
