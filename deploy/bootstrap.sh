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
          libtomlplusplus-dev libcli11-dev libspdlog-dev libmodbus-dev libsystemd-dev libnats-dev
          libcurl4-openssl-dev openssl dump1090-mutability
          mbpoll python3-pymodbus systemd prometheus nats-server mosquitto-clients
          tshark clang-14 libclang-rt-14-dev
          libjs-leaflet chromium chromium-driver python3-selenium
          debhelper dpkg-dev fakeroot lintian scdoc man-db git)

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

# ccache: one cache for every clone (CI builds a fresh clone each time): paths below the
# clone are hashed relative to it, and the working directory is left out of the hash of
# objects with debug information.
export CCACHE_DIR=${CCACHE_DIR:-$HOME/.cache/kew-ccache}
export CCACHE_BASEDIR=$here
export CCACHE_NOHASHDIR=true

# The one build tree of both commands, configured alike, so that the test command after
# the run command (or the other way round) builds nothing again. It compiles as the Debian
# package does (build type None with dpkg-buildflags: -O2, hardening, assertions on), so
# that the suite tests the code the package ships and the package's build finds every
# object it shares with this one in ccache. Warnings are errors: the compilers bootstrap
# installs (Debian 12's g++ 12 and clang 14) are the ones CI builds with, and a build by
# hand keeps the default (KEW_WERROR=OFF).
package_flags() {  # NAME: dpkg-buildflags' value, as debian/rules gets it
  (cd "$here" && DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get "$1")
}
configure_and_build() {
  local cppflags
  cppflags=$(package_flags CPPFLAGS)
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=None -DKEW_WERROR=ON \
    -DCMAKE_CXX_FLAGS="$(package_flags CXXFLAGS) $cppflags" \
    -DCMAKE_EXE_LINKER_FLAGS="$(package_flags LDFLAGS)" -DCMAKE_SHARED_LINKER_FLAGS="$(package_flags LDFLAGS)" \
    >/dev/null
  cmake --build "$build" -j "$jobs"
}

# The second build, with clang, ASan + UBSan and libFuzzer: the decoder and encoder unit
# tests under the sanitizers, then a short smoke run of every fuzz target (tests/fuzz).
# Only the targets needed are built, with line tables for the reports' file and line (-g1)
# rather than full debugging information; benchmarks are off. It runs after the package:
# the builds are CPU-bound, and beside the main build or the suite it slowed them by about
# what it gained (docs/testing.md, "How long it takes").
# KEW_FUZZ_SECONDS sets the run per target (default 15); KEW_SKIP_SANITIZE=1 skips the stage.
sanitize_build="$build-sanitize"
sanitize_and_fuzz() {
  if [ "${KEW_SKIP_SANITIZE:-0}" = 1 ]; then
    echo "bootstrap: sanitizer and fuzz stage skipped (KEW_SKIP_SANITIZE=1)"
    return 0
  fi
  CC=clang-14 CXX=clang++-14 cmake -S "$here" -B "$sanitize_build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
    -DKEW_SANITIZE=ON -DKEW_BUILD_FUZZERS=ON -DKEW_BUILD_BENCHMARKS=OFF -DKEW_WERROR=ON >/dev/null
  # kew_decoder_tests: the tests of kew_protocol (tests/protocol/sources.cmake), without
  # the other libraries' tests (tests/fuzz/CMakeLists.txt).
  cmake --build "$sanitize_build" -j "$jobs" --target kew_decoder_tests kew_fuzzers
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$sanitize_build/tests/fuzz/kew_decoder_tests" --gtest_brief=1
  bash "$here/tests/fuzz/run_fuzzers.sh" "$sanitize_build/tests/fuzz" "${KEW_FUZZ_SECONDS:-15}"
}

# The Debian package: built with warnings as errors (the second build type, dpkg-buildflags'
# -O2 and hardening), linted; installed, checked and purged only when CI=true
# (tests/package/test_deb.sh). KEW_SKIP_PACKAGE=1 skips the stage.
package() {
  if [ "${KEW_SKIP_PACKAGE:-0}" = 1 ]; then
    echo "bootstrap: package stage skipped (KEW_SKIP_PACKAGE=1)"
    return 0
  fi
  bash "$here/tests/package/test_deb.sh"
}

# The main job: the demo (deploy/demo.sh): kewd replays a bundled recording with its
# live map, kew-watch shows the alerts, kew-eval scores them when the recording ends.
run_demo() {
  bash "$here/deploy/demo.sh" "$build"
}

install_dependencies
case "$mode" in
  test)
    configure_and_build
    # Tests that take hours are not registered here (KEW_LONG_TESTS, docs/testing.md).
    # Twice as many tests at a time as cores: a test that keeps a core busy takes one of the
    # cores' slots (build/cpus.json, tests/CMakeLists.txt), and the end-to-end tests that
    # mostly wait (leases, outages, timers) fill the others.
    ctest --test-dir "$build" --output-on-failure -j "$((2 * jobs))" --resource-spec-file "$build/cpus.json"
    package
    sanitize_and_fuzz
    ;;
  run)
    configure_and_build
    run_demo
    ;;
  *)
    echo "usage: $0 test|run" >&2
    exit 64
    ;;
esac
