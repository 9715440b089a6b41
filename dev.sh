#!/usr/bin/env bash
# ibs developer entry point: the README's two quick-start commands.
#
#   ./dev.sh run [ARGS...]   build (release) and run the main job: `ibs run ARGS...`
#   ./dev.sh test [PRESET]   build and run the whole test suite with CTest (PRESET: debug | asan)
#   ./dev.sh fuzz [SECONDS] [TARGET...]
#                            build the libFuzzer targets (clang, preset `fuzz`) and run each for
#                            SECONDS (default 10) on its seed corpus: fuzz/run.sh, docs/robustness.md
#   ./dev.sh soak [MINUTES]  the soak (tools/soak.py, docs/robustness.md "Soak"; not in CI): a real-time
#                            test bench for MINUTES (default 60) under traffic, sampled each minute, then
#                            the campaign (10^7 transactions) and every fuzz target for 10 minutes
#                            (SOAK_FUZZ_SECONDS, SOAK_FUZZ_JOBS, SOAK_TRANSACTIONS change those)
#
# Each first checks for the Debian packages the build needs and installs the missing ones through
# apt-get (saying so); nothing is downloaded at build time. Only `fuzz` needs clang.
set -euo pipefail
cd "$(dirname "$0")"

packages=(g++ cmake make libgtest-dev libgmock-dev libbenchmark-dev libeigen3-dev libcli11-dev
          nlohmann-json3-dev libtomlplusplus-dev libasio-dev libpcap-dev libfmt-dev help2man)
# The compiler cache: CMakeLists.txt compiles through it when it is there (IBS_CCACHE), so that a
# second build of the same sources -- another preset, CI's install checks, a clean clone -- is quick.
packages+=(ccache)
# The tests only: tshark runs the Wireshark dissectors (CANLust and INTERBUS) over the captures the
# tests write (WiresharkDissector.*, CanlustCli.*, the capture tests; installed
# without its setuid question: DEBIAN_FRONTEND=noninteractive keeps the default, no setuid);
# gtkwave opens a run's save file headless under Xvfb (xvfb-run needs xauth); gnuplot draws the
# plots of `ibs run --plot`; pkgconf links a program against the installed master
# (tools/check_install.sh); python3 runs the test bench example, a user's own host test written with
# the standard library only (examples/testbench/, docs/testbench.md).
test_packages=(tshark gtkwave xvfb xauth gnuplot-nox pkgconf python3)
# The fuzz targets only: clang with libFuzzer and the sanitizer runtimes.
fuzz_packages=(clang libclang-rt-14-dev)

# ensure_packages [PACKAGE...]: installs the missing ones (default: the build's packages).
ensure_packages() {
  local wanted=("$@")
  ((${#wanted[@]} == 0)) && wanted=("${packages[@]}")
  local missing=()
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
  done
  ((${#missing[@]} == 0)) && return 0
  echo "dev.sh: installing missing Debian packages with apt-get (a minute or two): ${missing[*]}" >&2
  local sudo=()
  [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}" >&2
}

jobs=$(nproc 2>/dev/null || echo 2)
werror=()
[[ "${CI:-}" == "true" ]] && werror=(-DIBS_WERROR=ON)

build() {
  local preset=$1; shift
  cmake --preset "$preset" "${werror[@]}" >/dev/null
  cmake --build --preset "$preset" -j "$jobs" "$@"
}

# The main job keeps its output to the run itself: the build shows its progress on standard error
# and its output only when it fails (quiet_build, tools/build_progress.sh).
source tools/build_progress.sh
# What a first release build of ibs takes: about 7 CPU-minutes of compiling (measured on
# 2026-11-29, g++ 12, no compiler cache), shared by the cores.
first_build_minutes() { echo $(((7 + jobs - 1) / jobs)); }

cmd=${1:-}
case "$cmd" in
  run)
    shift
    ensure_packages
    if [[ -x build/release/tools/ibs/ibs ]]; then
      echo "dev.sh: building ibs (release, build/release) if the sources changed, then ibs run" >&2
    else
      echo "dev.sh: building ibs (release, build/release) for the first time: about $(first_build_minutes) minutes on" \
           "$jobs cores (seconds with a warm compiler cache), then ibs run" >&2
    fi
    quiet_build ibs build release --target ibs || exit 1
    exec ./build/release/tools/ibs/ibs run "$@"
    ;;
  test)
    preset=${2:-debug}
    ensure_packages
    ensure_packages "${test_packages[@]}"
    build "$preset"
    ctest --preset "$preset" -j "$jobs"
    ;;
  fuzz)
    shift
    ensure_packages
    ensure_packages "${fuzz_packages[@]}"
    exec fuzz/run.sh "$@"
    ;;
  soak)
    minutes=${2:-60}
    ensure_packages
    ensure_packages "${test_packages[@]}"
    ensure_packages "${fuzz_packages[@]}"
    quiet_build release --target ibs
    exec python3 tools/soak.py --ibs ./build/release/tools/ibs/ibs --minutes "$minutes"
    ;;
  *)
    echo "usage: ./dev.sh run [ARGS...] | ./dev.sh test [debug|asan] | ./dev.sh fuzz [SECONDS] [TARGET...]" >&2
    exit 2
    ;;
esac
