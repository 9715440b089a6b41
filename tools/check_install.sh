#!/usr/bin/env bash
# The installable master (docs/embedding.md), checked as a user would, outside the build tree:
#  1. a master-only build (-DIBS_MASTER_ONLY=ON) with Eigen, CLI11, toml++ and nlohmann-json
#     forbidden to CMake, installed into a fresh prefix; a program linked through pkg-config
#     (ibs-master) runs the master loop over the in-memory bus;
#  2. the whole project installed from a built tree (default build/debug) into another prefix;
#     examples/embed configured with find_package(ibs) against it, built and run: it must exit 0;
#  3. examples/ddi, a C master against the virtual board (libibs-ddi), built with CMake and run
#     in real time, then built through pkg-config (ibs-ddi) and run stepped; the shared library
#     must export the DDI_* calls only.
# Usage: tools/check_install.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
built=${1:-build/debug}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
jobs=$(nproc 2>/dev/null || echo 2)

echo "check_install: master-only build" >&2
cmake -S . -B "$work/master-build" --no-warn-unused-cli -DIBS_MASTER_ONLY=ON -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON -DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON >/dev/null
cmake --build "$work/master-build" -j "$jobs" >/dev/null
cmake --install "$work/master-build" --prefix "$work/master" >/dev/null
if [[ -e "$work/master/bin/ibs" ]] || ls "$work/master"/lib*/libibs_sim* >/dev/null 2>&1; then
  echo "check_install: the master-only installation holds the simulator or the tool" >&2
  exit 1
fi
cat >"$work/master_only.cpp" <<'CPP'
#include <cstdio>
#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/master/memory_bus.hpp"
int main() {
  using namespace ibs;
  const auto& kind = devices::mc6000::descriptor();
  const devices::Configuration c = kind.configure({});
  const interbus::DeviceSpec spec{"servo", c.id_code, c.bus};
  const interbus::BusConfig config = interbus::make_bus_config({&spec, 1});
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  drivers.push_back(kind.make_driver(c));
  master::MasterLoop loop(config, std::move(drivers));
  master::MemoryBus bus(config);
  interbus::ProcessImage image;
  loop.initial(image);
  loop.driver(0).sequencer().request(drivecom::Target::ready, Time{0});
  bus.device_sends(0)[0] = 0x0240;  // START-UP INHIBIT
  loop.cycle(bus, image, Time{std::chrono::milliseconds(1)});
  std::printf("control word %04X\n", static_cast<unsigned>(bus.device_receives(0)[0]));
  loop.cycle(bus, image, Time{std::chrono::milliseconds(2)});
  return bus.device_receives(0)[0] == 0x0006 ? 0 : 1;  // SHUTDOWN on its way to READY
}
CPP
export PKG_CONFIG_PATH="$work/master/lib/pkgconfig:$work/master/lib/x86_64-linux-gnu/pkgconfig"
# shellcheck disable=SC2046
g++ "$work/master_only.cpp" -o "$work/master_only" $(pkg-config --cflags --libs ibs-master)
"$work/master_only"

echo "check_install: the whole package from $built, examples/embed against it" >&2
cmake --install "$built" --prefix "$work/full" >/dev/null
cmake -S examples/embed -B "$work/embed-build" -DCMAKE_PREFIX_PATH="$work/full" >/dev/null
cmake --build "$work/embed-build" -j "$jobs" >/dev/null
"$work/embed-build/embed"

echo "check_install: examples/ddi (C, the virtual board's DDI) against the same installation" >&2
cmake -S examples/ddi -B "$work/ddi-build" -DCMAKE_PREFIX_PATH="$work/full" >/dev/null
cmake --build "$work/ddi-build" -j "$jobs" >/dev/null
"$work/ddi-build/ddi_master"
# The shared library gives the DDI's calls and nothing else; pkg-config finds it for a C build.
if nm -D --defined-only "$work"/full/lib*/libibs-ddi.so* "$work"/full/lib/*/libibs-ddi.so* 2>/dev/null \
    | awk '$2 == "T" && $3 !~ /^DDI_/' | grep -q .; then
  echo "check_install: libibs-ddi.so exports more than the DDI_* calls" >&2
  exit 1
fi
export PKG_CONFIG_PATH="$work/full/lib/pkgconfig:$work/full/lib/x86_64-linux-gnu/pkgconfig"
# shellcheck disable=SC2046
gcc -std=c99 -Wall -Werror examples/ddi/ddi_master.c -o "$work/ddi_pc" $(pkg-config --cflags --libs ibs-ddi) \
  -Wl,-rpath,"$(pkg-config --variable=libdir ibs-ddi)"
IBS_DDI_MODE=stepped "$work/ddi_pc"
echo "check_install: passed" >&2
