#!/usr/bin/env bash
# The installable master (docs/embedding.md), checked as a user would, outside the build tree:
#  1. a master-only build (-DIBS_MASTER_ONLY=ON) with Eigen, CLI11, toml++, nlohmann-json and {fmt}
#     forbidden to CMake, installed into a fresh prefix; a program linked through pkg-config
#     (ibs-master) runs the master loop over the in-memory bus;
#  2. the whole project installed from a built tree (default build/debug) into another prefix;
#     examples/embed configured with find_package(ibs) against it, built and run: it must exit 0;
#  3. examples/ddi, C masters against the virtual board (libibs-ddi): ddi_master (ibs/ddi.h) and
#     ibs_hli (Phoenix's legacy header names), built with CMake and run in real time, then built
#     through pkg-config (ibs-ddi, C99, -Wall -Wextra -Werror) and run stepped; the shared library
#     must export the DDI_* calls and the two legacy diagnostic readings only (the legacy helpers
#     are macros);
#  4. examples/hosts, a LUSTBUS, a CANLust and a DFS-1 host as a user's own programs, built with
#     CMake (ibs::lustbus, ibs::canlust, ibs::dfs1 and their transports) and run against the
#     installed tool's emulators, then built through pkg-config (ibs-lustbus, ibs-canlust, ibs-dfs1);
#  5. the package is relocatable (installed, moved, used), each header installed once, the Lua
#     dissectors in share/ibs/wireshark/plugins, and the simulator linked through pkg-config (ibs-sim);
#     the .pc files force no -std on a program, and an older standard gets a clear message;
#  6. examples/board, ibs's master on a controller board through the DDI bus adapter
#     (ibs::master_ddi, docs/board.md): built with CMake and through pkg-config (ibs-master-ddi with
#     ibs-ddi) against the virtual board and run in real time and stepped; and against a board
#     driver of one's own (a stand-in library with the DDI calls that refuses to open), chosen by
#     the CMake variable IBS_DDI_LIBRARY in the master-only build and by another -l: no source
#     change, the board's refusal with the call and its code, exit 2.
# Usage: tools/check_install.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
built=${1:-build/debug}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
jobs=$(nproc 2>/dev/null || echo 2)

# A board driver's library of one's own: the DDI calls, and a board that is not there.
fakeddi=$PWD/build/fake-ddi
mkdir -p "$fakeddi"
cat >"$work/fake_ddi.c" <<'C'
#include <ibs/ddi.h>
#include <ibs/phoenix/ibs_util.h>
IBDDIRET DDI_DevOpenNode(const char* n, int16_t p, IBDDIHND* h) { (void)n; (void)p; (void)h; return ERR_NODE_NOT_READY; }
IBDDIRET DDI_DevCloseNode(IBDDIHND h) { (void)h; return ERR_INVLD_NODE_HD; }
IBDDIRET DDI_DTI_ReadData(IBDDIHND h, T_DDI_DTI_ACCESS* a) { (void)h; (void)a; return ERR_INVLD_NODE_HD; }
IBDDIRET DDI_DTI_WriteData(IBDDIHND h, T_DDI_DTI_ACCESS* a) { (void)h; (void)a; return ERR_INVLD_NODE_HD; }
IBDDIRET DDI_DTI_ReadWriteData(IBDDIHND h, T_DDI_DTI_ACCESS* w, T_DDI_DTI_ACCESS* r) { (void)h; (void)w; (void)r; return ERR_INVLD_NODE_HD; }
IBDDIRET DDI_MXI_SndMessage(IBDDIHND h, T_DDI_MXI_ACCESS* a) { (void)h; (void)a; return ERR_INVLD_NODE_HD; }
IBDDIRET DDI_MXI_RcvMessage(IBDDIHND h, T_DDI_MXI_ACCESS* a) { (void)h; (void)a; return ERR_INVLD_NODE_HD; }
IBDDIRET DDI_GetInfo(IBDDIHND h, T_DDI_INFO* i) { (void)h; (void)i; return ERR_INVLD_NODE_HD; }
IBDDIRET GetIBSDiagnostic(IBDDIHND h, T_IBS_DIAG* d) { (void)h; (void)d; return ERR_INVLD_NODE_HD; }
C
gcc -std=c99 -Wall -Wextra -Werror -shared -fPIC -Iddi/include "$work/fake_ddi.c" -o "$fakeddi/libfakeddi.so"
fake_refusal="board: DDI_DevOpenNode(IBB1N1_D): ERR_NODE_NOT_READY (0087H)"

