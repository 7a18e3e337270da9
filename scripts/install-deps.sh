#!/usr/bin/env bash
# Installs what a fresh Debian 12 machine lacks to build dpcr, in levels:
#   --host   build and run the host apps (scripts/demo.sh: dpcr-sim)
#   --tests  + Catch2 and valgrind: the host test suite (scripts/test.sh, dpcr-bench)
#   --bench  + python3 and python3-matplotlib: tools/bench/run (results.json, docs/RESULTS.md, plots)
#   --peer   + mrpt-apps: the optional side-by-side peer of tools/bench/run (MRPT icp-slam; large,
#            never needed by CI)
#   --fuzz   + clang and its runtime libraries (libFuzzer, sanitizers): scripts/fuzz.sh
#   --all    + the fuzz level, cross compilers, qemu-user, the bare-metal toolchain and
#            qemu-system-arm + cpio for tools/emulated-board-test (.ci/run; the default). The
#            emulated board's own kernel and busybox are fetched by that tool with apt-get
#            download, not installed.
#   --board  the same as --all (kept for old instructions)
# Idempotent: installs only missing packages, and says nothing when all are present.
set -euo pipefail

level=${1:---all}
host=(
  build-essential cmake ninja-build
  libeigen3-dev                                # core: the only dependency
  libcli11-dev nlohmann-json3-dev libstb-dev   # host apps (header-only, so cross builds can use them too)
)
tests=(
  catch2                             # unit tests
  valgrind                           # instruction-count budgets (callgrind) and dpcr-bench
)
bench=(
  python3 python3-matplotlib         # tools/bench/run and its plots
)
peer=(
  mrpt-apps                          # tools/bench/run: MRPT icp-slam and carmen2rawlog (optional)
)
fuzz=(
  clang libclang-rt-14-dev           # scripts/fuzz.sh: the fuzz preset (libFuzzer, ASan, UBSan)
)
cross=(
  git
  g++-arm-linux-gnueabihf g++-aarch64-linux-gnu qemu-user   # cross presets + tests under emulation
  gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib  # baremetal core check
)
board=(
  qemu-system-arm cpio file          # tools/emulated-board-test: the emulated board (arm and aarch64), its initramfs
)
case $level in
  --host) packages=("${host[@]}") ;;
  --tests) packages=("${host[@]}" "${tests[@]}") ;;
  --bench) packages=("${host[@]}" "${tests[@]}" "${bench[@]}") ;;
  --peer) packages=("${host[@]}" "${tests[@]}" "${bench[@]}" "${peer[@]}") ;;
  --fuzz) packages=("${host[@]}" "${fuzz[@]}") ;;
  --all|--board) packages=("${host[@]}" "${tests[@]}" "${fuzz[@]}" "${cross[@]}" "${board[@]}") ;;
  *) echo "usage: $0 [--host|--tests|--bench|--peer|--fuzz|--all|--board]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
# A mirror mid-sync can fail one index (of a foreign architecture added by
# tools/emulated-board-test, say); the install below still says what is missing.
"${sudo_cmd[@]}" apt-get update -qq || echo "install-deps: apt-get update reported errors, trying the install" >&2
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
