// DFS-1: the frame codec and a whole status transaction (host and emulated controller in memory,
// bytes handed over directly, no line timing).
#include <benchmark/benchmark.h>

#include "ibs/devices/dfs1/controller.hpp"
#include "ibs/devices/dfs1/line.hpp"
#include "ibs/dfs1/frame.hpp"
#include "ibs/dfs1/host.hpp"

namespace {

namespace proto = ibs::dfs1;
namespace dev = ibs::devices::dfs1;
using namespace std::chrono_literals;

void BM_EncodeSeedExample(benchmark::State& state) {
  const proto::Frame f = proto::request::set_speed(1, 4096);
  for (auto _ : state) {
    proto::EncodedFrame e = proto::encode(f);
    benchmark::DoNotOptimize(e);
  }
}
BENCHMARK(BM_EncodeSeedExample);

void BM_DecodeStatusResponse(benchmark::State& state) {
  std::array<std::uint8_t, 16> d{};
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = static_cast<std::uint8_t>(i * 7);
  const proto::EncodedFrame e = proto::encode(proto::make_ack(1, d));
  proto::FrameDecoder decoder;
  for (auto _ : state) {
    int frames = 0;
    for (std::uint8_t b : e.span()) frames += decoder.push(b).status == proto::DecodeStatus::frame;
    benchmark::DoNotOptimize(frames);
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(e.size));
}
BENCHMARK(BM_DecodeStatusResponse);

// Host request -> controller -> reply -> host, bytes passed straight across.
void BM_StatusTransactionInMemory(benchmark::State& state) {
  dev::Controller controller({1});
  proto::HostTransaction host({100ms, 10ms});
  ibs::Time now{};
  for (auto _ : state) {
    now += 1ms;
    (void)host.start(proto::request::status(1), now);
    controller.receive(host.tx(), now);
    host.transmitted(now);
    const ibs::Time due = *controller.next_deadline();
    const auto reply = controller.pending(due);
    host.receive(reply, due);
    controller.consume(reply.size());
    auto r = host.take_result();
    benchmark::DoNotOptimize(r);
    now = due;
  }
}
BENCHMARK(BM_StatusTransactionInMemory);

// The same through the master's queue and the simulated line at 38400 baud (character timing).
void BM_StatusTransactionOnSimulatedLine(benchmark::State& state) {
  dev::Master master({100ms, 10ms});
  dev::Controller controller({1});
  dev::SimulatedLine line(master, {&controller}, 38400);
  for (auto _ : state) {
    (void)master.submit(proto::request::status(1));
    line.run_until_idle(line.now() + 1s);
    auto c = master.take_completion();
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_StatusTransactionOnSimulatedLine);

}  // namespace