echo "check_install: master-only build" >&2
# In build/master-only, the folder docs/embedding.md builds the same configuration in, so that
# check_docs finds it built (and ccache, hashing paths below the source folder, finds its objects).
# With -Werror in CI as dev.sh builds the presets, so that these objects are the release preset's
# too (the same flags: ccache hands them to check_docs's release build). Its DDI library is the
# fake board below, kept in build/fake-ddi so that the cached IBS_DDI_LIBRARY stays valid for
# check_docs's build of the same folder.
master_build=build/master-only
werror=()
[[ "${CI:-}" == "true" ]] && werror=(-DIBS_WERROR=ON)
cmake -S . -B "$master_build" --no-warn-unused-cli -DIBS_MASTER_ONLY=ON -DCMAKE_BUILD_TYPE=Release "${werror[@]}" \
  -DIBS_DDI_LIBRARY="$fakeddi/libfakeddi.so" \
  -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON -DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_fmt=ON >/dev/null
cmake --build "$master_build" -j "$jobs" >/dev/null
cmake --install "$master_build" --prefix "$work/master" >/dev/null
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
g++ -std="$(pkg-config --variable=cxx_std ibs-master)" "$work/master_only.cpp" -o "$work/master_only" \
  $(pkg-config --cflags --libs ibs-master)
"$work/master_only"
# The .pc files do not force a standard on the user's program; built with an older one, the
# headers say what they need at once.
# shellcheck disable=SC2046
if g++ -std=c++17 -c "$work/master_only.cpp" -o "$work/old.o" $(pkg-config --cflags ibs-master) 2>"$work/old.txt"; then
  echo "check_install: a C++17 build of the master compiled" >&2
  exit 1
fi
grep -q "ibs needs C++20 or later" "$work/old.txt" || { echo "check_install: no clear message for a C++17 build" >&2; exit 1; }
# The DDI bus adapter of the master-only installation runs on the board library IBS_DDI_LIBRARY
# named: examples/board unchanged, the board's refusal with the call and its code, exit 2.
cmake -S examples/board -B "$work/board-own" -DCMAKE_PREFIX_PATH="$work/master" >/dev/null
cmake --build "$work/board-own" -j "$jobs" >/dev/null
rc=0
LD_LIBRARY_PATH="$work" "$work/board-own/board" 2>"$work/board-own.txt" || rc=$?
[[ $rc == 2 ]] && grep -qF "$fake_refusal" "$work/board-own.txt" \
  || { echo "check_install: examples/board on IBS_DDI_LIBRARY's board: exit $rc, $(cat "$work/board-own.txt")" >&2; exit 1; }

echo "check_install: the whole package from $built, moved after installing, examples/embed against it" >&2
# Installed in one place and used from another: the package must be relocatable (no absolute
# path of the build machine in its CMake files or .pc files).
cmake --install "$built" --prefix "$work/full-installed" >/dev/null
mv "$work/full-installed" "$work/full"
if grep -rlE "$work/full-installed|$PWD|/usr/lib/[^ \"]*\.so" "$work/full"/lib*/cmake "$work"/full/lib*/pkgconfig \
    "$work"/full/lib/*/cmake "$work"/full/lib/*/pkgconfig 2>/dev/null; then
  echo "check_install: the installed package names absolute paths (files above)" >&2
  exit 1
fi
# Each header once: a folder shared by several libraries is installed once.
if cmake --install "$built" --prefix "$work/again" | sed 's/^-- [A-Za-z-]*: //' | sort | uniq -d | grep -q '\.hpp$'; then
  echo "check_install: a header is installed twice" >&2
  exit 1
fi
rm -rf "$work/again"
# The man page (help2man) and the bash completion, where man and bash-completion look.
[[ -s "$work/full/share/man/man1/ibs.1" ]] || { echo "check_install: no man page share/man/man1/ibs.1" >&2; exit 1; }
grep -q '^\.TH IBS "1"' "$work/full/share/man/man1/ibs.1" && grep -q "lustbus" "$work/full/share/man/man1/ibs.1" \
  || { echo "check_install: the man page is not one help2man made from ibs --help" >&2; exit 1; }
bash -c "source '$work/full/share/bash-completion/completions/ibs' && COMP_WORDS=(ibs ru) && COMP_CWORD=1 && _ibs && [[ \${COMPREPLY[*]} == run ]]" \
  || { echo "check_install: the bash completion does not complete 'ibs ru'" >&2; exit 1; }
# The Wireshark dissectors, as a plugin folder (docs/pcap.md, "Installed dissectors").
for lua in interbus canlust lustbus dfs1; do
  [[ -f "$work/full/share/ibs/wireshark/plugins/$lua.lua" ]] || { echo "check_install: $lua.lua not installed" >&2; exit 1; }
