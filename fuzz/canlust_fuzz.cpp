// CANLust (docs/canlust.md): arbitrary frames to every telegram decoder, to the cannelloni
// decoder, and to both sides of the parameter channel - the drive's ParameterServer fed arbitrary
// request telegrams, and the master's ParameterClient answered by a "noisy drive" that replies to
// its requests with arbitrary (often wrong) replies, with time steps in between.
//
// Asserts:
// - decoders: a decoded telegram re-encodes to the same bytes (the nominal length's prefix of the
//   frame; longer DLCs are tolerated on receive, decision D4); classify() and id() are inverse;
//   a datagram the cannelloni decoder accepts re-encodes to a datagram that decodes to the same
//   frames;
// - server: every request gets exactly one reply, with the request's parameter number and block
//   counter, once the drive's delay has passed; a string write is only ever accepted (status 0
//   to List_End, write_string() called) when its checksum is the XOR of the blocks echoed;
// - client: every accepted request ends with exactly one documented outcome, and within its
//   timeout (active since T with timeout D -> done once now >= T + D); a string read never ends
//   `done` unless List_End's checksum is the XOR of the data blocks the client took;
// - the CDA3000 drive (devices/cda3000, the drive side through the wing), fed arbitrary frames,
//   well-formed requests, control and system telegrams, time steps and mains resets: every status
//   word it sends or shows is one of the eight DRIVECOM states; every request gets one reply;
//   its parameters change only through a complete, checked transfer - a write answered 0 whose
//   value passes the table (04-PROG: to the factory settings; 151-ASTPR: its data set), a string
//   write closed with List_End answered 0 whose checksum is the XOR of the blocks echoed and whose
//   text is theirs, a mains reset (the flash copy; RAM values to their factory values) - and the
//   flash copy only through 150-SAVE, which stores every flash setting (the table's memory type:
//   a RAM value such as 80-SLOAD has no flash copy); every setting always passes the table; a data set download (80-SLOAD, D39) changes settings
//   and flash only at its accepted end, only Card Writeable ones, both alike, and never while open;
// - the data set text (`ibs canlust download`'s parser with the CDA3000's table): an accepted
//   text gives distinct Card Writeable parameters with values the table takes, each from a line
//   of the text, and written back as `NUMBER VALUE` lines it parses to the same records; a
//   refused one names a line of the text (or 0: no record) and gives no record.
//
// Input: byte 0 selects the part (FFH: the data set text; else by its value mod 5, 0: decoders,
// 1: cannelloni, 2: server, 3: client, 4: the CDA3000 drive); the rest is that part's input,
// read front to back.
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/can/cannelloni.hpp"
#include "ibs/canlust/data_set.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/canlust/parameter_client.hpp"
#include "ibs/canlust/telegrams.hpp"
#include "ibs/devices/cda3000/device.hpp"
#include "ibs/drivecom/status_word.hpp"

