#!/usr/bin/env bash
# The embedded build (docs/embedding.md, "An embedded build"), checked as a user would, outside the
# build tree:
#  1. -DIBS_EMBEDDED=ON in Release with -Werror, Eigen, CLI11, toml++, nlohmann-json, {fmt},
#     GoogleTest and Google Benchmark forbidden to CMake, installed into a fresh prefix without the trace and
#     replay headers;
#  2. the installed static libraries throw and catch nothing and carry no RTTI and no iostreams:
#     no reference to __cxa_throw, __cxa_begin_catch, __gxx_personality_v0 (nm), no typeinfo
#     (_ZTI, _ZTS), no std::cout & co. or std::ios_base::Init, no exception tables (objdump); the
#     calls into libstdc++'s own std::__throw_* (allocation failure and the like) are allowed: they
#     abort under -fno-exceptions, and are listed;
#  3. a program compiled with g++ -std=c++20 -fno-exceptions -fno-rtti and linked through
#     pkg-config (ibs-master) gets an error code for 405-SUPI = 13, then runs a master loop over
#     the in-memory bus and sees the control word it must; it exits 0 only when all of that held;
#  4. a constructor given a configuration its validate() refuses aborts with the error's code and
#     message (the embedded build's precondition);
#  5. the throwing API is not there: the same compiler refuses a call of make_layout.
# Usage: tools/check_embedded.sh
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
jobs=$(nproc 2>/dev/null || echo 2)

echo "check_embedded: the embedded build" >&2
# In build/embedded, the folder docs/embedding.md builds the same configuration in, so that
# check_docs finds it built (and ccache, hashing paths below the source folder, finds its objects).
embedded_build=build/embedded
cmake -S . -B "$embedded_build" --no-warn-unused-cli -DIBS_EMBEDDED=ON -DCMAKE_BUILD_TYPE=Release -DIBS_WERROR=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON -DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_fmt=ON >/dev/null
cmake --build "$embedded_build" -j "$jobs" >/dev/null
cmake --install "$embedded_build" --prefix "$work/prefix" >/dev/null
fail() {
  echo "check_embedded: $*" >&2
  exit 1
}
if [[ -e "$work/prefix/bin/ibs" ]] || ls "$work/prefix"/lib*/libibs_sim* >/dev/null 2>&1; then
  fail "the embedded installation holds the simulator or the tool"
fi
for header in interbus/trace.hpp interbus/replay.hpp interbus/text_file.hpp devices/trace_support.hpp \
              vf1000_channel/trace_adapters.hpp devices/mc6000/pcp_trace.hpp devices/mc6000/pd_trace.hpp \
              devices/vf1000/pd_trace.hpp devices/campaign_profile.hpp devices/mc6000/campaign_profile.hpp \
              devices/vf1000/campaign_profile.hpp; do
  if [[ -e "$work/prefix/include/ibs/$header" ]]; then fail "the embedded installation holds ibs/$header"; fi
done