done
if command -v tshark >/dev/null; then
  # Into a file first: grep -q would end the pipe early, and pipefail would count tshark's SIGPIPE.
  tshark -G protocols -X lua_script:"$work/full/share/ibs/wireshark/plugins/interbus.lua" >"$work/protocols.txt" 2>/dev/null || true
  grep -q $'\tinterbus$' "$work/protocols.txt" \
    || { echo "check_install: tshark does not load the installed interbus.lua" >&2; exit 1; }
  for lua in lustbus dfs1; do
    tshark -G protocols -X lua_script:"$work/full/share/ibs/wireshark/plugins/$lua.lua" >"$work/protocols.txt" 2>/dev/null || true
    grep -q $'\t'"$lua"'$' "$work/protocols.txt" \
      || { echo "check_install: tshark does not load the installed $lua.lua" >&2; exit 1; }
  done
fi
cmake -S examples/embed -B "$work/embed-build" -DCMAKE_PREFIX_PATH="$work/full" >/dev/null
cmake --build "$work/embed-build" -j "$jobs" >/dev/null
"$work/embed-build/embed"

echo "check_install: examples/ddi (C, the virtual board's DDI) against the same installation" >&2
cmake -S examples/ddi -B "$work/ddi-build" -DCMAKE_PREFIX_PATH="$work/full" >/dev/null
cmake --build "$work/ddi-build" -j "$jobs" >/dev/null
"$work/ddi-build/ddi_master"
"$work/ddi-build/ibs_hli"
# The shared library gives the DDI's calls and the legacy headers' two register readings
# (ibs_util.h) and nothing else: the legacy helpers (ddi_macr.h) are macros, as in Phoenix's SDK,
# so nothing of them is linked. pkg-config finds it for a C build.
# The exported names first (the globs that match nothing drop out; no pipe ends early).
shopt -s nullglob
ddi_libs=("$work"/full/lib*/libibs-ddi.so* "$work"/full/lib/*/libibs-ddi.so*)
shopt -u nullglob
((${#ddi_libs[@]} > 0)) || { echo "check_install: libibs-ddi.so is not installed" >&2; exit 1; }
ddi_exports=$(nm -D --defined-only "${ddi_libs[@]}" | awk '{ sub(/@.*/, "", $3) } $2 == "T" { print $3 }' | sort -u)
if [[ -n $(grep -v -e '^DDI_' -e '^GetIBSDiagnostic$' -e '^GetIBSDiagnosticEx$' <<<"$ddi_exports") ]]; then
  echo "check_install: libibs-ddi.so exports more than the DDI_* calls and GetIBSDiagnostic(Ex)" >&2
  exit 1
fi
for sym in GetIBSDiagnostic GetIBSDiagnosticEx; do
  grep -qx "$sym" <<<"$ddi_exports" || { echo "check_install: libibs-ddi.so does not export $sym" >&2; exit 1; }
done
export PKG_CONFIG_PATH="$work/full/lib/pkgconfig:$work/full/lib/x86_64-linux-gnu/pkgconfig"
# shellcheck disable=SC2046
gcc -std=c99 -Wall -Werror examples/ddi/ddi_master.c -o "$work/ddi_pc" $(pkg-config --cflags --libs ibs-ddi) \
  -Wl,-rpath,"$(pkg-config --variable=libdir ibs-ddi)"
IBS_DDI_MODE=stepped "$work/ddi_pc"
# The legacy-style master unchanged: Phoenix's header names from the installed ibs/phoenix folder.
# shellcheck disable=SC2046
gcc -std=c99 -Wall -Wextra -Werror examples/ddi/ibs_hli.c -o "$work/ibs_hli_pc" $(pkg-config --cflags --libs ibs-ddi) \
  -Wl,-rpath,"$(pkg-config --variable=libdir ibs-ddi)"
IBS_DDI_MODE=stepped "$work/ibs_hli_pc" | tee "$work/ibs_hli.txt"
grep -qx "done" "$work/ibs_hli.txt"
echo "check_install: examples/board (the master on a board through the DDI bus adapter) against the same installation" >&2
cmake -S examples/board -B "$work/board-build" -DCMAKE_PREFIX_PATH="$work/full" >/dev/null
cmake --build "$work/board-build" -j "$jobs" >/dev/null
"$work/board-build/board" | tee "$work/board.txt"
grep -qx "done" "$work/board.txt"
IBS_DDI_MODE=stepped "$work/board-build/board" | grep -qx "406-IBCNF = 2 (PCP through the board's mailbox)"
# Through pkg-config: the adapter, and the DDI calls from ibs-ddi -- or from another -l.
# shellcheck disable=SC2046
g++ -std="$(pkg-config --variable=cxx_std ibs-master-ddi)" -Wall -Wextra -Werror examples/board/main.cpp \
  -o "$work/board_pc" $(pkg-config --cflags --libs ibs-master-ddi ibs-ddi) -Wl,-rpath,"$(pkg-config --variable=libdir ibs-ddi)"
