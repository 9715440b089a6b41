// Speed of the VF1000 parameter channel (INTERBUS manual 4.1): single steps of the inverter (Server) and
// the master (Client), and whole transactions with both sides in memory, stepped by the timing
// convention of the cycle tables (each side answers the other's previous word).
#include <benchmark/benchmark.h>

#include "ibs/vf1000_channel/client.hpp"
#include "ibs/devices/vf1000/channel.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/vf1000_channel/server.hpp"

namespace {

using namespace ibs::vf1000_channel;
using namespace ibs::drive;
using namespace ibs::devices::vf1000;
using ibs::Time;
using ibs::Word;
using namespace std::chrono_literals;

ClientConfig bench_client() {
  ClientConfig c;
  c.start_synchronised = true;
  return c;
}

// Inverter step with nothing new (the master holds its word): the most frequent case.
void BM_ServerStepHold(benchmark::State& state) {
  Server s(server_config(), ServerStart::operational, Time{0}, parameters());
  Time now{0};
  s.step(0x2C2D, now, false);  // a description scan is running
  for (auto _ : state) {
    now += 8200us;
    benchmark::DoNotOptimize(s.step(0x2C2D, now, false));
  }
}
BENCHMARK(BM_ServerStepHold);

// Inverter step that sends the next byte of a description scan (a toggle every step).
void BM_ServerStepNextByte(benchmark::State& state) {
  Server s(server_config(), ServerStart::operational, Time{0}, parameters());
  Time now{0};
  bool toggle = true;
  s.step(master_start_word(true, Code::description_scan, pnr::kVb2), now, false);
  int sent = 1;
  for (auto _ : state) {
    now += 8200us;
    toggle = !toggle;
    if (sent == 18) {  // start the next scan after the last byte
      s.step(kMasterIdleWord, now, false);
      toggle = true;
      sent = 0;
      benchmark::DoNotOptimize(
          s.step(master_start_word(true, Code::description_scan, pnr::kVb2), now, false));
    } else {
      benchmark::DoNotOptimize(
          s.step(master_word(toggle, Code::description_scan, 0, 0), now, false));
    }
    ++sent;
  }
}
BENCHMARK(BM_ServerStepNextByte);

// Master step while it waits for the inverter's answer.
void BM_ClientStepWaiting(benchmark::State& state) {
  ClientConfig cfg = bench_client();
  cfg.timeout = 24h;
  Client c(cfg);
  Time now{0};
  c.submit(value_inquiry(pnr::kFmax1));
  c.step(kInverterWaitWord, now);
  for (auto _ : state) {
    now += 1ms;
    benchmark::DoNotOptimize(c.step(kInverterWaitWord, now));  // toggle 0: no answer yet
  }
}
BENCHMARK(BM_ClientStepWaiting);

// One transaction end to end: submit, step both sides until the outcome, read it. In a steady
// loop, so each iteration also carries the previous transaction's return to wait mode.
template <typename MakeRequest>
void run_transactions(benchmark::State& state, MakeRequest make, OutcomeKind expected) {
  Server s(server_config(), ServerStart::operational, Time{0}, parameters());
  Client c(bench_client());
  Time now{0};
  Word m2s = Client::initial_word();
  Word s2m = s.output();
  long steps = 0;
  for (auto _ : state) {
    const RequestId id = c.submit(make()).id;
    do {
      now += 16400us;
      const Word next_s2m = s.step(m2s, now, false);
      m2s = c.step(s2m, now);
      s2m = next_s2m;
      ++steps;
    } while (c.busy());
    const Outcome* o = c.outcome(id);
    if (o == nullptr || o->kind != expected) state.SkipWithError("unexpected outcome");
    benchmark::DoNotOptimize(o->value);
  }
  state.counters["steps"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kAvgIterations);
}

void BM_ValueInquiry(benchmark::State& state) {
  run_transactions(
      state, [] { return value_inquiry(pnr::kFmax1); }, OutcomeKind::value);
}
BENCHMARK(BM_ValueInquiry);

void BM_ValueTransfer(benchmark::State& state) {
  Word v = 0;
  run_transactions(
      state, [&v] { return value_transfer(pnr::kFmax1, static_cast<Word>(v++ % 19999U)); },
      OutcomeKind::written);
}
BENCHMARK(BM_ValueTransfer);

void BM_DescriptionScan(benchmark::State& state) {
  run_transactions(
      state, [] { return description_scan(pnr::kVb2); }, OutcomeKind::description);
}
BENCHMARK(BM_DescriptionScan);

}  // namespace
