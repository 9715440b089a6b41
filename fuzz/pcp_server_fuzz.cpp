// The MC6000's PCP server (pcp::Server, docs/pcp.md "Server") fed channel words cycle by cycle
// with time passed in: each cycle either arbitrary words, or the frame of a master-side link
// through which the input sends PDUs (Initiate, Read, Write with arbitrary index, subindex and
// data, arbitrary bytes), so that both the link's defences and the services behind them are
// reached; with power-ons, a running drive, faults and workloads in between.
//
// Asserts that a parameter's value in the server's store changes only on a complete, checked
// Write (docs/pcp.md, the table of negative confirmations):
// - complete: a Write.req for the parameter's index, subindex 0, carrying the new value in
//   exactly the type's bytes, is among the messages that the loose model of the channel
//   (fuzz/support/pcp_model.hpp: FIRST .. LAST in sequence, count word) could have
//   assembled from the frames the server saw -- decoded here from the documented layout;
// - checked: the parameter is writable (not a RAM actual value), the value lies within its
//   min..max, 85-SERR was 0 and the association stood before the step, and an EEPROM parameter
//   was not still being saved;
// - the documented exceptions: 80-SLOAD -2 reads -1 and then 0 or a parameter's number by itself;
//   during a download (80-SLOAD = -1 until its test ends) the CardWriteable parameters take
//   written values without the range check and a rejected dataset comes back (LUSTBUS manual 11.4);
//   4-PROG = 1 returns every parameter to its default; 85-SERR is the drive's own; actual values
//   never change;
// - the server's frame always has odd parity and the servo's direction.
//
// Input: a header (channel width, start mode, latency, password); then per cycle an action byte
// (time step, raw or link frame, what the master side sends or what happens to the servo) and
// its data.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/pcp_served.hpp"
#include "ibs/devices/mc6000/service.hpp"
#include "ibs/pcp/pdu.hpp"
#include "ibs/pcp/server.hpp"
#include "pcp_model.hpp"

