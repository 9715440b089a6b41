// The master's PCP client (pcp::Client, docs/pcp.md "Client") fed channel words cycle by cycle
// with time passed in: each cycle either arbitrary words or the frame of a real servo
// (pcp::Server) that the client talks to, so that associations and confirmations happen and
// arbitrary words hit them at any point; requests of every service submitted at any time with
// their own timeouts, user aborts, servo restarts.
//
// Asserts that every request ends with a documented result within its timeout:
// - a submission is refused only as documented: `busy` exactly while a request is outstanding,
//   `not_initiated` exactly for a service that needs an association when there is none;
// - every accepted request gets exactly one result, for its service, its InvokeID and its
//   submission time; none comes without a request;
// - after any step, a request submitted at T with timeout D is finished once now >= T + D; a
//   `timeout` result comes only then; at the end, with the servo silent, every request ends;
// - the result kind is one of the documented ones and fits the service: `incompatible` only for
//   Initiate, `type_mismatch` only for a typed Read, a typed Read that is `ok` has a value of its
//   type; `aborted` at once on the user's abort();
// - the client's frame always has odd parity and the master's direction.
//
// Input: a header (channel width, timeouts, how the servo starts); then per cycle an action byte
// (time step, raw words or the servo's frame, a submission or an event) and its data.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "fuzz_support.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/pcp/client.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/pcp_served.hpp"
#include "ibs/pcp/server.hpp"

namespace {

using namespace ibs;
using namespace ibs::pcp;
using ibs::fuzz::fail;
using ibs::fuzz::hex4;

int width(std::uint8_t b) {
  static constexpr int kWidths[] = {1, 2, 4};
  return kWidths[(b & 3U) % 3U];  // bits 0-1; the other bits are flags
}

struct Outstanding {
  ServiceCode service = ServiceCode::read;
  Time submitted{0};
  Duration timeout{0};
  bool typed_read = false;
  DataType type = DataType::usign16;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ibs::fuzz::Input in(data, size);
  const std::uint8_t h = in.ConsumeIntegral<std::uint8_t>();
  ClientConfig cfg;
  cfg.channel_words = width(h);
  cfg.request_timeout = std::chrono::milliseconds(1 + in.ConsumeIntegral<std::uint8_t>());
  cfg.link_ack_timeout = std::chrono::milliseconds(1 + in.ConsumeIntegral<std::uint8_t>());
  Client client(cfg);
  ServerConfig scfg = ibs::devices::mc6000::server_config(1);
  scfg.channel_words = cfg.channel_words;
  scfg.start = (h & 0x04U) != 0 ? StartMode::running : StartMode::power_on;
  if ((h & 0x08U) == 0) scfg.latency = LatencyModel::immediate();
  // The MC6000's parameters (the drive core's) behind the server.
  ibs::devices::mc6000::ParametersOnly drive(ibs::devices::mc6000::drive_parameters_config());
  if (scfg.start == StartMode::running) drive.read(Time{0}, ibs::devices::mc6000::kSerr);
  ibs::devices::mc6000::PcpServed served(drive);
  Server servo(scfg, served);
  const auto words = static_cast<std::size_t>(cfg.channel_words);
  const auto table = ibs::devices::mc6000::parameters();

  std::optional<Outstanding> open;
  std::uint8_t next_iid = 0;
  Time now{0};
  std::array<Word, 4> m2s{};
  std::array<Word, 4> s2m{};
  client.show(now, std::span<Word>(m2s.data(), words));
  servo.show(now, std::span<Word>(s2m.data(), words));
  ibs::fuzz::Recent<> recent;

  std::uint32_t takes = 0;
  std::optional<Result> held;
  const auto take = [&](const auto& where) {
    // Every other time without a copy (take_result_view): the same checks, and taken once.
    const Result* r = nullptr;
    if (++takes % 2 == 0) {
      r = client.take_result_view();
    } else if ((held = client.take_result())) {
      r = &*held;
    }
    if (r != nullptr) {
      if (client.take_result_view() != nullptr) fail("a result taken twice: " + where());
      if (!open) fail("a result (" + std::string(to_string(r->kind)) + ") without a request: " + where());
      const auto what = [&] {
        return "a " + std::string(to_string(open->service)) + " request ended " +
               std::string(to_string(r->kind)) + ": ";
      };
      if (r->service != open->service) fail(what() + "the result is for " + std::string(to_string(r->service)) + ": " + where());
      if (r->submitted_at != open->submitted) fail(what() + "the result names another submission time: " + where());
      if (r->completed_at != now) fail(what() + "completed_at is not now: " + where());
      if (r->invoke_id != static_cast<std::uint8_t>(next_iid - 1U)) fail(what() + "the wrong InvokeID: " + where());
      switch (r->kind) {
        case ResultKind::ok:
          if (open->typed_read && (!r->value || r->value->type != open->type)) fail(what() + "no value of the type asked for: " + where());
          break;
        case ResultKind::negative:
        case ResultKind::aborted:
        case ResultKind::link_reset:
        case ResultKind::protocol_error:
          break;
        case ResultKind::incompatible:
          if (open->service != ServiceCode::initiate) fail(what() + "incompatible is for Initiate: " + where());
          break;
        case ResultKind::type_mismatch:
          if (!open->typed_read) fail(what() + "type_mismatch is for a typed Read: " + where());
          break;
        case ResultKind::timeout:
          if (now < open->submitted + open->timeout) fail(what() + "before its timeout ran out: " + where());
          break;
        default:
          fail(what() + "an undocumented result kind " + std::to_string(static_cast<int>(r->kind)) + ": " + where());
      }
      open.reset();
    }
    if (open && !client.busy()) fail("the request is over but gave no result: " + where());
    if (!open && client.busy()) fail("busy without a request: " + where());
    if (open && now >= open->submitted + open->timeout) {
      fail("a " + std::string(to_string(open->service)) + " request is still outstanding " +
           std::to_string((now - open->submitted).count()) + " ns after its submission; its timeout is " +
           std::to_string(open->timeout.count()) + " ns: " + where());
    }
  };

