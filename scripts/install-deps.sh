#!/usr/bin/env bash
# Installs what a fresh Debian 12 machine lacks to build and test dpcr.
# Idempotent: installs only missing packages, and says nothing when all are present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev                      # core: the only dependency
  catch2                             # tests
  libcli11-dev nlohmann-json3-dev libstb-dev   # host tools (header-only, so cross builds can use them too)
  valgrind                           # instruction-count budgets (callgrind)
  g++-arm-linux-gnueabihf g++-aarch64-linux-gnu qemu-user   # cross presets + tests under emulation
  gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib  # baremetal core check
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
