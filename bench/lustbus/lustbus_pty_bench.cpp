// LUSTBUS over a pseudo-terminal in real time (docs/performance.md, "LUSTBUS over a pty"): the
// host (serial::transact, transports/serial/lustbus_host.hpp) asks an emulated VF1000 (serial::serve, reaction time 0) for 91-TYPE.
// Reported per ENQUIRY: the whole transaction (request out, answer in, closing EOT out) and the
// host's turnaround of the LUSTBUS manual 10 step 4 -- the last answer byte read to the EOT written --
// taken from the host's byte log timestamps; p50 and p99 over all iterations.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/lustbus/served_receiver.hpp"
#include "ibs/serial/byte_log.hpp"
#include "ibs/serial/lustbus_host.hpp"
#include "ibs/serial/pty.hpp"
#include "ibs/serial/serve.hpp"

namespace {

namespace lb = ibs::lustbus;

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

// Host turnarounds from the byte log: an `rx` line followed by a `tx ... 04` line.
std::vector<double> turnarounds_us(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<double> out;
  double last_rx = -1;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    double t = 0;
    std::string dir;
    std::string port;
    ls >> t >> dir >> port;
    std::string rest;
    std::getline(ls, rest);
    if (dir == "rx") {
      last_rx = t;
    } else if (dir == "tx" && rest == " 04" && last_rx >= 0) {
      out.push_back((t - last_rx) * 1e6);
      last_rx = -1;
    }
  }
  return out;
}

void BM_PtyEnquiryRoundTrip(benchmark::State& state) {
  ibs::devices::vf1000::LustbusTiming timing;
  timing.reaction = ibs::lustbus::ReactionModel::fixed(ibs::Duration(0));
  ibs::devices::vf1000::LustbusDevice vf(timing);
  lb::Receiver rx(vf, 1);
  auto pair = ibs::serial::PtyPair::open({9600, ibs::serial::k7E1, false});
  lb::ServedReceiver served_vf{&rx, [&vf](ibs::Time t) { vf.advance(t); }};
  std::vector<ibs::base::LineDevice*> served{&served_vf};
  std::atomic<bool> stop{false};
  std::thread server([&] { ibs::serial::serve(pair.master(), served, [&] { return stop.load(); }); });
  auto port = ibs::serial::SerialPort::open(pair.slave_path(), {9600, ibs::serial::k7E1, false});
  const std::string log_path = "/tmp/ibs_lustbus_pty_bench.log";
  {
    ibs::serial::ByteLog log(log_path);
    port.set_log(&log);
    lb::Host host(lb::HostConfig{});
    const auto request = lb::enquiry(1, lb::kTypeCode);
    std::vector<double> round_trips;
    for (auto _ : state) {
      const auto t0 = std::chrono::steady_clock::now();
      const lb::Outcome o = ibs::serial::transact(port, host, request);
      const auto t1 = std::chrono::steady_clock::now();
      if (o.kind != lb::OutcomeKind::value) state.SkipWithError("no value");
      round_trips.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
    port.set_log(nullptr);
    state.counters["round_trip_p50_us"] = percentile(round_trips, 0.50);
    state.counters["round_trip_p99_us"] = percentile(round_trips, 0.99);
  }
  const auto ta = turnarounds_us(log_path);
  state.counters["turnaround_p50_us"] = percentile(ta, 0.50);
  state.counters["turnaround_p99_us"] = percentile(ta, 0.99);
  state.counters["samples"] = static_cast<double>(ta.size());
  std::remove(log_path.c_str());
  stop = true;
  server.join();
}
BENCHMARK(BM_PtyEnquiryRoundTrip)->Iterations(2000)->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace
