#!/usr/bin/env bash
# Installs what is missing, builds, and maps the built-in simulated apartment (a 35-minute
# vacuum run). Outputs: out/apartment/{map.pgm,map.yaml,map.png,trajectory.tum,ground_truth.tum,metrics.json}
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset host >/dev/null
cmake --build --preset host
./build/host/host_sim/apps/dpcr-sim --world apartment --minutes 35 --seed 1 --out out/apartment "$@"
echo "outputs: $(pwd)/out/apartment/ (map.png to look at, metrics.json for the figures)"
