// The latency model (docs/pcp.md, "Latency model"): end to end at the master, a Read or Write
// takes INTERBUS manual 7.2's 10..35 ms over 1, 2 and 4 words as the workload goes 0..1, with the link on
// the servo's INTERBUS CPU at the bus cycle and the servo processor sampling every 1 ms, on the
// reference bus (one MC6000: 0.567 ms cycles), the default bus (an MC6000 and a VF1000:
// 0.726 ms) and a short ring (three MC6000: 0.989 ms).
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>

#include "pcp_harness.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::pcp {
namespace {

using namespace ibs::devices::mc6000;

struct Span {
  Duration min = Duration::max();
  Duration max = Duration::zero();
  void add(Duration d) {
    min = std::min(min, d);
    max = std::max(max, d);
  }
};

// Reads and writes of 1-, 2- and 4-byte parameters, RAM and EEPROM, at 40 bus/sample phases.
Span measure(int words, double workload, Duration cycle = 567us,
             std::optional<LatencyModel> latency = std::nullopt,
             test::Interface interface = test::Interface::at_cycle) {
  Span s;
  for (int phase = 0; phase < 40; ++phase) {
    Client client(test::client_config(words));
    ServerConfig sc = ibs::devices::mc6000::server_config(1);
    sc.channel_words = words;
    sc.workload = workload;
    sc.latency = latency;
    sc.start = StartMode::running;
    test::Served server_parameters((sc).start);
    Server server(sc, server_parameters.served);
    test::Bus bus(client, server, cycle, 1ms, interface);
    for (int k = 0; k < phase; ++k) bus.cycle();
    EXPECT_EQ(client.initiate(bus.now()), SubmitStatus::accepted);
    EXPECT_TRUE(bus.await()->ok());
    for (int op = 0; op < 6; ++op) {
      const Time t = bus.now();
      switch (op) {
        case 0:
          client.read(t, ParameterRef::number(83));
          break;
        case 1:
          client.write(t, ParameterRef::number(428), DataType::int32q16, 12.5);
          break;
        case 2:
          client.read(t, ParameterRef::number(428));
          break;
        case 3:
          client.write(t, ParameterRef::number(82), Value{DataType::usign8, 5});
          break;
        case 4:
          client.read(t, ParameterRef::number(82));
          break;
        default:
          client.write(t, ParameterRef::number(83), Value{DataType::usign16, 5});
          break;
      }
      const auto r = bus.await();
      EXPECT_TRUE(r && r->ok());
      if (r) s.add(r->completed_at - r->submitted_at);
    }
  }
  return s;
}

// The MC6000's calibration is its wing's (devices/mc6000/channel.hpp), by channel width.
TEST(LatencyModel, TheServosCalibrationPerWidth) {
  EXPECT_EQ(pcp_latency(4).processing_min, 7ms);
  EXPECT_EQ(pcp_latency(4).processing_max, 27ms);
  EXPECT_EQ(pcp_latency(2).processing_min, 6ms);
  EXPECT_EQ(pcp_latency(2).processing_max, 22ms);
  EXPECT_EQ(pcp_latency(1).processing_min, 0ms);
  EXPECT_EQ(pcp_latency(1).processing_max, 8ms);
  EXPECT_EQ(LatencyModel::immediate().processing(1.0), 0ms);
  // The servo's server follows the width it is finally given.
  ServerConfig sc = server_config(1);
  sc.channel_words = 4;
  ASSERT_NE(sc.latency_for, nullptr);
  EXPECT_EQ(sc.latency_for(sc.channel_words).processing_min, 7ms);
}

// PCP itself holds no drive's numbers: a server configured without a latency executes a request
// in the sample it completes, as immediate() does.
TEST(LatencyModel, NeutralWithoutADrivesCalibration) {
  EXPECT_EQ(LatencyModel{}.processing(0.0), 0ms);
  EXPECT_EQ(LatencyModel{}.processing(1.0), 0ms);
  const auto lock_step = [](ServerConfig sc) {
    sc.channel_words = 4;
    sc.workload = 1.0;
    sc.start = StartMode::running;
    Client client(test::client_config(4));
    test::Served parameters(sc.start);
    Server server(sc, parameters.served);
    test::Bus bus(client, server, 1ms, 1ms);
    EXPECT_EQ(client.initiate(bus.now()), SubmitStatus::accepted);
    EXPECT_TRUE(bus.await()->ok());
    client.read(bus.now(), ParameterRef::number(83));
    const auto r = bus.await();
    EXPECT_TRUE(r && r->ok());
    return r ? r->completed_at - r->submitted_at : Duration::max();
  };
  ServerConfig neutral = server_config(4);
  neutral.latency_for = nullptr;
  ServerConfig immediate = server_config(4);
  immediate.latency = LatencyModel::immediate();
  const Duration servo = lock_step(server_config(4));
  EXPECT_EQ(lock_step(neutral), lock_step(immediate));
  EXPECT_GE(servo, lock_step(neutral) + 27ms) << "the servo's 4-word processing at full load";
}

// INTERBUS manual 7.2: "The transfer time for value inquiries and value transfers is between 10 ms and
// 35 ms, depending on processor workload." Every width on every bus of the table, from workload 0
// to 1. Over one word the channel itself takes 12..26 ms of the window, so the workload spreads
// less of it there. (A full ring's 13.86 ms cycles are beyond any width: errata PCP-E7.)
struct WindowRow {
  int words;
  Duration cycle;
  const char* bus;
  Duration workload_share;  // at least this much between workload 0 and 1
};
class ManualWindow : public ::testing::TestWithParam<WindowRow> {};

TEST_P(ManualWindow, ReadAndWriteSpan10To35MsOverTheWorkload) {
  const WindowRow& row = GetParam();
  const Span idle = measure(row.words, 0.0, row.cycle);
  const Span busy = measure(row.words, 1.0, row.cycle);
  RecordProperty("idle", std::to_string(to_ms(idle.min)) + ".." + std::to_string(to_ms(idle.max)));
  RecordProperty("busy", std::to_string(to_ms(busy.min)) + ".." + std::to_string(to_ms(busy.max)));
  EXPECT_GE(idle.min, 10ms) << row.words << " words, " << row.bus;
  EXPECT_LE(busy.max, 35ms) << row.words << " words, " << row.bus;
  EXPECT_GE(busy.min - idle.min, row.workload_share) << "the workload matters";
}

INSTANTIATE_TEST_SUITE_P(
    Seed001Section7_2, ManualWindow,
    ::testing::Values(WindowRow{4, 567us, "reference", 15ms}, WindowRow{2, 567us, "reference", 15ms},
                      WindowRow{1, 567us, "reference", 5ms}, WindowRow{4, 726us, "default", 15ms},
                      WindowRow{2, 726us, "default", 15ms}, WindowRow{1, 726us, "default", 5ms},
                      WindowRow{4, 989us, "short", 15ms}, WindowRow{2, 989us, "short", 15ms},
                      WindowRow{1, 989us, "short", 5ms}),
    [](const ::testing::TestParamInfo<WindowRow>& i) {
      return std::to_string(i.param.words) + "WordsOn" + (std::string(i.param.bus) == "reference" ? "TheReferenceBus"
              : std::string(i.param.bus) == "default"                                           ? "TheDefaultBus"
                                                                                                  : "AShortRing");
    });

// The link on the servo's INTERBUS CPU moves one fragment per bus cycle both ways (window two,
// docs/pcp.md): a Read of 83 over one word, 10 request and 12 confirmation bytes, takes 22
// cycles of fragments and a few of turn-around and the sample the request waits for, however the
// 1 ms sample falls against the cycle.
TEST(LatencyModel, TheLinkMovesOneFragmentPerBusCycle) {
  for (const Duration cycle : {567us, 989us}) {
    Span transfer;
    for (int phase = 0; phase < 20; ++phase) {
      Client client(test::client_config(1));
      ServerConfig sc = ibs::devices::mc6000::server_config(1);
      sc.latency = LatencyModel::immediate();
      sc.start = StartMode::running;
      test::Served server_parameters(sc.start);
      Server server(sc, server_parameters.served);
      test::Bus bus(client, server, cycle, 1ms, test::Interface::at_cycle);
      for (int k = 0; k < phase; ++k) bus.cycle();
      client.initiate(bus.now());
      ASSERT_TRUE(bus.await()->ok());
      client.read(bus.now(), ParameterRef::number(83));
      const auto r = bus.await();
      ASSERT_TRUE(r && r->ok());
      transfer.add(r->completed_at - r->submitted_at);
    }
    EXPECT_GE(transfer.min, 22 * cycle);
    EXPECT_LE(transfer.max, 26 * cycle + 1ms) << "cycle " << to_ms(cycle) << " ms";
  }
}

TEST(LatencyModel, LockStepTraceTimingIsNeverFaster) {
  // One trace step = one bus cycle = one sample = 1 ms, and the link runs in the servo's step: a
  // fragment still moves every step, but each step is longer than the reference bus's cycle.
  const Span s = measure(4, 0.0, 1ms, std::nullopt, test::Interface::at_sample);
  EXPECT_GE(s.min, measure(4, 0.0).min);
  EXPECT_GE(s.min, 10ms);
}

}  // namespace
}  // namespace ibs::pcp
