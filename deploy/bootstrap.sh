#!/usr/bin/env bash
# One entry point for the README's two commands on a fresh Debian 12 machine:
#   bash deploy/bootstrap.sh test   install dependencies, build, run the whole test suite
#   bash deploy/bootstrap.sh run    install dependencies, build, run the main job
# Dependencies come from Debian's apt (run as root, or with sudo available).
set -euo pipefail

mode=${1:-test}
here=$(cd "$(dirname "$0")/.." && pwd)
build=${KEW_BUILD_DIR:-$here/build}
jobs=$(nproc)

packages=(build-essential cmake ccache
          libcgal-dev libgmp-dev libmpfr-dev libgeographiclib-dev
          libboost-dev libsimdjson-dev libfmt-dev zlib1g-dev
          libgtest-dev libgmock-dev libbenchmark-dev
          tshark clang-14 libclang-rt-14-dev)

install_dependencies() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "bootstrap: installing ${missing[*]}"
  local sudo=()
  [ "$(id -u)" -eq 0 ] || sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
}

configure_and_build() {
  export CCACHE_DIR=${CCACHE_DIR:-$HOME/.cache/kew-ccache}
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build "$build" -j "$jobs"
}

install_dependencies
configure_and_build
case "$mode" in
  test)
    ctest --test-dir "$build" --output-on-failure -j "$jobs"
    ;;
  run)
    # Until the daemon exists, the main job is the kinetic engine on a generated radar
    # workload, printing the thesis' three effects side by side.
    "$build/tests/bench/kew_thesis_bench" --quick
    ;;
  *)
    echo "usage: $0 test|run" >&2
    exit 64
    ;;
esac