IBS_DDI_MODE=stepped "$work/board_pc" | grep -qx "done"
# shellcheck disable=SC2046
g++ -std=c++20 examples/board/main.cpp -o "$work/board_own_pc" $(pkg-config --cflags --libs ibs-master-ddi) \
  -L"$fakeddi" -lfakeddi -Wl,-rpath,"$fakeddi"
rc=0
"$work/board_own_pc" 2>"$work/board-own-pc.txt" || rc=$?
[[ $rc == 2 ]] && grep -qF "$fake_refusal" "$work/board-own-pc.txt" \
  || { echo "check_install: examples/board with -lfakeddi: exit $rc, $(cat "$work/board-own-pc.txt")" >&2; exit 1; }
echo "check_install: examples/hosts (LUSTBUS, CANLust and DFS-1 hosts) against the same installation" >&2
cmake -S examples/hosts -B "$work/hosts-build" -DCMAKE_PREFIX_PATH="$work/full" >/dev/null
cmake --build "$work/hosts-build" -j "$jobs" >/dev/null
ibs_bin=$work/full/bin/ibs
# Each host against the installed tool's emulator on a pty (CAN over UDP on loopback); the
# emulators are stopped by the trap below whatever happens.
emulators=()
stop_emulators() {
  for p in "${emulators[@]}"; do kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done
  emulators=()
}
trap 'stop_emulators; rm -rf "$work"' EXIT
wait_for_line() {  # file prefix: the emulator's first line, within 10 s
  for _ in $(seq 100); do
    grep -q "^$2" "$1" 2>/dev/null && { sed -n "s/^$2//p" "$1" | head -n 1; return 0; }
    sleep 0.1
  done
  echo "check_install: no '$2' line from the emulator" >&2
  return 1
}
"$ibs_bin" lustbus emulate --pty vf1000@1 >"$work/lustbus.txt" 2>&1 &
emulators+=($!)
lustbus_pty=$(wait_for_line "$work/lustbus.txt" "pty: ")
"$work/hosts-build/lustbus_read" "$lustbus_pty" 1 00004 | tee "$work/lustbus_read.txt"
grep -qx "1 00004 = 0000" "$work/lustbus_read.txt"  # 4-FSSEL of a drive on LUSTBUS alone: 0 (docs/errata.md VF-E20)
"$ibs_bin" dfs1 emulate --pty dfs1@1 >"$work/dfs1.txt" 2>&1 &
emulators+=($!)
dfs1_pty=$(wait_for_line "$work/dfs1.txt" "pty: ")
"$work/hosts-build/dfs1_status" "$dfs1_pty" 1 | tee "$work/dfs1_status.txt"
grep -q "^uid 1: commanded 0 rpm, actual 0 rpm" "$work/dfs1_status.txt"
"$ibs_bin" canlust emulate --bus udp:29711:127.0.0.1:29710 cda3000@1 >"$work/canlust.txt" 2>&1 &
emulators+=($!)
wait_for_line "$work/canlust.txt" "bus: " >/dev/null
"$work/hosts-build/canlust_read" 29710 29711 1 360 | tee "$work/canlust_read.txt"
grep -qx "CDA 1 parameter 360: 406" "$work/canlust_read.txt"  # 360-DISP, as docs/canlust.md reads it
# The same hosts through pkg-config (ibs-lustbus, ibs-dfs1, ibs-canlust), as a build without CMake
# links them.
export PKG_CONFIG_PATH="$work/full/lib/pkgconfig:$work/full/lib/x86_64-linux-gnu/pkgconfig"
# shellcheck disable=SC2046
g++ -std=c++20 examples/hosts/lustbus_read.cpp -o "$work/lustbus_read_pc" $(pkg-config --cflags --libs ibs-lustbus)
"$work/lustbus_read_pc" "$lustbus_pty" 1 00004 >/dev/null
# shellcheck disable=SC2046
g++ -std=c++20 examples/hosts/dfs1_status.cpp -o "$work/dfs1_status_pc" $(pkg-config --cflags --libs ibs-dfs1)
# shellcheck disable=SC2046
g++ -std=c++20 examples/hosts/canlust_read.cpp -o "$work/canlust_read_pc" $(pkg-config --cflags --libs ibs-canlust)
stop_emulators
# The simulator through pkg-config (ibs-sim): the default scenario run by a user's program.
cat >"$work/sim_pc.cpp" <<'CPP'
#include <cstdio>
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"
int main() {
  ibs::sim::Simulator sim(ibs::sim::default_scenario());
  sim.run();
  const auto& summary = sim.summary();
  std::printf("%zu devices simulated\n", summary.devices.size());
  return summary.devices.size() == 2 ? 0 : 1;
}
CPP
# shellcheck disable=SC2046
g++ -std=c++20 "$work/sim_pc.cpp" -o "$work/sim_pc" $(pkg-config --cflags --libs ibs-sim)
"$work/sim_pc"
echo "check_install: passed" >&2