  std::size_t cycles = 0;
  while (in.remaining_bytes() > 0 && ++cycles < 20000) {
    const std::uint8_t op = in.ConsumeIntegral<std::uint8_t>();
    switch (op & 3U) {
      case 0: now += 500us; break;
      case 1: now += 1ms; break;
      case 2: now += 10ms; break;
      default: now += std::chrono::milliseconds(in.ConsumeIntegral<std::uint8_t>()); break;
    }
    const std::uint8_t act = (op >> 3U) & 7U;
    if (act >= 1 && act <= 4) {
      const std::uint8_t kind = in.ConsumeIntegral<std::uint8_t>();
      const std::uint8_t pb = in.ConsumeIntegral<std::uint8_t>();
      const ParameterRef p = pb < 224 ? ParameterRef::number(table[pb % table.size()].number)
                                      : ParameterRef::object(in.ConsumeIntegral<std::uint16_t>());
      const std::uint8_t tb = in.ConsumeIntegral<std::uint8_t>();
      const Duration t = tb < 128 ? Duration::zero() : std::chrono::milliseconds(tb - 127);
      const bool was_busy = client.busy();
      const bool was_associated = client.associated();
      Outstanding o{ServiceCode::read, now, t > Duration::zero() ? t : cfg.request_timeout};
      SubmitStatus s = SubmitStatus::accepted;
      switch (kind % 7) {
        case 0: o.service = ServiceCode::initiate; s = client.initiate(now, t); break;
        case 1: o.service = ServiceCode::read; s = client.read(now, p, t); break;
        case 2:
          o.service = ServiceCode::read;
          o.typed_read = true;
          o.type = static_cast<DataType>(1 + in.ConsumeIntegral<std::uint8_t>() % 8);
          s = client.read(now, p, o.type, t);
          break;
        case 3: {
          o.service = ServiceCode::write;
          const auto type = static_cast<DataType>(1 + in.ConsumeIntegral<std::uint8_t>() % 8);
          s = client.write(now, p, Value{type, in.ConsumeIntegral<std::uint32_t>()}, t);
          break;
        }
        case 4: o.service = ServiceCode::get_ov; s = client.get_ov(now, p, t); break;
        case 5: o.service = ServiceCode::identify; s = client.identify(now, t); break;
        default: o.service = ServiceCode::status; s = client.status(now, t); break;
      }
      const bool needs_association = o.service != ServiceCode::initiate;
      const auto what = [&] { return "submitting " + std::string(to_string(o.service)) + " gave " + std::string(to_string(s)); };
      if (was_busy != (s == SubmitStatus::busy)) fail(what() + " while busy " + std::to_string(was_busy));
      if (!was_busy && (needs_association && !was_associated) != (s == SubmitStatus::not_initiated)) {
        fail(what() + " while associated " + std::to_string(was_associated));
      }
      if (s == SubmitStatus::accepted) {
        open = o;
        ++next_iid;
        recent.note("submit");
      }
    } else if (act == 5) {
      const bool had = client.busy();
      client.abort(now);
      recent.note("abort");
      if (had) {
        const auto r = client.take_result();
        if (!r || r->kind != ResultKind::aborted) fail("abort() with a request outstanding did not end it as aborted");
        open.reset();
      }
    } else if (act == 6) {
      drive.parameters().power_on(now);
      servo.power_on(now);
      recent.note("servo-power-on");
    }

    // The servo answers the client's last frame; the client sees its answer or arbitrary words.
    servo.step(now, std::span<const Word>(m2s.data(), words), std::span<Word>(s2m.data(), words));
    std::array<Word, 4> seen = s2m;
    if ((op & 0x04U) != 0) {
      for (std::size_t i = 0; i < words; ++i) seen[i] = in.ConsumeIntegral<std::uint16_t>();
    }
    client.step(now, std::span<const Word>(seen.data(), words), std::span<Word>(m2s.data(), words));
    recent.words(seen[0], m2s[0]);
    const auto where = [&] { return "now " + std::to_string(now.count()) + " ns; cycles (first words s2m>m2s):" + recent.str(); };
    const auto admin = decode_admin(static_cast<std::uint8_t>(m2s[0] >> 8U));
    if (!admin || admin->dir != Direction::to_server) fail("the client's frame " + hex4(m2s[0]) + " is not a master frame: " + where());
    take(where);
  }
  // The servo goes silent: the outstanding request must end within its timeout.
  for (int i = 0; i < 300 && open; ++i) {
    now += 1ms;
    const std::array<Word, 4> silent{};
    client.step(now, std::span<const Word>(silent.data(), words), std::span<Word>(m2s.data(), words));
    take([&] { return "the servo silent, now " + std::to_string(now.count()) + " ns"; });
  }
  if (open) fail("a request never ended");
  return 0;
}