namespace {

using namespace ibs;
using namespace ibs::canlust;
using ibs::fuzz::Input;

CanFrame read_frame(Input& in) {
  CanFrame f;
  f.id = static_cast<std::uint16_t>(in.ConsumeIntegral<std::uint16_t>() & 0x7FFU);
  const auto flags = in.ConsumeIntegral<std::uint8_t>();
  f.dlc = static_cast<std::uint8_t>(flags % 9U);
  f.rtr = (flags & 0x80U) != 0 && (flags & 0x40U) != 0;
  for (auto& b : f.data) b = in.ConsumeIntegral<std::uint8_t>();
  for (std::size_t i = f.dlc; i < f.data.size(); ++i) f.data[i] = 0;
  return f;
}

bool same_prefix(const CanFrame& a, const CanFrame& b, std::size_t n) {
  return std::memcmp(a.data.data(), b.data.data(), n) == 0;
}

void decoders(Input& in) {
  IdentifierMap ids;
  ids.step = static_cast<std::uint8_t>(1 + in.ConsumeIntegral<std::uint8_t>() % 2);
  while (in.remaining_bytes() > 0) {
    const CanFrame f = read_frame(in);
    const auto c = ids.classify(f.id);
    if (c) IBS_FUZZ_REQUIRE(ids.id(c->kind, c->address) == f.id, "classify/id not inverse");
    const Address a = c ? c->address : 0;
    if (const auto s = decode_system(f)) {
      IBS_FUZZ_REQUIRE(same_prefix(encode_system(s.value), f, 1), "system re-encode");
    }
    for (std::uint8_t cacnf = 1; cacnf <= 4; ++cacnf) {
      const auto l = *process_layout_for_cacnf(cacnf);
      if (const auto d = decode_control(f, l)) {
        const auto e = encode_control(ids, a, l, d.value);
        IBS_FUZZ_REQUIRE(e && same_prefix(*e, f, nominal_length(l.reference)), "control re-encode");
      }
      if (const auto d = decode_status(f, l)) {
        const auto e = encode_status(ids, a, l, d.value);
        IBS_FUZZ_REQUIRE(e && same_prefix(*e, f, nominal_length(l.actual)), "status re-encode");
      }
    }
    if (const auto d = decode_error(f)) {
      const auto e = encode_error(ids, a, d.value);
      IBS_FUZZ_REQUIRE(e && same_prefix(*e, f, 3), "error re-encode");
    }
    if (const auto d = decode_parameter(f)) {
      const auto e = encode_parameter_request(ids, a, d.value);
      IBS_FUZZ_REQUIRE(e && same_prefix(*e, f, 8), "parameter re-encode");
      if (f.dlc == 8 && c && c->kind == TelegramKind::parameter_request) {
        IBS_FUZZ_REQUIRE(*e == f, "parameter frame re-encodes identically");
      }
    }
  }
}

void cannelloni_part(Input& in) {
  const auto bytes = in.ConsumeBytes<std::uint8_t>(in.remaining_bytes());
  std::array<CanFrame, 64> out{};
  const auto r = can::cannelloni::decode(bytes, out);
  if (r.status != can::cannelloni::DecodeStatus::ok) return;
  std::vector<std::uint8_t> again(can::cannelloni::encoded_size(std::span(out.data(), r.frames)));
  const auto n = can::cannelloni::encode(std::span(out.data(), r.frames), r.sequence, again);
  IBS_FUZZ_REQUIRE(n.has_value(), "decoded frames must encode");
  // An accepted datagram is its header and its frames, nothing more (issue 23, defect 3).
  IBS_FUZZ_REQUIRE(r.skipped != 0 || *n == bytes.size(), "an accepted datagram has bytes its frames do not explain");
  std::array<CanFrame, 64> back{};
  const auto r2 = can::cannelloni::decode(std::span(again.data(), *n), back);
  IBS_FUZZ_REQUIRE(r2.status == can::cannelloni::DecodeStatus::ok && r2.frames == r.frames &&
                       r2.skipped == 0 && r2.sequence == r.sequence, "cannelloni round trip");
  for (std::size_t i = 0; i < r.frames; ++i) IBS_FUZZ_REQUIRE(back[i] == out[i], "frame differs");
}

// A drive whose answers come from the input; it records the string writes it accepted.
class FuzzDrive final : public ParameterAccess {
 public:
  explicit FuzzDrive(Input& in) : in_(&in) {}
  ValueResult read(std::uint16_t, std::uint8_t, Time) override {
    return {status(), DataType::usign32, in_->ConsumeIntegral<std::uint32_t>(), delay()};
  }
  AccessResult write(std::uint16_t, std::uint8_t, std::uint32_t, Time) override { return {status(), delay()}; }
  ValueResult describe(std::uint16_t, std::uint8_t, Time) override {
    return {status(), DataType::usign32, in_->ConsumeIntegral<std::uint32_t>(), delay()};
  }
  StringResult read_string(std::uint16_t, std::span<char> out, Time) override {
    const auto n = static_cast<std::uint8_t>(in_->ConsumeIntegral<std::uint8_t>() % (out.size() + 1));
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<char>(1 + in_->ConsumeIntegral<std::uint8_t>() % 255);
    return {status(), n, delay()};
  }
  AccessResult begin_string_write(std::uint16_t, Time) override { return {status(), delay()}; }
  AccessResult write_string(std::uint16_t, std::string_view text, Time) override {
    IBS_FUZZ_REQUIRE(text.size() <= kMaxStringChars, "string longer than 99 characters");
    return {kStatusOk, {}};
  }