echo "check_embedded: the installed libraries" >&2
mapfile -t libs < <(find "$work/prefix" -name 'libibs_*.a' | sort)
((${#libs[@]} == 14)) || fail "expected the 14 master libraries, found ${#libs[@]}: ${libs[*]}"
# Mangled names: the C++ runtime's throw, catch and personality; typeinfo and its name; the
# standard streams (narrow and wide) and their initialiser.
forbidden='__cxa_throw|__cxa_rethrow|__cxa_allocate_exception|__cxa_begin_catch|__cxa_end_catch'
forbidden+='|__gxx_personality_v0|_ZTI|_ZTS|_ZSt[0-9]+w?(cout|cerr|clog|cin)|_ZNSt8ios_base4Init'
found=0
for lib in "${libs[@]}"; do
  if nm -A "$lib" | grep -E "$forbidden"; then found=1; fi
  if objdump -h "$lib" | grep -E '\.gcc_except_table'; then
    echo "$lib: exception tables" >&2
    found=1
  fi
done
((found == 0)) || fail "the libraries above throw, catch, carry RTTI or use iostreams"
echo "check_embedded: libstdc++ calls that abort under -fno-exceptions:" \
  "$(nm -C "${libs[@]}" | grep -oE 'std::__throw_[a-z_]+' | sort -u | tr '\n' ' ')" >&2

echo "check_embedded: a program without exceptions and RTTI against the installation" >&2
export PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig:$work/prefix/lib/x86_64-linux-gnu/pkgconfig"
cat >"$work/embedded.cpp" <<'CPP'
#include <cstdio>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>
#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/base/error.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/master/memory_bus.hpp"
#if defined(__cpp_exceptions) || defined(__GXX_RTTI)
#error "compiled with exceptions or RTTI"
#endif
static_assert(IBS_EMBEDDED == 1 && IBS_EXCEPTIONS == 0, "the embedded installation");

namespace {
void print(const ibs::Error& e) {
  const std::string_view code = ibs::to_string(e.code);
  std::printf("error code %d (%.*s): %s\n", static_cast<int>(e.code), static_cast<int>(code.size()), code.data(),
              e.message.c_str());
}
}  // namespace

int main() {
  using namespace ibs;
  const auto& kind = devices::mc6000::descriptor();
  devices::DeviceSettings bad;
  bad.drive.set_integer("supi", 13);
  const auto refused = kind.try_configure(bad);
  if (refused) return 1;
  print(refused.error());
  if (refused.error().code != ErrorCode::layout_setting_out_of_range || refused.error().setting != "supi") return 2;

  const auto configured = kind.try_configure({});
  if (!configured) {
    print(configured.error());
    return 3;
  }
  const devices::Configuration& c = configured.value();
  const interbus::DeviceSpec spec{"servo", c.id_code, c.bus};
  auto config = interbus::try_make_bus_config({&spec, 1});
  if (!config) {
    print(config.error());
    return 4;
  }
  if (master::MasterLoop::validate(config.value(), 0).code != ErrorCode::master_driver_count) return 5;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  drivers.push_back(kind.make_driver(c));
  if (const Error e = master::MasterLoop::validate(config.value(), drivers.size())) {
    print(e);
    return 6;
  }
  master::MasterLoop loop(config.value(), std::move(drivers));
  master::MemoryBus bus(config.value());
  interbus::ProcessImage image;
  loop.initial(image);
  loop.driver(0).sequencer().request(drivecom::Target::ready, Time{0});
  bus.device_sends(0)[0] = 0x0240;  // START-UP INHIBIT
  loop.cycle(bus, image, Time{std::chrono::milliseconds(1)});
  std::printf("control word %04X\n", static_cast<unsigned>(bus.device_receives(0)[0]));
  loop.cycle(bus, image, Time{std::chrono::milliseconds(2)});
  std::printf("control word %04X\n", static_cast<unsigned>(bus.device_receives(0)[0]));
  return bus.device_receives(0)[0] == 0x0006 ? 0 : 7;  // SHUTDOWN on its way to READY
}
CPP
flags=(-std=c++20 -fno-exceptions -fno-rtti -Wall -Wextra -Werror)
# shellcheck disable=SC2046
g++ "${flags[@]}" "$work/embedded.cpp" -o "$work/embedded" $(pkg-config --cflags --libs ibs-master)
"$work/embedded" || fail "the program exited $?"

echo "check_embedded: a constructor given what its validate() refuses aborts, naming the error" >&2
cat >"$work/precondition.cpp" <<'CPP'
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/master/master_loop.hpp"
int main() {
  using namespace ibs;
  const auto c = devices::vf1000::descriptor().try_configure({});
  const interbus::DeviceSpec spec{"fan", c->id_code, c->bus};
  const master::MasterLoop loop(interbus::try_make_bus_config({&spec, 1}).value(), {});  // no driver
  return static_cast<int>(loop.size());
}
CPP
# shellcheck disable=SC2046
g++ "${flags[@]}" "$work/precondition.cpp" -o "$work/precondition" $(pkg-config --cflags --libs ibs-master)
status=0
# (The shell's own "Aborted" notice is expected here: dropped.)
{ "$work/precondition" 2>"$work/precondition.log"; } 2>/dev/null || status=$?
((status == 134)) || fail "the constructor did not abort (exit $status)"
grep -qx "ibs: master_driver_count: master loop: 0 drivers for 1 devices" "$work/precondition.log" ||
  fail "the abort said: $(cat "$work/precondition.log")"

echo "check_embedded: no throwing API to call by mistake" >&2
cat >"$work/throwing.cpp" <<'CPP'
#include "ibs/devices/mc6000/layout.hpp"
int main() { return ibs::devices::mc6000::make_layout(11, 2).pd_words; }
CPP
# shellcheck disable=SC2046
if g++ "${flags[@]}" -c "$work/throwing.cpp" -o "$work/throwing.o" $(pkg-config --cflags ibs-master) \
  2>"$work/throwing.log"; then
  fail "make_layout, the throwing form, compiled against the embedded installation"
fi
if ! grep -q "make_layout" "$work/throwing.log"; then
  cat "$work/throwing.log" >&2
  fail "the call of make_layout was refused for another reason"
fi
echo "check_embedded: passed" >&2
