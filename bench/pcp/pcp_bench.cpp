// CPU cost of the PCP machines: one complete Read (submit -> confirmation) over 1, 2 and 4
// channel words, the client stepped every bus cycle and the server every device sample in
// lock-step (1 ms each, the trace timing). Simulated time is not measured here; docs/pcp.md
// ("Latency model") has that.
#include <benchmark/benchmark.h>

#include <array>

#include "ibs/pcp/client.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/pcp_served.hpp"
#include "ibs/pcp/server.hpp"

namespace {

using namespace ibs;
using namespace ibs::pcp;

struct Loop {
  explicit Loop(int words, LatencyModel latency)
      : client([&] {
          ClientConfig c;
          c.channel_words = words;
          return c;
        }()),
        served(drive),
        server([&] {
          ServerConfig c = ibs::devices::mc6000::server_config(1);
          c.channel_words = words;
          c.latency = latency;
          c.start = StartMode::running;
          return c;
        }(), served) {
    drive.read(now, ibs::devices::mc6000::kSerr);  // running: 85-SERR read
  }
  Loop(const Loop&) = delete;
  Loop& operator=(const Loop&) = delete;

  // Steps until the client reports, counting them in `steps`; the result stays in the client
  // (Client::take_result_view: no copy of the 312-byte Result).
  const Result& until_result(std::int64_t& steps) {
    for (;;) {
      now += 1ms;
      const auto to_server = m2s;
      const auto to_client = s2m;
      client.step(now, to_client, m2s);
      server.step(now, to_server, s2m);
      ++steps;
      if (const Result* r = client.take_result_view()) return *r;
    }
  }

  Client client;
  // The MC6000's parameters (its drive core's) behind the server.
  ibs::devices::mc6000::ParametersOnly drive{ibs::devices::mc6000::drive_parameters_config()};
  ibs::devices::mc6000::PcpServed served;
  Server server;
  Time now{};
  std::array<Word, 4> m2s{};
  std::array<Word, 4> s2m{};
};

// One Read of 2-IBSTU, submit to confirmation, both sides stepped. Out of line, so that callgrind
// counts one call per Read (bench/callgrind_per_call.sh ... read_once).
[[gnu::noinline]] const Result& read_once(Loop& loop, std::int64_t& steps) {
  loop.client.read(loop.now, ParameterRef::number(ibs::devices::mc6000::kIbstu));
  return loop.until_result(steps);
}

void run_reads(benchmark::State& state, LatencyModel latency) {
  const int words = static_cast<int>(state.range(0));
  Loop loop(words, latency);
  std::int64_t initiate_steps = 0;
  loop.client.initiate(loop.now);
  if (!loop.until_result(initiate_steps).ok()) state.SkipWithError("Initiate failed");
  // The Read's value checked: the bytes of the value the drive stores.
  const std::optional<Value> stored = loop.served.value(ibs::devices::mc6000::kIbstu);
  std::array<std::uint8_t, kMaxValueSize> b{};
  DataBytes expected;
  if (stored) expected.assign(std::span<const std::uint8_t>(b.data(), encode(*stored, b)));
  std::int64_t steps = 0;
  for (auto _ : state) {
    const Result& r = read_once(loop, steps);
    if (!r.ok() || !stored || !(r.data == expected)) {
      state.SkipWithError("the Read did not confirm 2-IBSTU's stored value");
      break;
    }
    benchmark::DoNotOptimize(r.data);
  }
  state.counters["steps/read"] =
      benchmark::Counter(static_cast<double>(steps) / static_cast<double>(state.iterations()));
  state.counters["ns/step"] = benchmark::Counter(
      static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Protocol work only: the servo answers in the step the request completes.
void BM_Read(benchmark::State& state) {
  run_reads(state, LatencyModel::immediate());
}
BENCHMARK(BM_Read)->Arg(1)->Arg(2)->Arg(4);

// With the calibrated latency model at workload 0 (idle steps while the servo "processes").
void BM_ReadCalibratedLatency(benchmark::State& state) {
  run_reads(state, ibs::devices::mc6000::pcp_latency(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_ReadCalibratedLatency)->Arg(1)->Arg(2)->Arg(4);


}  // namespace
