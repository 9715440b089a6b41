// LUSTBUS protocol core: one telegram encoded and decoded, the device's receiver taking a SELECT,
// and a whole ENQUIRY — host submit to outcome, device receiver and responder — in memory.
#include <benchmark/benchmark.h>

#include <cstdio>

#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/receiver.hpp"

namespace {

using namespace ibs;
using namespace ibs::lustbus;

// A responder with one value, the least a drive can do.
class OneValue : public Responder {
 public:
  EnquiryAnswer enquiry(const Code&, const Context&) override {
    return EnquiryAnswer::text(value_);
  }
  SelectAnswer select(const Code&, const Value& v, const Context&) override {
    value_ = v;
    return SelectAnswer::ack();
  }
  void checksum_error(const Context&) override {}

 private:
  Value value_ = make_value("03E8");
};

void BM_EncodeSelect(benchmark::State& state) {
  const Code c = make_code(105);
  const Value v = make_value("03E8");
  for (auto _ : state) {
    Frame f = encode_select(1, c, v);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_EncodeSelect);

void BM_EncodeMc32BitValue(benchmark::State& state) {
  for (auto _ : state) {
    const auto v = encode(Family::enhanced, DataType::int32q16, 333.254);
    Frame f = encode_select(1, make_code(20428), v.value);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_EncodeMc32BitValue);

void BM_DecodeAnswer(benchmark::State& state) {
  const Frame answer = encode_text_answer(1, make_code(112), make_value("03E8"));
  AnswerDecoder d;
  for (auto _ : state) {
    d.start(1, make_code(112), AnswerDecoder::Expect::text_or_nak);
    for (std::size_t i = 0; i < answer.size; ++i) d.feed(answer.bytes[i]);
    benchmark::DoNotOptimize(d.value());
  }
}
BENCHMARK(BM_DecodeAnswer);

void BM_ReceiverSelect(benchmark::State& state) {
  OneValue r;
  Receiver rx(r, 1);
  const Frame sel = encode_select(1, make_code(105), make_value("03E8"));
  Time now{0};
  for (auto _ : state) {
    for (std::size_t i = 0; i < sel.size; ++i) rx.receive(sel.bytes[i], now);
    benchmark::DoNotOptimize(rx.take_answer(now));
  }
}
BENCHMARK(BM_ReceiverSelect);

// One ENQUIRY: submit, EOT ADR CODE ENQ to the receiver, its answer to the host, the host's EOT,
// the outcome. Out of line, so that callgrind counts one call per exchange
// (bench/callgrind_per_call.sh ... enquiry_once).
[[gnu::noinline]] const Outcome* enquiry_once(Host& host, Receiver& rx, const Request& req, Time& now) {
  const RequestId id = host.submit(req).id;
  host.step(now);
  rx.receive(host.take_output(), now);
  host.output_done(now);
  host.receive(rx.take_answer(now), now);
  rx.receive(host.take_output(), now);  // EOT
  host.output_done(now);
  now += std::chrono::microseconds{1};
  return host.outcome(id);
}

void BM_EnquiryBothSides(benchmark::State& state) {
  OneValue r;
  Receiver rx(r, 1);
  Host host;
  const Request req = enquiry(1, make_code(112));
  Time now{0};
  for (auto _ : state) benchmark::DoNotOptimize(enquiry_once(host, rx, req, now));
}
BENCHMARK(BM_EnquiryBothSides);

// The same exchange with the wing's emulated VF1000 (its reaction time 0) answering 91-TYPE, the
// row of issue 26 (docs/performance.md); the answer is checked against the inverter's stored value.

void BM_EnquiryVf1000BothSides(benchmark::State& state) {
  devices::vf1000::LustbusTiming timing;
  timing.reaction = ReactionModel::fixed(Duration(0));
  devices::vf1000::LustbusDevice vf(timing);
  Receiver rx(vf, 1);
  Host host;
  const Request req = enquiry(1, kTypeCode);
  char text[8];
  std::snprintf(text, sizeof text, "%04X", static_cast<unsigned>(vf.value(kParamType)));
  const Value expected = make_value(text);
  Time now{0};
  for (auto _ : state) {
    const Outcome* o = enquiry_once(host, rx, req, now);
    if (o == nullptr || o->kind != OutcomeKind::value || !(o->value == expected)) {
      state.SkipWithError("the VF1000 did not answer 91-TYPE with its stored value");
      break;
    }
  }
}
BENCHMARK(BM_EnquiryVf1000BothSides);

}  // namespace