 private:
  std::uint8_t status() { return in_->ConsumeIntegral<std::uint8_t>() % 4 == 0 ? kStatusUnknownParameter : kStatusOk; }
  Duration delay() { return std::chrono::milliseconds(in_->ConsumeIntegral<std::uint8_t>() % 4 == 0 ? 50 : 0); }
  Input* in_;
};

void server_part(Input& in) {
  FuzzDrive drive(in);
  ParameterServer server(drive);
  Time now{0};
  std::uint32_t requests = 0, replies = 0;
  // The string write as the server echoed it: open after an accepted block 0.
  bool open = false;
  std::uint16_t open_param = 0;
  std::uint32_t xor_echoed = 0;
  std::vector<ParameterTelegram> sent;  // requests in order, matched with replies in order
  auto check_reply = [&](const ParameterTelegram& rep) {
    ++replies;
    IBS_FUZZ_REQUIRE(!sent.empty(), "a reply without a request");
    ParameterTelegram req;
    req = sent.front();
    sent.erase(sent.begin());
    IBS_FUZZ_REQUIRE(rep.parameter == req.parameter && rep.block == req.block, "reply does not echo");
    if (req.code == kModeStringWrite) {
      if (req.block == 0) {
        open = rep.code == kStatusOk;
        open_param = req.parameter;
        xor_echoed = 0;
      } else if (open && rep.code == kStatusOk) {
        IBS_FUZZ_REQUIRE(rep.data == req.data, "block not echoed");
        xor_echoed ^= req.data;
      } else {
        open = false;
      }
    } else if (req.code == kModeListEnd) {
      if (rep.code == kStatusOk) {
        IBS_FUZZ_REQUIRE(open && open_param == req.parameter && req.data == xor_echoed,
                         "string accepted with a wrong checksum or without a transfer");
      }
      open = false;
    } else {
      open = false;
    }
  };
  while (in.remaining_bytes() > 0) {
    const auto action = in.ConsumeIntegral<std::uint8_t>();
    if (action < 0x40) {
      now += std::chrono::milliseconds(action);
    } else {
      ParameterTelegram t;
      static constexpr std::uint8_t kModes[] = {kModeRead, kModeWrite, kModeDescribe, kModeStringRead,
                                                kModeStringWrite, kModeListEnd, 0x33};
      t.code = kModes[action % 7];
      t.parameter = in.ConsumeIntegral<std::uint8_t>() % 3;
      t.block = in.ConsumeIntegral<std::uint8_t>() % 8;
      t.data = in.ConsumeBool() ? in.ConsumeIntegral<std::uint32_t>() : xor_echoed;
      const bool pending = server.next_deadline() != Time::max();
      ++requests;
      server.receive(t, now);
      if (pending) {
        // One request at a time: a second one gets "repeat" at once (D12), before the first's reply.
        const auto r = server.take_reply(now);
        IBS_FUZZ_REQUIRE(r && r->code == kStatusRepeat && r->parameter == t.parameter &&
                             r->block == t.block, "busy request not answered with repeat");
        ++replies;
      } else {
        sent.push_back(t);
      }
    }
    while (auto r = server.take_reply(now)) check_reply(*r);
  }
  now += 1s;
  while (auto r = server.take_reply(now)) check_reply(*r);
  IBS_FUZZ_REQUIRE(requests == replies, "every request gets exactly one reply");
}

struct Tracked {
  RequestId id = 0;
  Request request;
  Duration timeout{};
  bool active = false;
  bool done = false;
  Time since{};
};

void client_part(Input& in) {
  ClientConfig cfg;
  cfg.timeout = std::chrono::milliseconds(1 + in.ConsumeIntegral<std::uint8_t>());
  cfg.string_timeout = std::chrono::milliseconds(1 + in.ConsumeIntegral<std::uint8_t>() * 4);
  cfg.queue_capacity = 1 + in.ConsumeIntegral<std::uint8_t>() % 8;
  cfg.completed_capacity = 64;
  ParameterClient client(cfg);
  const IdentifierMap ids;
  std::vector<Tracked> tracked;
  Time now{0};
  // The noisy drive's view of the string read of each address (0..3).
  struct Noisy {
    bool waiting = false;
    ParameterTelegram request{};
    bool answered = false;  // a matching reply went out for this request
    std::uint32_t xor_taken = 0;
  };
  std::array<Noisy, 4> drives{};
  std::array<std::uint32_t, 4> last_list_end{};

  auto step = [&] {
    client.step(now);
    for (auto& t : tracked) {
      const auto p = client.poll(t.id);
      if (t.done) continue;
      if (p.state == RequestState::active && !t.active) {
        t.active = true;
        t.since = now;
      }
      if (p.state == RequestState::done) {
        t.done = true;
        const Outcome& o = *p.outcome;
        IBS_FUZZ_REQUIRE(o.kind <= OutcomeKind::aborted, "undocumented outcome");
        if (o.kind == OutcomeKind::timeout) {
          IBS_FUZZ_REQUIRE(o.finished >= o.started + t.timeout, "timeout reported early");
        } else {
          IBS_FUZZ_REQUIRE(o.finished < o.started + t.timeout, "reply taken after the timeout");
        }
        if (t.request.kind == RequestKind::read_string && o.kind == OutcomeKind::done) {
          IBS_FUZZ_REQUIRE(o.value == drives[t.request.address].xor_taken &&
                               o.value == last_list_end[t.request.address],
                           "string read done with a wrong checksum");
        }
        continue;
      }
      if (t.active) IBS_FUZZ_REQUIRE(now < t.since + t.timeout, "request active past its timeout");
    }
    while (auto f = client.take_frame()) {
      const auto c = ids.classify(f->id);
      IBS_FUZZ_REQUIRE(c && c->kind == TelegramKind::parameter_request, "client sent a non-request");
      const auto d = decode_parameter(*f);
      IBS_FUZZ_REQUIRE(static_cast<bool>(d), "client's request does not decode");
      Noisy& n = drives[c->address % 4];
      if (d.value.code == kModeStringRead && d.value.block == 0) n.xor_taken = 0;
      n.waiting = true;
      n.request = d.value;
      n.answered = false;
    }
  };

  while (in.remaining_bytes() > 0) {
    const auto action = in.ConsumeIntegral<std::uint8_t>();
    if (action < 0x60) {
      now += std::chrono::milliseconds(action % 32);
    } else if (action < 0x80) {
      const auto a = static_cast<Address>(in.ConsumeIntegral<std::uint8_t>() % 4);
      Request r;
      switch (in.ConsumeIntegral<std::uint8_t>() % 5) {
        case 0: r = read(a, 1); break;
        case 1: r = write(a, 1, in.ConsumeIntegral<std::uint32_t>()); break;
        case 2: r = describe(a, 1, 0); break;
        case 3: r = read_string(a, 2); break;
        default: r = write_string(a, 2, std::string(in.ConsumeIntegral<std::uint8_t>() % 110, 'x')); break;
      }
      if (in.ConsumeBool()) r.timeout = std::chrono::milliseconds(in.ConsumeIntegral<std::uint8_t>());
      const auto s = client.submit(r);
      if (s) {
        const bool str = r.kind == RequestKind::read_string || r.kind == RequestKind::write_string;
        tracked.push_back({s.id, r, r.timeout.value_or(str ? cfg.string_timeout : cfg.timeout)});
      }
    } else if (action < 0xF0) {
      // The noisy drive answers its address's outstanding request, correctly or not.
      Noisy& n = drives[action % 4];
      const Address a = action % 4;
      ParameterTelegram rep = n.request;
      const auto how = in.ConsumeIntegral<std::uint8_t>();
      rep.code = (how & 3U) == 0 ? in.ConsumeIntegral<std::uint8_t>() : ((how & 3U) == 1 ? kStatusListEnd : kStatusOk);
      rep.data = (how & 4U) != 0 ? n.xor_taken : in.ConsumeIntegral<std::uint32_t>();
      if ((how & 8U) != 0) rep.block = in.ConsumeIntegral<std::uint8_t>();
      if ((how & 16U) != 0) rep.parameter = in.ConsumeIntegral<std::uint16_t>();
      const bool matching = n.waiting && !n.answered && rep.parameter == n.request.parameter &&
                            rep.block == n.request.block;
      if (matching) {
        n.answered = true;
        if (n.request.code == kModeStringRead && rep.code == kStatusOk) n.xor_taken ^= rep.data;
        if (n.request.code == kModeStringRead && rep.code == kStatusListEnd) last_list_end[a] = rep.data;
      }
      client.receive(*encode_parameter_reply(ids, a, rep), now);
    } else {
      // Any frame at all.
      client.receive(read_frame(in), now);
    }
    step();
  }
  // The drive falls silent: queued requests start as the ones before them time out.
  for (std::size_t i = 0; i <= cfg.queue_capacity + 1; ++i) {
    now += 10s;
    step();
  }
  for (const auto& t : tracked) IBS_FUZZ_REQUIRE(t.done, "request never ended");
}

namespace cda = ibs::devices::cda3000;

// `saved` is the flash: the parameters the table keeps there (Memory::flash). A RAM value has no
// flash copy (saved_value() is nullopt) and may differ from what a SAVE stored: 80-SLOAD keeps
// naming a rejected data set's parameter (D39) after a 150-SAVE (issue 41: the oracle once
// compared every parameter, and this legitimate path "changed the flash without 150-SAVE").
struct Snapshot {
  std::array<std::uint32_t, cda::kParameters.size()> current{};
  std::array<std::uint32_t, cda::kParameters.size()> saved{};
  std::string text;
  std::string saved_text;
};

bool in_flash(const cda::ParameterInfo& p) { return p.memory == cda::Memory::flash && !p.is_string(); }

Snapshot snapshot(const cda::Cda3000& d) {
  Snapshot s;
  for (std::size_t i = 0; i < cda::kParameters.size(); ++i) {
    const auto& p = cda::kParameters[i];
    if (p.number == cda::kReff) continue;  // the reference the drive follows, not a setting
    s.current[i] = d.value(p.number).value_or(0);
    const auto saved = d.saved_value(p.number);
    IBS_FUZZ_REQUIRE(saved.has_value() == in_flash(p), "a flash copy of a RAM value, or none of a flash one");
    s.saved[i] = saved.value_or(0);
  }
  s.text = std::string(d.text(cda::kName));
  s.saved_text = std::string(d.saved_text(cda::kName));
  return s;
}

// The flash holds the settings: every flash parameter's copy is its setting.
bool flash_is_settings(const Snapshot& s) {
  for (std::size_t i = 0; i < cda::kParameters.size(); ++i) {
    if (in_flash(cda::kParameters[i]) && s.saved[i] != s.current[i]) return false;
  }
  return s.saved_text == s.text;
}

// Numbers whose settings may change with a write of `number`.
bool may_change(std::uint16_t written, std::uint32_t value, std::uint16_t changed) {
  if (written == cda::kProg && value == 1) return true;
  if (written == cda::kAstpr) {
    return changed == cda::kAstpr || changed == cda::kAster || changed == cda::kFisa0 ||
           changed == cda::kClsel || changed == cda::kRssl1;
  }
  return changed == written;
}

void check_settings(const cda::Cda3000& d) {
  for (const auto& p : cda::kParameters) {
    if (p.is_string() || p.number == cda::kReff) continue;
    IBS_FUZZ_REQUIRE(cda::check_value(p, *d.value(p.number)) == cda::ValueCheck::ok, "a setting outside the table");
    if (in_flash(p)) {
      IBS_FUZZ_REQUIRE(cda::check_value(p, *d.saved_value(p.number)) == cda::ValueCheck::ok,
                       "a saved setting outside the table");
    }
  }
  IBS_FUZZ_REQUIRE(drivecom::decode_state(d.status_word()).has_value(), "status word matches no DRIVECOM state");
}

void drive_part(Input& in) {
  cda::DeviceConfig c;
  c.saved = cda::commissioned_for_bus(1, static_cast<std::uint8_t>(1 + in.ConsumeIntegral<std::uint8_t>() % 3));
  c.saved.emplace_back(cda::kCawdg, in.ConsumeIntegral<std::uint8_t>() % 64);
  c.saved.emplace_back(cda::kCascy, 1 + in.ConsumeIntegral<std::uint8_t>() % 64);
  c.saved.emplace_back(cda::kRop2, in.ConsumeIntegral<std::uint8_t>() % 4);  // the watchdog's reaction
  c.save_time = 0ms;  // every reply at once: each request is matched with its reply below
  c.prog_time = 0ms;
  c.download_check_time = 0ms;
  cda::Cda3000 d(c);
  const IdentifierMap ids;
  Time now{0};
  d.power_on(now);
  // The string write as the drive echoed it.
  bool open = false;
  std::uint16_t open_param = 0;
  std::uint32_t xor_echoed = 0;
  std::string blocks;
  static constexpr std::uint16_t kNumbers[] = {cda::kProg, cda::kName, cda::kSave, cda::kAstpr, cda::kAster,
                                               cda::kClsel, cda::kRssl1, cda::kDisp, cda::kReff, cda::kCacnf,
                                               cda::kCamod, cda::kCladr, cda::kCawdg, cda::kCascy, cda::kOptn2,
                                               cda::kSload, cda::kSload, cda::kRop2, cda::kCawmk, 999};
  static constexpr std::uint8_t kModes[] = {kModeRead, kModeWrite, kModeDescribe, kModeStringRead,
                                            kModeStringWrite, kModeListEnd, 0x33};
  // Frames out: status words are DRIVECOM states; returns the replies.
  const auto drain = [&](std::vector<ParameterTelegram>& replies) {
    while (auto f = d.take_frame()) {
      const auto k = ids.classify(f->id);
      IBS_FUZZ_REQUIRE(k.has_value(), "the drive sent a foreign identifier");
      if (k->kind == TelegramKind::status) {
        const auto st = decode_status(*f, d.layout());
        IBS_FUZZ_REQUIRE(st && drivecom::decode_state(st.value.word).has_value(),
                         "status telegram matches no DRIVECOM state");
      } else if (k->kind == TelegramKind::parameter_reply) {
        replies.push_back(decode_parameter(*f).value);
      }
    }
  };
  while (in.remaining_bytes() > 0) {
    const auto action = in.ConsumeIntegral<std::uint8_t>();
    const Snapshot before = snapshot(d);
    const bool was_downloading = d.downloading();
    std::vector<ParameterTelegram> replies;
    std::optional<ParameterTelegram> request;
    if (action < 0x40) {
      now += std::chrono::milliseconds(action);
      d.step(now);
    } else if (action < 0x48) {
      d.power_on(now);  // a mains reset: the flash copy becomes the settings
      const Snapshot after = snapshot(d);
      IBS_FUZZ_REQUIRE(after.saved == before.saved && after.saved_text == before.saved_text, "mains reset changed the flash");
      IBS_FUZZ_REQUIRE(flash_is_settings(after), "mains reset did not load the flash");
      for (const auto& p : cda::kParameters) {
        if (p.writable() && !in_flash(p) && !p.is_string()) {
          IBS_FUZZ_REQUIRE(*d.value(p.number) == cda::wire_of(p, p.factory), "mains reset kept a RAM value");
        }
      }
      open = false;
      drain(replies);
      check_settings(d);
      continue;
    } else {
      CanFrame f;
      const Address a = d.address();
      switch (action % 4) {
        case 0: f = read_frame(in); break;
        case 1: {
          ParameterTelegram t;
          t.parameter = kNumbers[in.ConsumeIntegral<std::uint8_t>() % std::size(kNumbers)];
          t.code = kModes[in.ConsumeIntegral<std::uint8_t>() % std::size(kModes)];
          const auto how = in.ConsumeIntegral<std::uint8_t>();
          t.data = (how & 1U) != 0 ? xor_echoed : ((how & 2U) != 0 ? in.ConsumeIntegral<std::uint8_t>() % 8U
                                                                     : in.ConsumeIntegral<std::uint32_t>());
          if ((how & 12U) == 12U) t.data = (how & 16U) != 0 ? cda::kSloadStart : cda::kSloadEnd;
          t.block = in.ConsumeIntegral<std::uint8_t>() % 8;
          f = *encode_parameter_request(ids, a, t);
          break;
        }
        case 2:
          f = *encode_control(ids, a, d.layout(),
                              {in.ConsumeIntegral<std::uint16_t>(), in.ConsumeIntegral<std::int32_t>()});
          break;
        default: f = encode_system(in.ConsumeBool() ? SystemCommand::start : SystemCommand::stop); break;
      }
      const auto k = ids.classify(f.id);
      if (k && k->kind == TelegramKind::parameter_request && k->address == a && !f.rtr && f.dlc >= 8) {
        request = decode_parameter(f).value;
      }
      d.receive(f, now);
    }
    drain(replies);
    const Snapshot after = snapshot(d);
    check_settings(d);
    if (request) {
      IBS_FUZZ_REQUIRE(replies.size() == 1 && replies[0].parameter == request->parameter &&
                           replies[0].block == request->block, "a request without exactly one reply");
    }
    const ParameterTelegram* rep = replies.empty() ? nullptr : &replies.back();
    const bool accepted = request && rep != nullptr && rep->code == kStatusOk;
    // The string machine as the drive echoed it (4.5.x writing).
    if (request && request->code == kModeStringWrite && request->block == 0) {
      open = accepted;
      open_param = request->parameter;
      xor_echoed = 0;
      blocks.clear();
    } else if (request && request->code == kModeStringWrite && open && accepted) {
      xor_echoed ^= request->data;
      for (unsigned i = 0; i < 4; ++i) blocks += static_cast<char>((request->data >> (8U * i)) & 0xFFU);
    } else if (request && request->code != kModeListEnd) {
      open = false;
    }
    // A download's end (D39): the only moment a download changes settings, and then only Card
    // Writeable ones, settings and flash alike (the handshake itself reads its result).
    const bool download_end = accepted && was_downloading && request->code == kModeWrite &&
                              request->parameter == cda::kSload && request->data == cda::kSloadEnd;
    if (download_end) {
      IBS_FUZZ_REQUIRE(!d.downloading(), "the download is still open after its end");
      for (std::size_t i = 0; i < cda::kParameters.size(); ++i) {
        const auto& p = cda::kParameters[i];
        if (p.number == cda::kReff || p.number == cda::kSload) continue;
        if (before.current[i] != after.current[i] || before.saved[i] != after.saved[i]) {
          IBS_FUZZ_REQUIRE(cda::card_writeable(p) && after.current[i] == after.saved[i],
                           "a download's end changed what is no Card Writeable setting, or not in flash");
        }
      }
      continue;
    }
    if (was_downloading && accepted && request->code == kModeWrite && request->parameter != cda::kSload) {
      IBS_FUZZ_REQUIRE(before.current == after.current, "a value of an open download acted before its end");
    }
    // Settings: only a write answered 0, with a value the table takes.
    for (std::size_t i = 0; i < cda::kParameters.size(); ++i) {
      const auto n = cda::kParameters[i].number;
      if (n == cda::kReff || before.current[i] == after.current[i]) continue;
      IBS_FUZZ_REQUIRE(accepted && request->code == kModeWrite, "a setting changed without an accepted write");
      IBS_FUZZ_REQUIRE(may_change(request->parameter, request->data, n), "a write changed another setting");
      if (n == request->parameter) IBS_FUZZ_REQUIRE(after.current[i] == request->data, "a write stored another value");
    }
    if (before.saved != after.saved || before.saved_text != after.saved_text) {
      IBS_FUZZ_REQUIRE(accepted && request->code == kModeWrite && request->parameter == cda::kSave &&
                           request->data == 1,
                       "the flash changed without 150-SAVE");
      IBS_FUZZ_REQUIRE(flash_is_settings(after), "150-SAVE did not store the settings");
    }
    if (before.text != after.text) {
      const bool prog = accepted && request->code == kModeWrite && request->parameter == cda::kProg && request->data == 1;
      if (!prog) {
        IBS_FUZZ_REQUIRE(accepted && request->code == kModeListEnd && open && open_param == request->parameter &&
                             request->data == xor_echoed,
                         "a text changed without a complete string write with the right checksum");
        IBS_FUZZ_REQUIRE(after.text == std::string(blocks.c_str()), "the text is not the blocks'");
      }
    }
    if (request && request->code == kModeListEnd) open = false;
  }
}

// `ibs canlust download`'s reading of a data set text, with the CDA3000's table as the resolver.
ResolvedRecord resolve_cda(std::string_view param, std::string_view value) {
  const cda::ParameterInfo* p = cda::find_parameter(param);
  if (p == nullptr) return {0, 0, "not a parameter"};
  if (!cda::card_writeable(*p)) return {0, 0, "not Card Writeable"};
  cda::ParsedValue v = cda::parse_value(*p, value);
  if (!v.wire) return {0, 0, v.error.empty() ? std::string("refused") : v.error};
  return {p->number, *v.wire, {}};
}

void data_set_part(Input& in) {
  const std::vector<char> bytes = in.ConsumeBytes<char>(in.remaining_bytes());
  const std::string text(bytes.begin(), bytes.end());
  const DataSetParse p = parse_data_set(text, resolve_cda);
  const std::size_t lines = ibs::fuzz::count_lines(text);
  if (!p) {
    IBS_FUZZ_REQUIRE(p.records.empty() && !p.error.empty() && p.error_line <= lines, "a refusal without its line");
    return;
  }
  IBS_FUZZ_REQUIRE(!p.records.empty(), "an accepted data set without records");
  std::string again;
  for (std::size_t i = 0; i < p.records.size(); ++i) {
    const DataSetRecord& r = p.records[i];
    const cda::ParameterInfo* info = cda::find_parameter(r.parameter);
    IBS_FUZZ_REQUIRE(info != nullptr && cda::card_writeable(*info), "a record no data set may hold");
    IBS_FUZZ_REQUIRE(cda::check_value(*info, r.value) == cda::ValueCheck::ok, "a record the table refuses");
    IBS_FUZZ_REQUIRE(r.line >= 1 && r.line <= lines && (i == 0 || r.line > p.records[i - 1].line),
                     "a record outside the text's lines");
    for (std::size_t j = 0; j < i; ++j) IBS_FUZZ_REQUIRE(p.records[j].parameter != r.parameter, "a parameter twice");
    again += std::to_string(r.parameter) + " " + std::to_string(cda::number_of(*info, r.value)) + "\n";
  }
  const DataSetParse q = parse_data_set(again, resolve_cda);
  IBS_FUZZ_REQUIRE(q && q.records.size() == p.records.size(), "the records written back do not parse");
  for (std::size_t i = 0; i < q.records.size(); ++i) {
    IBS_FUZZ_REQUIRE(q.records[i].parameter == p.records[i].parameter && q.records[i].value == p.records[i].value,
                     "the records written back parse to others");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Input in(data, size);
  const auto part = in.ConsumeIntegral<std::uint8_t>();
  if (part == 0xFF) {
    data_set_part(in);
    return 0;
  }
  switch (part % 5) {
    case 0: decoders(in); break;
    case 1: cannelloni_part(in); break;
    case 2: server_part(in); break;
    case 3: client_part(in); break;
    default: drive_part(in); break;
  }
  return 0;
}