namespace {

using namespace ibs;
using namespace ibs::pcp;
using ibs::fuzz::Bytes;
using ibs::fuzz::fail;
using ibs::fuzz::hex4;
using ibs::devices::mc6000::kProg;
using ibs::devices::mc6000::kSerr;
using ibs::devices::mc6000::kSload;

// A Write.req as docs/pcp.md lays it out: `0082 count IID,CR index subindex<<8|length data...`.
struct PlausibleWrite {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  Bytes data;
};
std::optional<PlausibleWrite> as_write(const Bytes& m) {
  if (m.size() < 10 || m[0] != 0x00 || m[1] != 0x82) return std::nullopt;
  const std::size_t length = m[9];
  if (10 + length > m.size()) return std::nullopt;
  return PlausibleWrite{static_cast<std::uint16_t>(m[6] << 8U | m[7]), m[8],
                        Bytes(m.begin() + 10, m.begin() + 10 + static_cast<std::ptrdiff_t>(length))};
}

std::optional<std::uint32_t> big_endian(const Bytes& b, std::size_t n) {
  if (b.size() != n) return std::nullopt;
  std::uint32_t v = 0;
  for (const std::uint8_t x : b) v = v << 8U | x;
  return v;
}

int width(std::uint8_t b) {
  static constexpr int kWidths[] = {1, 2, 4};
  return kWidths[(b & 3U) % 3U];  // bits 0-1; the other bits are flags
}

// A PDU of the given service from the input: the documented layouts, sometimes bent.
Bytes make_request(ibs::fuzz::Input& in, std::uint8_t kind, std::uint16_t password, std::uint8_t iid) {
  Pdu pdu;
  RequestPdu r;
  r.invoke_id = iid;
  r.cr = in.ConsumeIntegral<std::uint8_t>() < 240 ? 2 : in.ConsumeIntegral<std::uint8_t>();
  const auto table = ibs::devices::mc6000::parameters();
  const auto pick_index = [&]() -> std::uint16_t {
    const std::uint8_t b = in.ConsumeIntegral<std::uint8_t>();
    if (b < 224) return table[b % table.size()].index();
    return in.ConsumeIntegral<std::uint16_t>();
  };
  switch (kind % 5) {
    case 0:
      r.service = ServiceCode::initiate;
      r.password = in.ConsumeBool() ? password : in.ConsumeIntegral<std::uint16_t>();
      r.kbl = kDefaultClientKbl;
      break;
    case 1: {
      r.service = ServiceCode::write;
      r.index = pick_index();
      r.subindex = in.ConsumeIntegral<std::uint8_t>() < 240 ? 0 : in.ConsumeIntegral<std::uint8_t>();
      const ParameterInfo* p = find_by_index(table, r.index);
      const std::size_t n = (p != nullptr && in.ConsumeIntegral<std::uint8_t>() < 224) ? size_of(p->type)
                                                                                       : in.ConsumeIntegral<std::uint8_t>() % 6;
      const Bytes d = in.ConsumeBytes<std::uint8_t>(n);
      r.data.assign(d);
      break;
    }
    case 2:
      r.service = ServiceCode::read;
      r.index = pick_index();
      break;
    case 3:
      r.service = ServiceCode::get_ov;
      r.index = pick_index();
      break;
    default: {
      // Arbitrary bytes with a fitting count word.
      const std::size_t count = 1 + in.ConsumeIntegral<std::uint8_t>() % 20;
      Bytes b = in.ConsumeBytes<std::uint8_t>(4 + 2 * count);
      b.resize(4 + 2 * count, 0);
      b[2] = 0;
      b[3] = static_cast<std::uint8_t>(count);
      return b;
    }
  }
  if (!encode(r, pdu)) return {};
  return Bytes(pdu.bytes.begin(), pdu.bytes.begin() + static_cast<std::ptrdiff_t>(pdu.size));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ibs::fuzz::Input in(data, size);
  const std::uint8_t h = in.ConsumeIntegral<std::uint8_t>();
  ServerConfig cfg = ibs::devices::mc6000::server_config(1);
  cfg.channel_words = width(h);
  cfg.start = (h & 0x04U) != 0 ? StartMode::running : StartMode::power_on;
  if ((h & 0x08U) == 0) cfg.latency = LatencyModel::immediate();
  cfg.workload = static_cast<double>(in.ConsumeIntegral<std::uint8_t>()) / 255.0;
  cfg.password = (h & 0x10U) != 0 ? in.ConsumeIntegral<std::uint16_t>() : 0;
  cfg.link_ack_timeout = std::chrono::milliseconds(10 + in.ConsumeIntegral<std::uint8_t>());
  // The MC6000's parameters (the drive core's) behind the server.
  ibs::devices::mc6000::ParametersOnly drive(ibs::devices::mc6000::drive_parameters_config());
  if (cfg.start == StartMode::running) drive.read(Time{0}, kSerr);
  ibs::devices::mc6000::PcpServed served(drive);
  Server server(cfg, served);
  const auto words = static_cast<std::size_t>(cfg.channel_words);
  // The master's side of the channel, for the input's PDUs.
  Link master(LinkConfig{cfg.channel_words, Direction::to_server, cfg.link_ack_timeout, cfg.start == StartMode::running});
  fuzz::PlausibleMessages model(cfg.channel_words, true);
  std::vector<PlausibleWrite> writes;
  bool factory_defaults = false;  // a plausible, accepted 4-PROG = 1
  bool sload_end = false;         // a plausible 80-SLOAD = -2
  const auto table = drive.parameters().table();
  Time now{0};
  std::uint8_t iid = 0;
  // The store's values, taken once a step (a lookup by number is a search: kept to one pass).
  const auto snapshot = [&](std::vector<std::uint32_t>& v) {
    v.clear();
    for (const ParameterInfo& p : table) v.push_back(drive.parameters().value(p.number)->raw);
  };
  std::vector<std::uint32_t> before;
  std::vector<std::uint32_t> after;
  snapshot(before);
  std::size_t serr_slot = 0;
  while (serr_slot < table.size() && table[serr_slot].number != kSerr) ++serr_slot;
  ibs::fuzz::Recent<> recent;
  std::array<Word, 4> s2m{};
  server.show(now, std::span<Word>(s2m.data(), words));

  // IBS_FUZZ_TRACE=1: say which parameters changed and why that was allowed.
  const bool trace = std::getenv("IBS_FUZZ_TRACE") != nullptr;
  std::size_t cycles = 0;
  while (in.remaining_bytes() > 0 && ++cycles < 20000) {
    const std::uint8_t op = in.ConsumeIntegral<std::uint8_t>();
    switch (op & 3U) {
      case 0: now += 500us; break;
      case 1: now += 1ms; break;
      case 2: now += 10ms; break;
      default: now += std::chrono::milliseconds(in.ConsumeIntegral<std::uint8_t>()); break;
    }
    switch ((op >> 3U) & 7U) {
      case 1: case 2: case 3: {
        if (master.can_send()) {
          const Bytes pdu = make_request(in, in.ConsumeIntegral<std::uint8_t>(), cfg.password, iid++);
          if (!pdu.empty()) master.send(pdu);
        }
        break;
      }
      case 4:
        drive.parameters().power_on(now);
        server.power_on(now);
        snapshot(before);
        recent.note("power-on");
        break;
      case 5: {
        const std::uint8_t b = in.ConsumeIntegral<std::uint8_t>();
        drive.set_running((b & 1U) != 0);
        drive.set_fault((b & 2U) != 0);
        server.set_workload(static_cast<double>(b) / 255.0);
        break;
      }
      case 6:
        master.abort();
        break;
      default: break;
    }

    // The frame the servo sees this cycle.
    std::array<Word, 4> m2s{};
    master.transmit(now, std::span<Word>(m2s.data(), words));
    if ((op & 0x04U) != 0) {
      for (std::size_t i = 0; i < words; ++i) m2s[i] = in.ConsumeIntegral<std::uint16_t>();
    }
    for (Bytes& m : model.feed(std::span<const Word>(m2s.data(), words))) {
      if (auto w = as_write(m)) writes.push_back(std::move(*w));
    }

    const std::uint32_t serr_before = serr_slot < before.size() ? before[serr_slot] : 0;
    const bool associated_before = server.associated();
    const bool eeprom_busy_before = drive.parameters().eeprom_busy(now);
    const bool downloading_before = drive.parameters().downloading();

    server.step(now, std::span<const Word>(m2s.data(), words), std::span<Word>(s2m.data(), words));
    snapshot(after);

    recent.words(m2s[0], s2m[0]);
    const auto where = [&] {
      return "now " + std::to_string(now.count()) + " ns, 85-SERR before " + std::to_string(serr_before) +
             ", associated " + std::to_string(associated_before) + "; cycles (first words m2s>s2m):" + recent.str();
    };

    const auto admin = decode_admin(static_cast<std::uint8_t>(s2m[0] >> 8U));
    if (!admin || admin->dir != Direction::to_client) fail("the server's frame " + hex4(s2m[0]) + " is not a servo frame: " + where());

    // Which plausible writes would have passed the checks now.
    const auto passes = [&](const ParameterInfo& p, std::uint32_t raw) {
      return p.writable() && compare(p.type, raw, ParameterStore::to_raw(p, p.min)) >= 0 &&
             compare(p.type, raw, ParameterStore::to_raw(p, p.max)) <= 0 && serr_before == 0 && associated_before &&
             !(p.category == Category::eeprom && eeprom_busy_before);
    };
    const auto written_with = [&](const ParameterInfo& p, std::uint32_t raw) {
      for (const PlausibleWrite& w : writes) {
        if (w.index != p.index() || w.subindex != 0) continue;
        const auto v = big_endian(w.data, size_of(p.type));
        if (v && *v == raw) return true;
      }
      return false;
    };
    const ParameterInfo* prog = find_parameter(table, kProg);
    if (!factory_defaults && prog != nullptr && written_with(*prog, 1) && passes(*prog, 1)) factory_defaults = true;
    const ParameterInfo* sload = find_parameter(table, kSload);
    const std::uint32_t minus1 = value_from_signed_raw(DataType::integer16, -1)->raw;
    const std::uint32_t minus2 = value_from_signed_raw(DataType::integer16, -2)->raw;
    if (sload != nullptr && written_with(*sload, minus2)) sload_end = true;

    for (std::size_t i = 0; i < table.size(); ++i) {
      const ParameterInfo& p = table[i];
      const std::uint32_t now_raw = after[i];
      if (p.number == kSerr || now_raw == before[i]) continue;
      bool ok = false;
      if (p.number == kSload) {
        ok = (now_raw == minus1 && (written_with(p, minus1) || written_with(p, minus2)) && passes(p, now_raw)) ||
             (now_raw == 0 && sload_end);
      } else {
        ok = written_with(p, now_raw) && passes(p, now_raw);
      }
      if (!ok && factory_defaults && now_raw == ParameterStore::default_raw(p)) ok = true;
      // 11.4: the dataset without the range check, and the old one back when it is rejected.
      const bool download_ended = downloading_before && !drive.parameters().downloading();
      if (!ok && downloading_before && ibs::devices::mc6000::card_writeable(p.number) &&
          (download_ended || (written_with(p, now_raw) && serr_before == 0 && associated_before))) {
        ok = true;
      }
      if (!ok && p.number == kSload && download_ended) ok = true;  // 0 or the rejected number
      if (trace) std::fprintf(stderr, "parameter %u: %u -> %u (%s)\n", p.number, before[i], now_raw, ok ? "allowed" : "NOT allowed");
      if (!ok) {
        fail("parameter " + std::to_string(p.number) + " changed from " + std::to_string(before[i]) + " to " +
             std::to_string(now_raw) + " without a complete, checked Write (" + std::to_string(writes.size()) +
             " plausible writes seen): " + where());
      }
    }

    std::swap(before, after);

    // The master side reads the servo's frame and takes whatever arrives.
    master.receive(now, std::span<const Word>(s2m.data(), words));
    if (master.has_message()) master.release_message();
  }
  return 0;
}
