// CANLust speed: telegram coding, one parameter read both sides in memory (client -> frame ->
// server -> drive -> frame -> client), a string read, the exact frame length with stuffing, and
// the CDA3000 master driver's cycle for 100 drives (issue 12: under 2 us).
#include <benchmark/benchmark.h>

#include <span>

#include "ibs/can/bit_timing.hpp"
#include "ibs/can/cannelloni.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/canlust/parameter_client.hpp"
#include "ibs/canlust/telegrams.hpp"
#include "ibs/devices/cda3000/device.hpp"
#include "ibs/devices/cda3000/driver.hpp"

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

// Issue 26's row: one parameter read of the client from the emulated CDA3000 (the wing's drive,
// commissioned for the bus at address 1), both in memory: the request frame into the drive, its
// reply frame out of it into the client, the value checked against the drive's own. Out of line,
// so that callgrind counts one call per read (bench/callgrind_per_call.sh ... cda3000_read_once).
struct Cda3000Pair {
  devices::cda3000::Cda3000 drive{devices::cda3000::DeviceConfig{
      .connector_address = 1, .saved = devices::cda3000::commissioned_for_bus(1)}};
  ParameterClient client{[] {
    ClientConfig c;
    c.completed_capacity = 4;
    return c;
  }()};
  Time now{0};
  std::uint32_t expected = 0;
  Cda3000Pair() {
    drive.power_on(now);
    drive.step(now);
    while (drive.take_frame()) {
    }
    expected = *drive.value(571);
  }
};

// The frames are taken into one frame of the caller (take_frame(CanFrame&), issue 26).
[[gnu::noinline]] std::uint32_t cda3000_read_once(Cda3000Pair& p) {
  const auto id = p.client.submit(read(1, 571)).id;
  p.client.step(p.now);
  CanFrame f;
  if (p.client.take_frame(f)) p.drive.receive(f, p.now);
  p.drive.step(p.now);
  std::uint32_t value = ~0U;
  while (p.drive.take_frame(f)) p.client.receive(f, p.now);
  if (const Poll r = p.client.poll(id); r.outcome != nullptr && r.outcome->kind == OutcomeKind::done) {
    value = r.outcome->value;
  }
  p.now += 1ms;
  return value;
}

void BM_ParameterReadCda3000BothSides(benchmark::State& state) {
  Cda3000Pair p;
  for (auto _ : state) {
    if (cda3000_read_once(p) != p.expected) {
      state.SkipWithError("the read did not return 571-CLADR's value");
      break;
    }
  }
}
BENCHMARK(BM_ParameterReadCda3000BothSides);

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

// The CDA3000 master driver's cycle for 100 drives (addresses 0..99), all held in ENABLED with
// a reference: the sequencers on the drives' last status words, the control telegrams due, and
// the frames taken out of the outbox (not put on a bus).
struct HundredDrives {
  devices::cda3000::Driver driver;
  IdentifierMap ids;
  ProcessLayout layout = *process_layout_for_cacnf(2);
  Time now{0};

  static devices::cda3000::DriverConfig config() {
    devices::cda3000::DriverConfig c;
    for (unsigned a = 0; a < 100; ++a) c.drives.push_back({static_cast<Address>(a), 2, 400.0});
    return c;
  }
  HundredDrives() : driver(config()) {
    driver.system_start(now);
    for (unsigned a = 0; a < 100; ++a) {
      const auto ad = static_cast<Address>(a);
      driver.request(ad, drivecom::Target::enabled, now);
      driver.set_reference_hz(ad, 10.0 + 0.25 * a);
      status(ad);
    }
    for (int i = 0; i < 3; ++i) cycle(1ms);  // every sequencer reached ENABLED
  }
  void status(Address a) {
    driver.receive(*encode_status(ids, a, layout, {0x0637, q16_from_double(10.0 + 0.25 * a)}), now);
  }
  std::size_t cycle(Duration dt) {
    now += dt;
    driver.cycle(now);
    std::size_t n = 0;
    while (auto f = driver.take_frame()) {
      benchmark::DoNotOptimize(f);
      ++n;
    }
    return n;
  }
};

// A 1 ms master cycle: the status telegrams of that millisecond (575-CASCY 80 ms: 100 drives
// spread over it, about 1.25 each cycle) taken in, the cycle, the control telegrams that fall due
// (control period 50 ms: 2 each cycle).
void BM_Cda3000MasterCycle100Drives(benchmark::State& state) {
  HundredDrives h;
  std::size_t frames = 0;
  std::uint64_t tick = 0;
  for (auto _ : state) {
    // Drive a sends its status at a x 0.8 ms in every 80 ms.
    const std::uint64_t ms = tick % 80;
    for (unsigned a = 0; a < 100; ++a) {
      if ((a * 8U) / 10U == ms) h.status(static_cast<Address>(a));
    }
    frames += h.cycle(1ms);
    ++tick;
  }
  state.counters["frames/cycle"] = benchmark::Counter(static_cast<double>(frames) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_Cda3000MasterCycle100Drives);

// The worst cycle: every drive's control telegram due at once (100 frames encoded and queued).
void BM_Cda3000MasterCycle100DrivesAllDue(benchmark::State& state) {
  HundredDrives h;
  std::size_t frames = 0;
  for (auto _ : state) frames += h.cycle(50ms);
  state.counters["frames/cycle"] = benchmark::Counter(static_cast<double>(frames) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_Cda3000MasterCycle100DrivesAllDue);

}  // namespace
