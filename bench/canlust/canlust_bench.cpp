// CANLust speed: telegram coding, one parameter read both sides in memory (client -> frame ->
// server -> drive -> frame -> client), a string read, and the exact frame length with stuffing.
#include <benchmark/benchmark.h>

#include <span>

#include "ibs/can/bit_timing.hpp"
#include "ibs/can/cannelloni.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/canlust/parameter_client.hpp"
#include "ibs/canlust/telegrams.hpp"

namespace {

using namespace ibs;
using namespace ibs::canlust;

class TableDrive final : public ParameterAccess {
 public:
  ValueResult read(std::uint16_t n, std::uint8_t, Time) override {
    return {kStatusOk, DataType::usign16, n == 360 ? 406U : 0U, {}};
  }
  AccessResult write(std::uint16_t, std::uint8_t, std::uint32_t, Time) override { return {}; }
  ValueResult describe(std::uint16_t, std::uint8_t, Time) override { return {}; }
  StringResult read_string(std::uint16_t, std::span<char> out, Time) override {
    constexpr std::string_view s = "CANLust benchmark string";
    std::copy(s.begin(), s.end(), out.begin());
    return {kStatusOk, static_cast<std::uint8_t>(s.size()), {}};
  }
  AccessResult write_string(std::uint16_t, std::string_view, Time) override { return {}; }
};

void BM_ParameterFrameEncodeDecode(benchmark::State& state) {
  const IdentifierMap ids;
  ParameterTelegram t{360, kModeRead, 0, 0};
  for (auto _ : state) {
    const auto f = encode_parameter_request(ids, 1, t);
    const auto c = ids.classify(f->id);
    const auto d = decode_parameter(*f);
    benchmark::DoNotOptimize(c);
    benchmark::DoNotOptimize(d);
    ++t.data;
  }
}
BENCHMARK(BM_ParameterFrameEncodeDecode);

void BM_ControlFrameEncodeDecode(benchmark::State& state) {
  const IdentifierMap ids;
  const auto l = *process_layout_for_cacnf(2);
  ControlTelegram t{0x000F, q16_from_double(20.5)};
  for (auto _ : state) {
    const auto f = encode_control(ids, 1, l, t);
    const auto d = decode_control(*f, l);
    benchmark::DoNotOptimize(d);
    ++t.reference;
  }
}
BENCHMARK(BM_ControlFrameEncodeDecode);

void BM_CannelloniEncodeDecode(benchmark::State& state) {
  const auto f = CanFrame::make(1323, {0x68, 0x01, 0x00, 0x96, 0x01, 0x00, 0x00, 0x00});
  std::array<std::uint8_t, 32> buf{};
  std::array<CanFrame, 1> out{};
  std::uint8_t seq = 0;
  for (auto _ : state) {
    const auto n = can::cannelloni::encode(std::span(&f, 1), seq++, buf);
    const auto r = can::cannelloni::decode(std::span(buf.data(), *n), out);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_CannelloniEncodeDecode);

// One read: the client's request frame, the server's reply frame, the outcome.
void BM_ParameterReadBothSides(benchmark::State& state) {
  TableDrive drive;
  ParameterServer server(drive);
  ClientConfig cfg;
  cfg.completed_capacity = 4;
  ParameterClient client(cfg);
  const IdentifierMap ids;
  Time now{0};
  for (auto _ : state) {
    const auto id = client.submit(read(1, 360)).id;
    client.step(now);
    const auto req = client.take_frame();
    server.receive(decode_parameter(*req).value, now);
    const auto rep = encode_parameter_reply(ids, 1, *server.take_reply(now));
    client.receive(*rep, now);
    benchmark::DoNotOptimize(client.poll(id).outcome->value);
    now += 1ms;
  }
}
BENCHMARK(BM_ParameterReadBothSides);

void BM_StringReadBothSides(benchmark::State& state) {
  TableDrive drive;
  ParameterServer server(drive);
  ClientConfig cfg;
  cfg.completed_capacity = 4;
  ParameterClient client(cfg);
  const IdentifierMap ids;
  Time now{0};
  for (auto _ : state) {
    const auto id = client.submit(read_string(1, 7)).id;
    client.step(now);
    while (auto req = client.take_frame()) {
      server.receive(decode_parameter(*req).value, now);
      client.receive(*encode_parameter_reply(ids, 1, *server.take_reply(now)), now);
    }
    benchmark::DoNotOptimize(client.poll(id).outcome->text.length);
    now += 1ms;
  }
}
BENCHMARK(BM_StringReadBothSides);

void BM_FrameBitsWithStuffing(benchmark::State& state) {
  auto f = CanFrame::make(881, {0x37, 0x02, 0x00, 0x80, 0x14, 0x00});
  for (auto _ : state) {
    benchmark::DoNotOptimize(can::frame_bits(f).total());
    ++f.data[5];
  }
}
BENCHMARK(BM_FrameBitsWithStuffing);

}  // namespace
