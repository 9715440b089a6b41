// ibs's master on a controller board: the default bus's MC6000 (405-SUPI 11, 406-IBCNF 2) and
// VF1000 brought to ENABLED through the DDI bus adapter, 406-IBCNF read through PCP over the
// board's mailbox, then both drives stopped and the board shut down -- also on SIGINT or SIGTERM.
// The loop runs every bus cycle on CLOCK_MONOTONIC; time is passed in. Exits 0 only when all of
// that happened, within 10 s. Against ibs's virtual board (libibs-ddi) in real time, or stepped
// (IBS_DDI_MODE=stepped); on a real board, the board's DDI library in its place (docs/board.md).
#include <signal.h>
#include <time.h>

#include <csignal>
#include <cstdio>
#include <memory>
#include <vector>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/master/ddi_board.hpp"
#include "ibs/master/master_loop.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

ibs::Time monotonic() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ibs::Time{std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec};
}

void sleep_until(ibs::Time t) {
  const timespec ts{static_cast<time_t>(t.count() / 1'000'000'000), static_cast<long>(t.count() % 1'000'000'000)};
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

}  // namespace

int main() {
  using namespace ibs;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);

  // The ring, the drivers: as for any bus (docs/embedding.md).
  const devices::DriveDescriptor* kinds[] = {&devices::mc6000::descriptor(), &devices::vf1000::descriptor()};
  std::vector<interbus::DeviceSpec> ring;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  for (const devices::DriveDescriptor* kind : kinds) {
    const devices::Configuration c = kind->configure({});
    ring.push_back({std::string(kind->name()), c.id_code, c.bus});
    drivers.push_back(kind->make_driver(c));
  }
  const interbus::BusConfig config = interbus::make_bus_config(ring);

  // The board: both nodes, plug & play off, its configuration the master's, data transfer on.
  auto opened = master::DdiBoard::open(config);  // IBB1N1: the first ISA / PCI board
  if (!opened) {
    std::fprintf(stderr, "board: %s\n", opened.error().message.c_str());
    return 2;
  }
  master::DdiBoard& board = *opened.value();
  master::MasterLoop loop(config, std::move(drivers));
  board.attach(loop);  // the servo's parameters through the board's mailbox
  interbus::ProcessImage image;
  loop.initial(image);

  const Duration cycle = board.cycle_time() > Duration::zero() ? board.cycle_time() : Duration{2ms};
  const Time start = monotonic();
  Time next = start;
  const auto next_cycle = [&] {  // each cycle at its deadline; its time from the start
    next += cycle;
    sleep_until(next);
    return monotonic() - start + Time{0};
  };
  loop.driver(0).sequencer().request(drivecom::Target::enabled, Time{0});
  loop.driver(1).sequencer().request(drivecom::Target::enabled, Time{0});
  loop.driver(0).set_reference(1000.0);  // rpm
  loop.driver(1).set_reference(25.0);    // Hz
  devices::ParamId read = 0;
  bool enabled = false;
  devices::ParamStatus ibcnf;
  Time t{0};
  while (!g_stop && t < Time{10s}) {
    t = next_cycle();
    loop.cycle(board.bus(), image, t);
    if (board.bus().failed()) break;             // SysFail: every device lost, nothing to stop
    board.bus().clear_events();                  // what the board reported (BUS, PF, ...): not needed here
    enabled = loop.driver(0).sequencer().report().state_seen == drivecom::State::enabled &&
              loop.driver(1).sequencer().report().state_seen == drivecom::State::enabled;
    if (enabled && read == 0) read = loop.driver(0).parameters().submit(devices::ParamOp::read, 406, 0);
    if (read != 0) ibcnf = loop.driver(0).parameters().status(read);
    if (ibcnf.done()) break;
  }
  std::printf("MC6000 %s at %.0f rpm; VF1000 %s at %.2f Hz\n", enabled ? "ENABLED" : "not enabled",
              loop.driver(0).actual(), enabled ? "ENABLED" : "not enabled", loop.driver(1).actual());
  if (ibcnf.kind == devices::ParamKind::value) {
    std::printf("406-IBCNF = %lld (PCP through the board's mailbox)\n", static_cast<long long>(ibcnf.value));
  }
  // Stop: references 0, SHUTDOWN to READY once at rest; then data transfer stopped, nodes closed.
  const bool stopped = !board.bus().failed() && master::stop_drives(loop, board.bus(), image, next_cycle);
  const Error closed = board.close();
  if (closed) std::fprintf(stderr, "board: %s\n", closed.message.c_str());
  const bool ok = enabled && ibcnf.kind == devices::ParamKind::value && ibcnf.value == 2 && stopped && !closed && !g_stop;
  std::printf("%s\n", ok ? "done" : "FAILED");
  return ok ? 0 : 1;
}
