// The CLI11 wiring of `ibs canlust ...`, the emulator's serving loop, the client loops in real
// time, the frame recorder (candump log, pcap) and the file side of `ibs decode` for a candump log
// (the format is can/candump.hpp's).
#include "canlust_cmd.hpp"

#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <poll.h>
#include <unistd.h>
#include <algorithm>
#include <cstring>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "ibs/control/channel.hpp"
#include "ibs/base/text_file.hpp"
#include "ibs/can/can_text.hpp"
#include "ibs/can/candump.hpp"
#include "ibs/can/socketcan.hpp"
#include "ibs/can/udp.hpp"
#include "ibs/canlust/data_set.hpp"
#include "ibs/canlust/parameter_client.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/tool/format.hpp"
#include "emulate_events.hpp"
#include "stop_signals.hpp"
#ifdef IBS_HAVE_PCAP
#include "ibs/can/pcap_writer.hpp"
#endif

namespace ibs::cli {

namespace cl = ::ibs::canlust;
using Clock = std::chrono::steady_clock;
using Wall = std::chrono::system_clock;

namespace {

constexpr Duration kPoll = 20ms;

Time since(Clock::time_point t0) { return std::chrono::duration_cast<Duration>(Clock::now() - t0); }

using tool::hex;

// A frame's data bytes as candump prints them: "40 02 00 00 00 00".
std::string data_hex(const cl::CanFrame& f) { return tool::hex_bytes(f.payload()); }

std::optional<long long> parse_int(std::string_view s) {
  long long v = 0;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  const auto r = std::from_chars(first, last, v);
  if (first == last || r.ec != std::errc{} || r.ptr != last) return std::nullopt;
  return v;
}

struct BusSpec {
  bool udp = false;
  can::UdpConfig udp_config{};
  std::string iface;
};

BusSpec parse_bus(const std::string& spec) {
  const auto bad = [&](const std::string& why) {
    return std::invalid_argument("--bus '" + spec + "': " + why +
                                 " (expected udp:LOCALPORT:HOST:PORT or socketcan:IFACE)");
  };
  std::vector<std::string> parts;
  std::size_t pos = 0;
  for (;;) {
    const auto c = spec.find(':', pos);
    parts.push_back(spec.substr(pos, c == std::string::npos ? std::string::npos : c - pos));
    if (c == std::string::npos) break;
    pos = c + 1;
  }
  BusSpec b;
  if (parts[0] == "socketcan") {
    if (parts.size() != 2 || parts[1].empty()) throw bad("socketcan needs an interface name");
    b.iface = parts[1];
    return b;
  }
  if (parts[0] != "udp") throw bad("unknown bus type '" + parts[0] + "'");
  if (parts.size() != 4) throw bad("udp needs LOCALPORT, HOST and PORT");
  const auto port = [&](const std::string& text, const char* what) {
    const auto v = parse_int(text);
    if (!v || *v < 0 || *v > 65535) throw bad(std::string(what) + " '" + text + "' is not a port number (0..65535)");
    return static_cast<std::uint16_t>(*v);
  };
  b.udp = true;
  b.udp_config.local_host = parts[2] == "localhost" ? "127.0.0.1" : parts[2];
  b.udp_config.remote_host = b.udp_config.local_host;
  b.udp_config.local_port = port(parts[1], "LOCALPORT");
  b.udp_config.remote_port = port(parts[3], "PORT");
  return b;
}

std::string interface_name(const std::string& spec) {
  const BusSpec b = parse_bus(spec);
  return b.udp ? "udp" + std::to_string(b.udp_config.local_port) : b.iface;
}

cl::IdentifierMap ids_for(const CanBusOptions& o) {
  if (o.id_step < 1 || o.id_step > 2) throw std::invalid_argument("--id-step must be 1 or 2");
  cl::IdentifierMap ids;
  ids.step = static_cast<std::uint8_t>(o.id_step);
  return ids;
}

cl::ProcessLayout layout_for(const CanBusOptions& o) {
  const auto l = cl::process_layout_for_cacnf(static_cast<std::uint8_t>(o.cacnf));
  if (o.cacnf > 4 || !l) throw std::invalid_argument("--cacnf must be 1..4 (492-CACNF)");
  return *l;
}

std::optional<cl::ErrorReaction> parse_reaction(std::string_view s) {
  if (s == "wrn" || s == "warning") return cl::ErrorReaction::warning;
  if (s == "stop") return cl::ErrorReaction::stop;
  if (s == "quick-stop") return cl::ErrorReaction::quick_stop;
  if (s == "disable-power") return cl::ErrorReaction::disable_power;
  return std::nullopt;
}

// A bus with its recorder: every frame sent or received goes through here.
struct Session {
  std::unique_ptr<can::CanTransport> bus;
  std::unique_ptr<FrameRecorder> own_recorder;
  FrameRecorder* recorder = nullptr;  // own_recorder's, or the one --repeat's readings share
  std::string name;

  explicit Session(const CanBusOptions& o) : bus(open_bus(o.bus)), name(interface_name(o.bus)) {
    std::unique_ptr<FrameRecorder>& kept = o.shared_recorder != nullptr ? *o.shared_recorder : own_recorder;
    if (!kept && (!o.log.empty() || !o.pcap.empty())) kept = std::make_unique<FrameRecorder>(o.log, o.pcap, name, o.log_stdout);
    recorder = kept.get();
  }
  bool send(const cl::CanFrame& f) {
    if (recorder) recorder->record(f);
    return bus->send(f) == can::IoStatus::ok;
  }
  // monitor's filters: a frame they hold back is neither returned nor recorded, as candump's
  // socket filters keep it from its log.
  const can::CanFilterSet* filters = nullptr;
  std::optional<cl::CanFrame> receive(Duration wait) {
    const can::Received r = bus->receive(std::max<Duration>(wait, Duration::zero()));
    if (r.status != can::IoStatus::ok) return std::nullopt;
    if (filters != nullptr && !filters->passes(r.frame)) return std::nullopt;
    if (recorder) recorder->record(r.frame);
    return r.frame;
  }
};

// ---- emulate --control ----------------------------------------------------------------------

struct ControlEvent {
  std::size_t drive = 0;  // index into the served drives
  devices::CanlustEvent event;
};

// "fault E-OTI", "load 80.0 %", "input ENPO low", "mains off", "power cycle".
std::string event_words(const devices::CanlustEvent& e) {
  using K = devices::CanlustEvent::Kind;
  switch (e.kind) {
    case K::fault: return "fault " + e.cause;
    case K::load: return "load " + tool::fixed(e.load, 1, "%");
    case K::input: return "input " + e.input + (e.level ? " high" : " low");
    default: return std::string(devices::to_string(e.kind));
  }
}

// One control line of `emulate --control`: a JSON object with the scenario's drive-event keys
// (docs/canlust.md, "Live control"): `device` (the address as a number, or NAME@ADDR as given;
// optional with one drive) and one of fault = "device" + cause, fault = "mains_reset" |
// "mains_off" | "mains_on", mains = "off" | "on", load = NUMBER, input = NAME + level. Empty
// when it is good, else what is wrong.
std::string parse_control_event(std::string_view text, const std::vector<std::string>& specs,
                                std::span<devices::CanlustDrive* const> drives, ControlEvent& out) {
  using K = devices::CanlustEvent::Kind;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // nlohmann's text begins "[json.exception....] ": the what is the rest.
    std::string what = e.what();
    if (const auto at = what.find("] "); !what.empty() && what.front() == '[' && at != std::string::npos) {
      what.erase(0, at + 2);
    }
    return "not JSON: " + what;
  }
  if (!j.is_object()) return "expected a JSON object, e.g. {\"device\": 1, \"fault\": \"device\", \"cause\": \"E-OTI\"}";
  if (j.contains("at")) return "control entries apply at once: no 'at'";
  static const std::set<std::string> known{"device", "fault", "cause", "mains", "load", "input", "level"};
  for (const auto& [k, v] : j.items()) {
    (void)v;
    if (known.count(k) == 0) {
      return "unknown key '" + k + "' (expected device and one of fault (+ cause), mains, load, input (+ level); "
             "master commands need a master)";
    }
  }
  if (!j.contains("device")) {
    if (drives.size() != 1) return "device is needed: " + std::to_string(drives.size()) + " drives are served";
    out.drive = 0;
  } else {
    const nlohmann::json& d = j["device"];
    bool found = false;
    for (std::size_t i = 0; i < drives.size() && !found; ++i) {
      if ((d.is_number_unsigned() && d.get<std::uint64_t>() == drives[i]->address()) ||
          (d.is_string() && d.get<std::string>() == specs[i])) {
        out.drive = i;
        found = true;
      }
    }
    if (!found) return "device " + d.dump() + " is not served (give its address or NAME@ADDR as on the command line)";
  }
  int actions = 0;
  const auto str = [&](const char* key, std::string& v) -> std::string {
    if (!j[key].is_string()) return std::string(key) + ": expected a string";
    v = j[key].get<std::string>();
    return {};
  };
  std::string v;
  if (j.contains("fault")) {
    ++actions;
    if (auto e = str("fault", v); !e.empty()) return e;
    if (v == "device") out.event.kind = K::fault;
    else if (v == "mains_reset") out.event.kind = K::power_cycle;
    else if (v == "mains_off") out.event.kind = K::mains_off;
    else if (v == "mains_on") out.event.kind = K::mains_on;
    else return "fault = \"" + v + "\": expected device, mains_reset, mains_off or mains_on";
  }
  if (j.contains("cause")) {
    if (!j.contains("fault") || out.event.kind != K::fault) return "cause belongs to fault = \"device\"";
    const auto& c = j["cause"];
    if (c.is_number_unsigned()) out.event.cause = std::to_string(c.get<std::uint64_t>());
    else if (c.is_string()) out.event.cause = c.get<std::string>();
    else return "cause: expected the error's name or number";
  } else if (j.contains("fault") && out.event.kind == K::fault) {
    return "fault = \"device\" needs a cause (an error of the drive's table, by name or number)";
  }
  if (j.contains("mains")) {
    ++actions;
    if (auto e = str("mains", v); !e.empty()) return e;
    if (v != "off" && v != "on") return "mains = \"" + v + "\": expected \"off\" or \"on\"";
    out.event.kind = v == "off" ? K::mains_off : K::mains_on;
  }
  if (j.contains("load")) {
    ++actions;
    if (!j["load"].is_number()) return "load: expected a number (% of the rated torque)";
    out.event.kind = K::load;
    out.event.load = j["load"].get<double>();
  }
  if (j.contains("input")) {
    ++actions;
    if (auto e = str("input", v); !e.empty()) return e;
    out.event.kind = K::input;
    out.event.input = v;
    if (!j.contains("level")) return "input needs a level (\"high\" or \"low\")";
    if (auto e = str("level", v); !e.empty()) return e;
    if (v != "high" && v != "low") return "level = \"" + v + "\": expected \"high\" or \"low\"";
    out.event.level = v == "high";
  } else if (j.contains("level")) {
    return "level belongs to an input";
  }
  if (actions != 1) return "needs exactly one of fault, mains, load, input";
  return {};
}

// ---- emulate --------------------------------------------------------------------------------

int emulate(const CanlustEmulateOptions& o, std::ostream& out, std::ostream& err) {
  const auto bad = [&](const std::string& what) {
    err << "ibs canlust emulate: " << what << "\n";
    return kExitCanBadInput;
  };
  const std::string forms = devices::drive_names(devices::Bus::canlust, ", ", " or ", "@ADDR");
  if (o.devices.empty()) return bad("no device: give " + forms + " (one or more)");
  std::vector<std::unique_ptr<devices::CanlustDrive>> drives;
  std::vector<devices::CanlustDrive*> raw;
  std::vector<const devices::CanlustFace*> faces;  // --json: each drive's words for its frames
  cl::IdentifierMap ids;
  cl::ProcessLayout layout;
  try {
    ids = ids_for(o.bus);
    layout = layout_for(o.bus);
    const auto reaction = parse_reaction(o.watchdog_reaction);
    if (!reaction) {
      return bad("--watchdog-reaction '" + o.watchdog_reaction + "': expected wrn, stop, quick-stop or disable-power");
    }
    std::set<unsigned> seen;
    for (const std::string& spec : o.devices) {
      // The drive by the name before '@', from the registry's CANLust faces.
      const unsigned max = o.factory ? 7U : ids.max_address;
      const auto at = spec.find('@');
      const devices::Drive* drive =
          at == std::string::npos ? nullptr : devices::find_drive(std::string_view(spec).substr(0, at), devices::Bus::canlust);
      const auto a = drive != nullptr ? parse_int(std::string_view(spec).substr(at + 1)) : std::nullopt;
      if (!a || *a < (o.factory ? 0 : 1) || *a > static_cast<long long>(max)) {
        return bad("device '" + spec + "': expected " + forms + " with ADDR " + (o.factory ? "0..7 (the connector's address, 2.1)" : "1..99 (571-CLADR)"));
      }
      if (!seen.insert(static_cast<unsigned>(*a)).second) return bad("device '" + spec + "': address given twice");
      devices::CanlustFaceOptions c;
      c.ids = ids;
      c.watchdog_reaction = *reaction;
      c.factory = o.factory;
      c.address = static_cast<std::uint8_t>(*a);
      c.cacnf = static_cast<std::uint8_t>(o.bus.cacnf);
      drives.push_back(drive->canlust->make(c));
      raw.push_back(drives.back().get());
      faces.push_back(drive->canlust);
    }
  } catch (const std::invalid_argument& e) {
    return bad(e.what());
  }
  // Blocked before the first line is printed: whoever reads it may signal at once.
  StopSignals signals;
  std::unique_ptr<Session> s;
  try {
    s = std::make_unique<Session>(o.bus);
  } catch (const std::invalid_argument& e) {
    return bad(e.what());
  }
  std::unique_ptr<control::Channel> control;
  if (!o.control.empty()) {
    std::string error;
    control = control::Channel::open(o.control, error);
    if (!control) return bad("--control " + o.control + ": " + error);
  }
  EmulateEvents events(out);
  // The first line says where it serves (with --json the `serving` event).
  events.serving(o.bus.json, "bus", std::string(s->bus->name()), std::string());
  const auto drive_event = [&](std::size_t i, Time at, std::string_view what) {
    return EmulateEvents::event(at, what, o.devices[i], raw[i]->address());
  };
  std::function<void(Time)> each_turn;
  if (control) {
    each_turn = [&](Time now) {
      control->poll(
          [&](const control::Origin& from, std::string_view text) {
            const std::string where = control::to_string(from) + ": ";
            ControlEvent ev;
            const std::string why = parse_control_event(text, o.devices, raw, ev);
            if (!why.empty()) {
              err << where << why << "\n" << std::flush;
              return;
            }
            const devices::CanlustEventResult r = raw[ev.drive]->apply(ev.event, now);
            // A refused event is a bad line: its text says why (the drive's own check).
            if (!r.ok) {
              err << where << r.text << "\n" << std::flush;
            } else if (o.bus.json) {
              nlohmann::ordered_json j = drive_event(ev.drive, now, "control");
              j["what"] = event_words(ev.event);
              j["taken"] = true;
              j["control_line"] = from.line;
              if (from.client != 0) j["control_client"] = from.client;
              j["result"] = r.text;
              events.print(j);
            } else {
              err << where << o.devices[ev.drive] << ": " << event_words(ev.event) << ": " << r.text << "\n"
                  << std::flush;
            }
          },
          [&](const control::Origin& from, std::string_view what) {
            err << from << ": " << what << "\n" << std::flush;
          },
          [&](std::string_view notice) { err << notice << "\n" << std::flush; });
    };
  }
  // With --json the loop is watched: each frame from the bus that a drive takes as its own (a
  // control or parameter request at its address, 5.5; System Start / Stop, which every drive
  // tells), each frame a drive sends, and each change of its DRIVECOM or system state (5.2).
  struct Seen {
    std::optional<drivecom::State> state;
    std::optional<cl::SystemState> system;
    std::uint64_t telegrams = 0;
    std::uint64_t answers = 0;
  };
  std::vector<Seen> seen(raw.size());
  const auto with_frame = [&](nlohmann::ordered_json j, std::size_t i, const cl::CanFrame& f) {
    const devices::CanlustFrameText e = faces[i]->explain_frame(f, ids, layout);
    j["kind"] = e.id ? std::string(cl::to_string(e.id->kind)) : std::string("unknown");
    j["id"] = f.id;
    j["id_hex"] = hex(f.id, 3);
    j["dlc"] = f.dlc;
    j["rtr"] = f.rtr;
    j["bytes"] = data_hex(f);
    j["text"] = e.text;
    events.print(j);
  };
  const auto check_state = [&](std::size_t i, Time now) {
    const drivecom::State state = raw[i]->state();
    const cl::SystemState system = raw[i]->system_state();
    if (seen[i].state == state && seen[i].system == system) return;
    seen[i].state = state;
    seen[i].system = system;
    nlohmann::ordered_json j = drive_event(i, now, "state");
    j["state"] = std::string(drivecom::to_string(state));
    j["system"] = std::string(cl::to_string(system));
    events.print(j);
  };
  ServeWatch watch;
  watch.received = [&](const cl::CanFrame& f, Time now) {
    const std::optional<cl::Classified> c = ids.classify(f.id);
    for (std::size_t i = 0; c && i < raw.size(); ++i) {
      const bool to_drive = c->kind == cl::TelegramKind::control || c->kind == cl::TelegramKind::parameter_request;
      if (c->kind != cl::TelegramKind::system && !(to_drive && c->address == raw[i]->address())) continue;
      ++seen[i].telegrams;
      with_frame(drive_event(i, now, "telegram"), i, f);
    }
    for (std::size_t i = 0; i < raw.size(); ++i) check_state(i, now);
  };
  watch.stepped = check_state;
  watch.sent = [&](std::size_t i, const cl::CanFrame& f, Time now) {
    ++seen[i].answers;
    with_frame(drive_event(i, now, "answer"), i, f);
  };
  const Clock::time_point t0 = Clock::now();
  serve_canlust(*s->bus, raw, s->recorder, [&signals]() { return signals.raised(); }, each_turn,
                o.bus.json ? &watch : nullptr);
  if (o.bus.json) {
    for (std::size_t i = 0; i < raw.size(); ++i) {
      nlohmann::ordered_json j = drive_event(i, since(t0), "summary");
      j["counters"] = {{"telegrams", seen[i].telegrams},
                       {"answers", seen[i].answers},
                       {"watchdog_trips", raw[i]->watchdog_trips()}};
      events.print(j);
    }
  }
  return kExitCanOk;
}

// ---- the client commands --------------------------------------------------------------------

// The drive the client commands talk to: its parameter table names PARAM and formats values, its
// words explain status telegrams and frames. The registry has one drive that speaks CANLust, so it
// is the default and there is no --drive option; a second one would make every client command
// ambiguous, and then it needs one (`emulate` already names its drives: DRIVE@ADDR).
const devices::CanlustFace& client_face() {
  const std::vector<const devices::Drive*> on = devices::drives_on(devices::Bus::canlust);
  if (on.size() != 1) {
    throw std::logic_error(std::to_string(on.size()) + " drives speak CANLust (" +
                           devices::drive_names(devices::Bus::canlust, ", ", " and ") +
                           "); the client commands know which one only when there is exactly one");
  }
  return *on.front()->canlust;
}

struct Target {
  std::uint16_t number = 0;
  std::optional<devices::CanlustParameter> info;  // nullopt: not in the table; asked as a raw number
};

Target resolve(const devices::CanlustFace& face, const std::string& text) {
  if (auto p = face.find_parameter(text)) return {p->number, std::move(p)};
  const auto n = parse_int(text);
  if (n && *n >= 0 && *n <= 0xFFFF) return {static_cast<std::uint16_t>(*n), std::nullopt};
  throw std::invalid_argument("PARAM '" + text + "' is not a " + std::string(face.title) +
                              " parameter (give NUMBER, NAME or NUMBER-NAME, e.g. 574-CAWDG)");
}

std::string target_name(const Target& t) {
  return t.info ? t.info->name : "parameter " + std::to_string(t.number);
}

// "CDA 3".
std::string drive_label(const devices::CanlustFace& face, unsigned address) {
  return std::string(face.short_title) + " " + std::to_string(address);
}

// One parameter request in real time: submit, then frames out and in until its outcome.
cl::Outcome transact(Session& s, cl::ParameterClient& client, const cl::Request& r) {
  const Clock::time_point t0 = Clock::now();
  const auto sub = client.submit(r);
  if (!sub) throw std::invalid_argument("request refused: " + std::string(cl::to_string(sub.error)));
  for (;;) {
    Time now = since(t0);
    client.step(now);
    while (auto f = client.take_frame()) s.send(*f);
    const auto p = client.poll(sub.id);
    if (p.state == cl::RequestState::done) return *p.outcome;
    const Time next = client.next_deadline();
    const Duration wait = next <= now ? Duration::zero() : std::min<Duration>(next - now, 10ms);
    if (auto f = s.receive(wait)) client.receive(*f, since(t0));
  }
}

std::string value_text(const devices::CanlustFace& face, const Target& t, std::uint32_t v) {
  return t.info ? face.format_value(t.number, v) : std::to_string(v);
}

int report_outcome(const devices::CanlustFace& face, const std::string& cmd, int address, const Target& t, const cl::Outcome& o,
                   nlohmann::json& j, bool json, std::ostream& out, std::ostream& err) {
  j["outcome"] = std::string(cl::to_string(o.kind));
  j["elapsed_ms"] = to_ms(o.finished - o.started);
  if (o.kind == cl::OutcomeKind::done) return -1;  // the caller prints the result
  if (o.kind == cl::OutcomeKind::refused) {
    j["status"] = o.status;
    j["status_text"] = o.status == cl::kStatusListEnd ? std::string("List_End") : cl::describe_status(o.status);
  }
  if (json) out << j.dump() << "\n";
  err << "ibs canlust " << cmd << ": " << drive_label(face, static_cast<unsigned>(address)) << " " << target_name(t) << ": " << cl::describe(o) << "\n";
  return kExitCanDevice;
}

cl::ParameterClient make_client(const CanBusOptions& o) {
  cl::ClientConfig c;
  c.ids = ids_for(o);
  return cl::ParameterClient(c);
}

int read_cmd(const devices::CanlustFace& face, const CanlustClientOptions& o, std::ostream& out, std::ostream& err,
             cl::OutcomeKind* outcome) {
  const Target t = resolve(face, o.parameter);
  Session s(o.bus);
  cl::ParameterClient client = make_client(o.bus);
  const auto a = static_cast<cl::Address>(o.address);
  cl::Request r = (t.info && t.info->is_string) ? cl::read_string(a, t.number) : cl::read(a, t.number);
  if (o.timeout_ms > 0) r.timeout = std::chrono::milliseconds(o.timeout_ms);
  const cl::Outcome res = transact(s, client, r);
  if (outcome != nullptr) *outcome = res.kind;
  nlohmann::json j;
  j["address"] = o.address;
  j["command"] = "read";
  j["parameter"] = t.number;
  if (t.info) j["name"] = t.info->name;
  if (const int rc = report_outcome(face, "read", o.address, t, res, j, o.bus.json, out, err); rc >= 0) return rc;
  std::string text;
  if (r.kind == cl::RequestKind::read_string) {
    text = std::string(res.text.view());
    j["value"] = text;
  } else {
    text = value_text(face, t, res.value);
    j["value"] = t.info ? nlohmann::json(face.number_of(t.number, res.value)) : nlohmann::json(res.value);
    if (t.info && t.info->type == cl::DataType::int32q16) j["value"] = cl::double_from_q16(static_cast<std::int32_t>(res.value));
  }
  j["text"] = text;
  if (o.bus.json) {
    out << j.dump() << "\n";
  } else {
    out << drive_label(face, static_cast<unsigned>(o.address)) << " " << target_name(t) << ": " << text << "\n";
  }
  return kExitCanOk;
}

int write_cmd(const devices::CanlustFace& face, const CanlustClientOptions& o, std::ostream& out, std::ostream& err) {
  const Target t = resolve(face, o.parameter);
  const auto a = static_cast<cl::Address>(o.address);
  cl::Request r;
  std::string shown;
  if (t.info && t.info->is_string) {
    if (!t.info->writable) throw std::invalid_argument(t.info->name + " is read-only");
    if (o.value.size() > cl::kMaxStringChars) {
      throw std::invalid_argument(t.info->name + ": the text has " + std::to_string(o.value.size()) +
                                  " characters, at most 99 fit (4.1.1: 100 bytes with the terminator)");
    }
    r = cl::write_string(a, t.number, o.value);
    shown = o.value;
  } else if (t.info) {
    if (!t.info->writable) throw std::invalid_argument(t.info->name + " is read-only");
    const devices::CanlustValue v = face.parse_value(t.number, o.value);
    if (!v.wire) throw std::invalid_argument(v.error);
    r = cl::write(a, t.number, *v.wire);
    shown = face.format_value(t.number, *v.wire);
    if (const auto timeout = face.write_timeout(t.number)) r.timeout = *timeout;
  } else {
    const auto v = parse_int(o.value);
    if (!v || *v < -2147483648LL || *v > 4294967295LL) {
      throw std::invalid_argument("parameter " + std::to_string(t.number) + ": VALUE '" + o.value +
                                  "' is not a 32-bit number (the parameter is not in the " + std::string(face.title) + " table)");
    }
    r = cl::write(a, t.number, static_cast<std::uint32_t>(static_cast<std::uint64_t>(*v) & 0xFFFFFFFFULL));
    shown = o.value;
  }
  if (o.timeout_ms > 0) r.timeout = std::chrono::milliseconds(o.timeout_ms);
  Session s(o.bus);
  cl::ParameterClient client = make_client(o.bus);
  const cl::Outcome res = transact(s, client, r);
  nlohmann::json j;
  j["address"] = o.address;
  j["command"] = "write";
  j["parameter"] = t.number;
  if (t.info) j["name"] = t.info->name;
  j["text"] = shown;
  if (r.kind == cl::RequestKind::write_string) {
    j["value"] = o.value;
  } else {
    j["value"] = r.value;
  }
  if (const int rc = report_outcome(face, "write", o.address, t, res, j, o.bus.json, out, err); rc >= 0) return rc;
  if (o.bus.json) {
    out << j.dump() << "\n";
  } else {
    out << drive_label(face, static_cast<unsigned>(o.address)) << " " << target_name(t) << " = " << shown << ": done\n";
  }
  return kExitCanOk;
}

int describe_cmd(const devices::CanlustFace& face, const CanlustClientOptions& o, std::ostream& out, std::ostream& err) {
  const Target t = resolve(face, o.parameter);
  Session s(o.bus);
  cl::ParameterClient client = make_client(o.bus);
  const auto a = static_cast<cl::Address>(o.address);
  std::vector<std::uint32_t> items;
  nlohmann::json j;
  j["address"] = o.address;
  j["command"] = "describe";
  j["parameter"] = t.number;
  if (t.info) j["name"] = t.info->name;
  // D10: one item per request until the drive answers List_End.
  for (std::uint8_t item = 0; item < 32; ++item) {
    cl::Request r = cl::describe(a, t.number, item);
    if (o.timeout_ms > 0) r.timeout = std::chrono::milliseconds(o.timeout_ms);
    const cl::Outcome res = transact(s, client, r);
    if (res.kind == cl::OutcomeKind::refused && res.status == cl::kStatusListEnd && item > 0) break;
    if (const int rc = report_outcome(face, "describe", o.address, t, res, j, o.bus.json, out, err); rc >= 0) return rc;
    items.push_back(res.value);
  }
  j["items"] = items;
  // D29: the drive's items, as its face reads them.
  std::string text = drive_label(face, static_cast<unsigned>(o.address)) + " " + target_name(t) + ":";
  if (const auto d = face.read_description(items)) {
    const cl::DataType type = d->type;
    const bool is_signed = type == cl::DataType::int8 || type == cl::DataType::int16 ||
                           type == cl::DataType::int32 || type == cl::DataType::int32q16;
    const auto num = [&](std::uint32_t v) -> nlohmann::json {
      if (type == cl::DataType::int32q16) return cl::double_from_q16(static_cast<std::int32_t>(v));
      if (is_signed) return static_cast<std::int32_t>(v);
      return v;
    };
    j["type"] = std::string(cl::to_string(type));
    j["min"] = num(d->min);
    j["max"] = num(d->max);
    j["factory"] = num(d->factory);
    j["writable"] = d->writable;
    j["flash"] = d->flash;
    j["after_mains_reset"] = d->after_mains_reset;
    j["short_name"] = d->short_name;
    j["unit"] = d->unit;
    const std::string unit = d->unit.empty() ? "" : " " + d->unit;
    text += " " + d->short_name + ", " + j["type"].get<std::string>() + ", " + j["min"].dump() + ".." +
            j["max"].dump() + unit + ", factory " + j["factory"].dump() + unit + ", " +
            (d->writable ? "writable" : "read-only") + (d->flash ? ", flash" : ", RAM") +
            (d->after_mains_reset ? ", acts after a mains reset" : "");
  } else {
    for (std::size_t i = 0; i < items.size(); ++i) text += " item " + std::to_string(i) + " = " + hex(items[i], 8) + "H";
  }
  if (o.bus.json) {
    out << j.dump() << "\n";
  } else {
    out << text << "\n";
  }
  return kExitCanOk;
}

int system_cmd(const devices::CanlustFace& face, bool start, const CanlustClientOptions& o, std::ostream& out, std::ostream& err) {
  (void)err;
  const cl::IdentifierMap ids = ids_for(o.bus);
  const cl::ProcessLayout layout = layout_for(o.bus);
  if (o.listen_ms < 0) throw std::invalid_argument("--listen-ms must be 0 or more");
  Session s(o.bus);
  s.send(cl::encode_system(start ? cl::SystemCommand::start : cl::SystemCommand::stop));
  const Clock::time_point t0 = Clock::now();
  const Duration listen = std::chrono::milliseconds(o.listen_ms);
  std::map<unsigned, cl::StatusTelegram> last;
  std::set<unsigned> logons;
  while (since(t0) < listen) {
    const auto f = s.receive(std::min<Duration>(listen - since(t0), kPoll));
    if (!f) continue;
    const auto c = ids.classify(f->id);
    if (!c) continue;
    if (c->kind == cl::TelegramKind::status) {
      if (const auto d = cl::decode_status(*f, layout)) last[c->address] = d.value;
    } else if (c->kind == cl::TelegramKind::logon) {
      logons.insert(c->address);
    }
  }
  nlohmann::json j;
  j["command"] = start ? "start" : "stop";
  j["drives"] = nlohmann::json::array();
  j["logons"] = logons;
  if (!o.bus.json) out << (start ? "System Start" : "System Stop") << " sent\n";
  for (const auto& [a, st] : last) {
    const std::string words = layout.mode == cl::WordMode::drivecom ? face.explain_status_word(st.word)
                                                                    : "EasyDrive word " + hex(st.word, 4);
    const double hz = face.hz_from_wire(layout.actual, st.actual);
    j["drives"].push_back({{"address", a}, {"status_word", st.word}, {"status", words}, {"actual_hz", hz}});
    if (!o.bus.json) out << drive_label(face, a) << ": status " << words << "; actual " << hz << " Hz\n";
  }
  if (!o.bus.json) {
    for (const unsigned a : logons) out << drive_label(face, a) << ": logging on (System Logon)\n";
    if (last.empty() && logons.empty()) out << "no drive answered within " << o.listen_ms << " ms\n";
  }
  if (o.bus.json) out << j.dump() << "\n";
  return kExitCanOk;
}

// candump's -t: (a)bsolute wall-clock time, (d)elta to the frame before, (z)ero at the first
// frame; "(1795431275.322679)" or "(000.013265)" as candump prints them.
std::string candump_stamp(char mode, std::int64_t us) {
  return fmt::format("({:0{}}.{:06})", us / 1000000, mode == 'a' ? 10 : 3, us % 1000000);
}

can::CanFilterSet filters_of(const std::vector<std::string>& given) {
  can::CanFilterSet set;
  for (const std::string& f : given) {
    if (const auto e = can::add_candump_filters(f, set)) {
      throw std::invalid_argument("--filter '" + f + "', column " + std::to_string(e->column) + ": " + e->what +
                                  " (candump's filters: ID:MASK, ID~MASK, j; hex)");
    }
  }
  return set;
}

// candump with CANLust's words: every frame the filters let through, its time as -t says, the
// interface, the identifier in hex, [DLC], the bytes and what they mean; until --duration-ms,
// COUNT frames, MS without a frame (-T) or a signal.
int monitor_cmd(const devices::CanlustFace& face, const CanlustClientOptions& o, std::ostream& out, std::ostream& err) {
  (void)err;
  const cl::IdentifierMap ids = ids_for(o.bus);
  const cl::ProcessLayout layout = layout_for(o.bus);
  if (o.duration_ms < 0) throw std::invalid_argument("--duration-ms must be 0 (until a signal) or more");
  if (o.idle_ms < 0) throw std::invalid_argument("-T must be 0 (never) or more");
  if (o.timestamp.size() != 1 || std::string_view("adz").find(o.timestamp[0]) == std::string_view::npos) {
    throw std::invalid_argument("-t '" + o.timestamp + "': expected a (absolute), d (delta) or z (zero at the first frame)");
  }
  const char mode = o.timestamp[0];
  const can::CanFilterSet filters = filters_of(o.filters);
  StopSignals signals;
  Session s(o.bus);
  s.filters = &filters;
  const Clock::time_point t0 = Clock::now();
  const Duration limit = o.duration_ms > 0 ? Duration(std::chrono::milliseconds(o.duration_ms)) : Duration::max();
  const Duration idle = o.idle_ms > 0 ? Duration(std::chrono::milliseconds(o.idle_ms)) : Duration::max();
  Time last_frame = since(t0);
  std::optional<Time> first;
  Time previous{};
  unsigned shown = 0;
  while (since(t0) < limit && !signals.raised() && (o.count == 0 || shown < o.count)) {
    const Time now = since(t0);
    if (idle != Duration::max() && now - last_frame >= idle) break;
    Duration wait = kPoll;
    if (limit != Duration::max()) wait = std::min<Duration>(wait, limit - now);
    if (idle != Duration::max()) wait = std::min<Duration>(wait, idle - (now - last_frame));
    const auto f = s.receive(wait);
    if (!f) continue;
    const Time at = since(t0);
    last_frame = at;
    std::int64_t us = 0;
    if (mode == 'a') {
      us = std::chrono::duration_cast<std::chrono::microseconds>(Wall::now().time_since_epoch()).count();
    } else {
      if (!first) first = previous = at;
      us = std::chrono::duration_cast<std::chrono::microseconds>(at - (mode == 'z' ? *first : previous)).count();
      previous = at;
    }
    ++shown;
    const auto e = face.explain_frame(*f, ids, layout);
    if (o.bus.json) {
      nlohmann::json j;
      j["time"] = static_cast<double>(us) / 1e6;
      j["iface"] = s.name;
      j["id"] = f->id;
      j["id_hex"] = hex(f->id, 3);
      j["dlc"] = f->dlc;
      j["rtr"] = f->rtr;
      j["data"] = data_hex(*f);
      if (e.id) {
        j["kind"] = std::string(cl::to_string(e.id->kind));
        if (e.id->kind != cl::TelegramKind::system) j["address"] = e.id->address;
      }
      j["text"] = e.text;
      out << j.dump() << "\n" << std::flush;
    } else {
      // candump: " (TIME)  IFACE  ID   [DLC]  BYTES"; then CANLust's words.
      std::string d = f->rtr ? "remote request" : data_hex(*f);
      d.resize(std::max<std::size_t>(d.size(), 23), ' ');
      out << candump_stamp(mode, us) << "  " << s.name << "  " << hex(f->id, 3) << "   [" << static_cast<unsigned>(f->dlc)
          << "]  " << d << "  " << e.text << "\n"
          << std::flush;
    }
  }
  return kExitCanOk;
}

// cansend: one frame, ID#DATA, on the bus.
int send_cmd(const devices::CanlustFace& face, const CanlustClientOptions& o, std::ostream& out, std::ostream& err) {
  const can::FrameText t = can::parse_cansend(o.frame);
  if (!t.frame) {
    throw std::invalid_argument("'" + o.frame + "', column " + std::to_string(t.error.column) + ": " + t.error.what +
                                " (cansend's ID#DATA: 3 hex digits 000..7FF, '#', 0..8 bytes of 2 hex digits, '.' "
                                "between bytes; ID#R or ID#R0..R8 a remote frame)");
  }
  const cl::IdentifierMap ids = ids_for(o.bus);
  const cl::ProcessLayout layout = layout_for(o.bus);
  Session s(o.bus);
  const std::string text = can::cansend_text(*t.frame);
  if (!s.send(*t.frame)) {
    err << "ibs canlust send: " << text << ": not sent: " << s.bus->last_error() << "\n";
    return kExitCanDevice;
  }
  if (o.bus.json) {
    nlohmann::json j;
    j["command"] = "send";
    j["frame"] = text;
    j["id"] = t.frame->id;
    j["text"] = face.explain_frame(*t.frame, ids, layout).text;
    out << j.dump() << "\n";
  }
  return kExitCanOk;
}

// canplayer: the frames of a candump log on the bus, paced as their times say (the first at once),
// until the last one or a signal. The whole log is read and checked before the first frame goes.
int play_cmd(const devices::CanlustFace& face, const CanlustClientOptions& o, std::ostream& out, std::ostream& err) {
  (void)face;
  const std::string name = o.file == "-" ? "<stdin>" : o.file;
  std::string text;
  if (o.file == "-") {
    std::string chunk(64 * 1024, '\0');
    while (std::cin.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || std::cin.gcount() > 0) {
      text.append(chunk.data(), static_cast<std::size_t>(std::cin.gcount()));
      if (text.size() > kMaxInputFileBytes) throw std::invalid_argument(name + ": larger than 256 MiB");
    }
  } else {
    try {
      text = read_text_file(o.file);  // a regular file of bounded size: never a FIFO or a device
    } catch (const FileReadError& e) {
      throw std::invalid_argument(o.file + ": " + e.what());
    }
  }
  ids_for(o.bus);
  layout_for(o.bus);
  const std::vector<std::string> lines = lines_of(text);
  const can::CandumpLog log = can::read_candump_log(lines);
  if (log.error) {
    throw std::invalid_argument(name + ":" + std::to_string(log.error->line) + ": " + log.error->what +
                                " (a candump log line: (SECONDS.MICROS) IFACE ID#DATA): '" + log.error->text + "'");
  }
  std::vector<std::int64_t> times;
  for (const can::CandumpEntry& e : log.entries) {
    const std::string where = name + ":" + std::to_string(e.line) + ": ";
    if (!e.record.classic) {
      throw std::invalid_argument(where + "an extended-identifier or CAN FD frame: CANLust carries 11-bit classic frames only");
    }
    const auto us = can::candump_time_us(e.record.time);
    if (!us) throw std::invalid_argument(where + "the time '" + e.record.time + "' is not SECONDS.MICROS (up to 6 digits after the point)");
    times.push_back(*us);
  }
  if (log.entries.empty()) throw std::invalid_argument(name + ": no frame to play");
  StopSignals signals;
  Session s(o.bus);
  const Clock::time_point t0 = Clock::now();
  std::size_t sent = 0;
  std::size_t failed = 0;
  for (std::size_t i = 0; i < log.entries.size(); ++i) {
    // The frame's time after the first one's; a time earlier than the one before goes at once.
    const auto due = t0 + std::chrono::microseconds(std::max<std::int64_t>(times[i] - times[0], 0));
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(due - Clock::now()).count();
      pollfd p{signals.fd(), POLLIN, 0};
      const timespec ts{static_cast<time_t>(std::max<long long>(left, 0) / 1'000'000'000),
                        static_cast<long>(std::max<long long>(left, 0) % 1'000'000'000)};
      if (::ppoll(&p, 1, &ts, nullptr) > 0 && signals.raised()) {
        err << "ibs canlust play: " << name << ": interrupted after " << sent << " of " << log.entries.size()
            << " frames\n";
        return kExitCanInterrupted;
      }
      if (left <= 0 || Clock::now() >= due) break;
    }
    if (s.send(log.entries[i].record.frame)) {
      ++sent;
    } else {
      ++failed;
      err << "ibs canlust play: " << name << ":" << log.entries[i].line << ": not sent: " << s.bus->last_error() << "\n";
    }
  }
  if (o.bus.json) {
    nlohmann::json j;
    j["command"] = "play";
    j["file"] = name;
    j["frames"] = log.entries.size();
    j["sent"] = sent;
    j["seconds"] = static_cast<double>(times.back() - times.front()) / 1e6;
    out << j.dump() << "\n";
  }
  return failed == 0 ? kExitCanOk : kExitCanDevice;
}

// CANLust manual, "Downloading parameter data sets": FILE (one `PARAM VALUE` a line, '#' a comment) is
// read, never written; every value is checked against the drive's table before anything is sent
// (a refusal names FILE:LINE), then the set goes through the drive's handshake in one sequence
// (canlust::DataSetDownload) and the drive checks the whole set (D39).
int download_cmd(const devices::CanlustFace& face, const CanlustClientOptions& o, std::ostream& out, std::ostream& err) {
  if (face.download == nullptr) throw std::invalid_argument(std::string(face.title) + " offers no data set download");
  const cl::DownloadHandshake& h = *face.download;
  std::string text;
  try {
    text = read_text_file(o.parameter);  // a regular file of bounded size: never a FIFO or a device
  } catch (const FileReadError& e) {
    throw std::invalid_argument(o.parameter + ": " + e.what());
  }
  const auto resolve = [&face](std::string_view param, std::string_view value) -> cl::ResolvedRecord {
    const auto p = face.find_parameter(param);
    if (!p) {
      return {0, 0, "'" + std::string(param) + "' is not a " + std::string(face.title) + " parameter"};
    }
    if (!p->in_data_set) return {0, 0, p->name + " cannot be part of a data set (it is not Card Writeable)"};
    const devices::CanlustValue v = face.parse_value(p->number, value);
    if (!v.wire) return {0, 0, v.error};
    return {p->number, *v.wire, {}};
  };
  const cl::DataSetParse parsed = cl::parse_data_set(text, resolve);
  if (!parsed) {
    throw std::invalid_argument(o.parameter + (parsed.error_line > 0 ? ":" + std::to_string(parsed.error_line) : "") +
                                ": " + parsed.error);
  }
  const auto name_of = [&face](std::uint16_t n) {
    const auto p = face.parameter(n);
    return p ? p->name : "parameter " + std::to_string(n);
  };
  const auto line_of = [&](std::uint16_t n) -> std::string {
    for (const auto& r : parsed.records) {
      if (r.parameter == n) return " (" + o.parameter + ":" + std::to_string(r.line) + ")";
    }
    return "";
  };
  const std::string handshake = name_of(h.parameter);
  Session s(o.bus);
  cl::ClientConfig cc;
  cc.ids = ids_for(o.bus);
  if (o.timeout_ms > 0) cc.timeout = std::chrono::milliseconds(o.timeout_ms);
  cl::ParameterClient client(cc);
  const auto a = static_cast<cl::Address>(o.address);
  cl::DataSetDownload d(h, a, parsed.records);
  const Clock::time_point t0 = Clock::now();
  for (;;) {
    const Time now = since(t0);
    d.step(client);
    client.step(now);
    while (auto f = client.take_frame()) s.send(*f);
    d.step(client);
    if (d.finished()) break;
    const Time next = client.next_deadline();
    const Duration wait = next <= now ? Duration::zero() : std::min<Duration>(next - now, 10ms);
    if (auto f = s.receive(wait)) client.receive(*f, since(t0));
  }
  const cl::DownloadResult& r = d.result();
  const std::size_t n = parsed.records.size();
  nlohmann::json j;
  j["address"] = o.address;
  j["command"] = "download";
  j["file"] = o.parameter;
  j["records"] = n;
  j["outcome"] = std::string(cl::to_string(r.state));
  const std::string who = drive_label(face, static_cast<unsigned>(o.address));
  if (r.state == cl::DownloadState::downloaded) {
    if (o.bus.json) {
      out << j.dump() << "\n";
    } else {
      out << who << ": " << n << (n == 1 ? " parameter" : " parameters") << " downloaded, " << handshake
          << " = 0: the data set is in the EEPROM\n";
    }
    return kExitCanOk;
  }
  std::string why;
  if (r.state == cl::DownloadState::rejected) {
    j["rejected_parameter"] = r.rejected_parameter;
    why = "the drive found the data set implausible: " + name_of(r.rejected_parameter) + line_of(r.rejected_parameter) +
          ", " + handshake + " = " + std::to_string(r.rejected_parameter) + "; the old data set stays";
  } else {
    j["failed_step"] = r.step;
    if (r.outcome.kind == cl::OutcomeKind::refused) j["status"] = r.outcome.status;
    const std::string step = r.step == 0       ? handshake + " = -1 (open)"
                             : r.step <= n     ? name_of(parsed.records[r.step - 1].parameter) + " (" + o.parameter + ":" +
                                                 std::to_string(parsed.records[r.step - 1].line) + ")"
                             : r.step == n + 1 ? handshake + " = -2 (check and save)"
                                               : "reading " + handshake;
    why = step + ": " + cl::describe(r.outcome) +
          (r.step >= 1 && r.step <= n ? "; the download was dropped, the old data set stays" : "");
  }
  if (o.bus.json) out << j.dump() << "\n";
  err << "ibs canlust download: " << who << ": " << why << "\n";
  return kExitCanDevice;
}

int client(const CLI::App& which, const CanlustClientOptions& o, std::ostream& out, std::ostream& err,
           cl::OutcomeKind* outcome = nullptr) {
  const std::string name = which.get_name();
  try {
    const cl::IdentifierMap ids = ids_for(o.bus);
    layout_for(o.bus);
    if (name == "read" || name == "write" || name == "describe" || name == "download") {
      if (o.address < 0 || o.address > ids.max_address) {
        throw std::invalid_argument("--address must be 0.." + std::to_string(ids.max_address));
      }
      if (o.timeout_ms < 0) throw std::invalid_argument("--timeout-ms must be positive");
    }
    const devices::CanlustFace& face = client_face();
    if (name == "read") return read_cmd(face, o, out, err, outcome);
    if (name == "write") return write_cmd(face, o, out, err);
    if (name == "describe") return describe_cmd(face, o, out, err);
    if (name == "download") return download_cmd(face, o, out, err);
    if (name == "start") return system_cmd(face, true, o, out, err);
    if (name == "stop") return system_cmd(face, false, o, out, err);
    if (name == "send") return send_cmd(face, o, out, err);
    if (name == "play") return play_cmd(face, o, out, err);
    return monitor_cmd(face, o, out, err);
  } catch (const std::invalid_argument& e) {
    err << "ibs canlust " << name << ": " << e.what() << "\n";
    return kExitCanBadInput;
  }
}

void add_bus_options(CLI::App* cmd, CanBusOptions& b) {
  cmd->add_option("-p,--bus", b.bus, "udp:LOCALPORT:HOST:PORT (CAN over UDP, cannelloni format) or socketcan:IFACE")
      ->required();
  cmd->add_option("--id-step", b.id_step, "identifier = base + STEP x address: 2 (the examples, default) or 1 (the text)");
  cmd->add_option("--cacnf", b.cacnf, "the drives' 492-CACNF (1..3 DRIVECOM, 4 EasyDrive; default 2): the telegram layout");
  cmd->add_flag("-j,--json", b.json, "print JSON");
  cmd->add_option("--log", b.log, "write every frame sent and received to FILE in candump -l format (- for standard output; the command's own output then goes to standard error)");
  cmd->add_option("--pcap", b.pcap, "write every frame sent and received to FILE as pcap (LINKTYPE_CAN_SOCKETCAN)");
}

void add_parameter_options(CLI::App* cmd, CanlustClientOptions& o) {
  cmd->add_option("-a,--address,--addr", o.address, "the drive's CAN address (571-CLADR)")->required();
  cmd->add_option("--timeout-ms", o.timeout_ms, "the request's timeout (default 250 ms, strings 2 s)");
}

}  // namespace

// ---- recorder ---------------------------------------------------------------------------------

struct FrameRecorder::Files {
  std::ofstream log;
  std::ostream* log_out = nullptr;  // the file, or standard output for `--log -`
#ifdef IBS_HAVE_PCAP
  std::unique_ptr<can::PcapWriter> pcap;
#endif
  std::string iface;
};

FrameRecorder::FrameRecorder(const std::string& log, const std::string& pcap, std::string iface,
                             std::ostream* log_stdout)
    : files_(std::make_unique<Files>()) {
  files_->iface = std::move(iface);
  if (log == "-") {
    // candump -L: the log on standard output (the command's own lines go to standard error).
    files_->log_out = log_stdout;
  }
  if (!log.empty() && log != "-" && !pcap.empty() &&
      std::filesystem::weakly_canonical(log) == std::filesystem::weakly_canonical(pcap)) {
    throw std::invalid_argument("--log " + log + " and --pcap " + pcap + " are the same file");
  }
  // Both recordings are live (written frame by frame until the command ends), so they are written
  // in place; but nothing is emptied before both can be opened: the log is first opened without
  // truncating it (and removed again if this made it), then the capture, and only then is the log
  // truncated (issue 23, defect 4: a bad --pcap had emptied an existing --log).
  bool log_made = false;
  if (!log.empty() && log != "-") {
    std::error_code ec;
    log_made = !std::filesystem::exists(log, ec);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | O_NONBLOCK, 0666);
    if (fd < 0) {
      throw std::invalid_argument("--log " + log + ": cannot open the file for writing: " + std::strerror(errno));
    }
    ::close(fd);
  }
  const auto unmake_log = [&] {
    std::error_code ec;
    if (log_made) std::filesystem::remove(log, ec);
  };
  if (!pcap.empty()) {
#ifdef IBS_HAVE_PCAP
    auto w = can::PcapWriter::open(pcap);
    if (!w) {
      unmake_log();
      throw std::invalid_argument("--pcap " + pcap + ": " + w.error);
    }
    files_->pcap = std::move(w.transport);
#else
    unmake_log();
    throw std::invalid_argument("--pcap: this ibs was built without libpcap (apt-get install libpcap-dev)");
#endif
  }
  if (!log.empty() && log != "-") {
    files_->log.open(log, std::ios::out | std::ios::trunc);
    if (!files_->log) throw std::invalid_argument("--log " + log + ": cannot open the file for writing");
    files_->log_out = &files_->log;
  }
}

FrameRecorder::~FrameRecorder() = default;

void FrameRecorder::record(const cl::CanFrame& f, Wall::time_point at) {
  if (files_->log_out != nullptr) *files_->log_out << can::candump_line(f, at, files_->iface) << "\n" << std::flush;
#ifdef IBS_HAVE_PCAP
  if (files_->pcap) {
    files_->pcap->write(f, std::chrono::duration_cast<Duration>(at.time_since_epoch()));
    files_->pcap->flush();
  }
#endif
}

std::optional<int> decode_candump_log(const std::string& file, unsigned id_step, unsigned cacnf,
                                      std::ostream& out, std::ostream& err) {
  // Only a regular file is looked at (a FIFO would block the open), and only its head until it
  // says candump (a 2 GiB file of another kind is not read whole); everything else, and every
  // file error before that, is the trace reader's to report.
  constexpr std::size_t kSniffBytes = 64 * 1024;
  try {
    const std::string head = read_text_head(file, kSniffBytes);
    const auto first = lines_of(head, head.size() < kSniffBytes);
    // A first line that opens as candump's "(SECONDS.FRACTION) " is a candump log, good or bad:
    // a bad one is told what is wrong with it, not the trace format's first header.
    const auto opener = std::find_if(first.begin(), first.end(),
                                     [](const std::string& l) { return l.find_first_not_of(" \t") != std::string::npos; });
    const bool looks = opener != first.end() && opener->find_first_not_of(" \t") != std::string::npos &&
                       (*opener)[opener->find_first_not_of(" \t")] == '(';
    if (!looks && !can::is_candump_log(first)) return std::nullopt;
  } catch (const FileReadError&) {
    return std::nullopt;
  }
  std::vector<std::string> lines;
  try {
    lines = lines_of(read_text_file(file));
  } catch (const FileReadError& e) {
    err << "ibs decode: " << file << ": " << e.what() << "\n";
    return kExitCanBadInput;
  }
  CanBusOptions o;
  o.id_step = id_step;
  o.cacnf = cacnf;
  cl::IdentifierMap ids;
  cl::ProcessLayout layout;
  try {
    ids = ids_for(o);
    layout = layout_for(o);
  } catch (const std::invalid_argument& e) {
    err << "ibs decode: " << e.what() << "\n";
    return kExitCanBadInput;
  }
  const can::CandumpLog log = can::read_candump_log(lines);
  if (log.error) {
    err << file << ":" << log.error->line << ": not a candump log line: '" << log.error->text << "'\n";
    return kExitCanBadInput;
  }
  const devices::CanlustFace& face = client_face();
  std::string text;
  for (const can::CandumpEntry& e : log.entries) {
    std::string line = e.text;
    line.resize(std::max<std::size_t>(line.size(), 44), ' ');
    text += line + "  " +
            (e.record.classic ? face.explain_frame(e.record.frame, ids, layout).text
                              : std::string("extended or CAN FD frame: not CANLust")) + "\n";
  }
  out << text;
  return kExitCanOk;
}

std::unique_ptr<can::CanTransport> open_bus(const std::string& spec) {
  const BusSpec b = parse_bus(spec);
  if (b.udp) {
    auto t = can::UdpCanTransport::open(b.udp_config);
    if (!t) throw std::invalid_argument("--bus '" + spec + "': " + t.error);
    return std::move(t.transport);
  }
  auto t = can::SocketCan::open(b.iface);
  if (!t) throw std::invalid_argument("--bus '" + spec + "': " + t.error);
  return std::move(t.transport);
}

void serve_canlust(can::CanTransport& bus, std::span<devices::CanlustDrive* const> drives, FrameRecorder* recorder,
                   const std::function<bool()>& stop, const std::function<void(Time now)>& each_turn,
                   const ServeWatch* watch) {
  const Clock::time_point t0 = Clock::now();
  for (devices::CanlustDrive* d : drives) d->power_on(Time{0});
  while (!stop()) {
    Time now = since(t0);
    if (each_turn) each_turn(now);
    for (std::size_t i = 0; i < drives.size(); ++i) {
      drives[i]->step(now);
      if (watch != nullptr && watch->stepped) watch->stepped(i, now);
      while (auto f = drives[i]->take_frame()) {
        if (watch != nullptr && watch->sent) watch->sent(i, *f, now);
        if (recorder != nullptr) recorder->record(*f);
        (void)bus.send(*f);  // UDP with PORT 0 has no peer until one sends: the frame is lost
        for (std::size_t k = 0; k < drives.size(); ++k) {
          if (k != i) drives[k]->receive(*f, now);
        }
      }
    }
    Time next = Time::max();
    for (const devices::CanlustDrive* d : drives) next = std::min(next, d->next_deadline());
    now = since(t0);
    const Duration wait = next <= now ? Duration::zero() : std::min<Duration>(next - now, kPoll);
    const can::Received r = bus.receive(wait);
    if (r.status != can::IoStatus::ok) continue;
    if (recorder != nullptr) recorder->record(r.frame);
    now = since(t0);
    for (devices::CanlustDrive* d : drives) d->receive(r.frame, now);
    if (watch != nullptr && watch->received) watch->received(r.frame, now);
  }
}

void add_canlust_commands(CLI::App& app, CanlustCommandState& state) {
  state.canlust = app.add_subcommand(
      "canlust", "CDA3000 drives on a CANLust bus (CM-CAN1): emulate drives, start/stop, parameters, monitor (docs/canlust.md)");
  state.canlust->require_subcommand(1);

  CanlustEmulateOptions& eo = state.emulate_options;
  state.emulate = state.canlust->add_subcommand("emulate", "emulate CDA3000 drives on the bus until SIGINT/SIGTERM");
  state.emulate->add_option("DEVICE", eo.devices,
                            devices::drive_names(devices::Bus::canlust, ", ", " or ", "@ADDR") + ", one per drive")
      ->required();
  state.emulate->add_option("--watchdog-reaction", eo.watchdog_reaction,
                            "the drives' stored reaction when 574-CAWDG runs out (the error response of E-OP2, a "
                            "parameter the master may write): wrn, stop, quick-stop, disable-power (default)");
  state.emulate->add_flag("--factory", eo.factory,
                          "factory settings (CLSEL TERM, CLADR 0): ADDR is the connector's address 0..7");
  state.emulate->add_option("--control", eo.control,
                            "live control: - (standard input) or unix:PATH; JSON lines, each a drive event "
                            "(fault with cause, mains, load, input; docs/canlust.md)");
  add_bus_options(state.emulate, eo.bus);
  state.emulate->get_option("--json")->description(
      "one JSON object a line per event: serving, telegram, answer, state, control, summary (docs/canlust.md)");

  CanlustClientOptions& co = state.client_options;
  state.start = state.canlust->add_subcommand("start", "broadcast System Start (221, 01H) and show the drives' status");
  state.start->add_option("--listen-ms", co.listen_ms, "listen this long for status telegrams (default 300)");
  add_bus_options(state.start, co.bus);
  state.stop = state.canlust->add_subcommand("stop", "broadcast System Stop (221, 00H) and show the drives' status");
  state.stop->add_option("--listen-ms", co.listen_ms, "listen this long for status telegrams (default 300)");
  add_bus_options(state.stop, co.bus);

  state.read = state.canlust->add_subcommand("read", "read a parameter (mode 05, strings mode 11)");
  state.read->add_option("PARAM", co.parameter, "NUMBER, NAME or NUMBER-NAME, e.g. 360, DISP, 360-DISP")->required();
  add_parameter_options(state.read, co);
  add_repeat_options(state.read, co.repeat);
  add_bus_options(state.read, co.bus);

  state.write = state.canlust->add_subcommand("write", "write a parameter (mode 02, strings mode 08)");
  state.write->add_option("PARAM", co.parameter, "NUMBER, NAME or NUMBER-NAME")->required();
  state.write->add_option("VALUE", co.value, "a number, a substitution text (OPTN2), Hz (20.5) or a text")->required();
  add_parameter_options(state.write, co);
  add_bus_options(state.write, co.bus);

  state.describe = state.canlust->add_subcommand("describe", "read a parameter's description (mode 04, item by item)");
  state.describe->add_option("PARAM", co.parameter, "NUMBER, NAME or NUMBER-NAME")->required();
  add_parameter_options(state.describe, co);
  add_bus_options(state.describe, co.bus);

  state.download = state.canlust->add_subcommand(
      "download", "download a parameter data set (PARAM VALUE lines): checked by the drive as a whole, then in its EEPROM");
  state.download->add_option("FILE", co.parameter, "the data set: `PARAM VALUE` per line, '#' starts a comment")->required();
  state.download->add_option("-a,--address,--addr", co.address, "the drive's CAN address (571-CLADR)")->required();
  state.download->add_option("--timeout-ms", co.timeout_ms, "each request's timeout (default 250 ms; the final check 2 s)");
  add_bus_options(state.download, co.bus);

  state.monitor = state.canlust->add_subcommand(
      "monitor", "candump with CANLust's words: every frame, filtered, in hex and decoded, until SIGINT/SIGTERM");
  state.monitor
      ->add_option("-f,--filter", co.filters,
                   "candump's filters, hex: ID:MASK (id & mask == ID & MASK), ID~MASK (!=), j (all must match); "
                   "comma-separated or repeated; none: every frame")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  state.monitor->add_option("-n,--count", co.count, "stop after COUNT frames (candump -n)")->type_name("COUNT");
  state.monitor
      ->add_option("-t,--timestamp", co.timestamp,
                   "the time of each frame (candump -t): a absolute, d delta to the frame before, z since the first "
                   "frame (default)")
      ->type_name("a|d|z");
  state.monitor->add_option("-T,--idle-ms", co.idle_ms, "stop after MS without a frame (candump -T; default: never)")
      ->type_name("MS");
  state.monitor->add_option("--duration-ms", co.duration_ms, "stop after MS (default: until a signal)");
  add_bus_options(state.monitor, co.bus);

  state.send = state.canlust->add_subcommand("send", "cansend: send one frame, ID#DATA (e.g. 0DD#01: System Start)");
  state.send
      ->add_option("FRAME", co.frame,
                   "ID#DATA: 3 hex digits, '#', 0..8 bytes of 2 hex digits ('.' between bytes allowed); ID#R a remote frame")
      ->required();
  add_bus_options(state.send, co.bus);

  state.play = state.canlust->add_subcommand(
      "play", "canplayer: send the frames of a candump log, paced in real time by their timestamps");
  state.play->add_option("FILE", co.file, "the candump log ((SECONDS.MICROS) IFACE ID#DATA a line); - standard input")
      ->required();
  add_bus_options(state.play, co.bus);
}

std::optional<int> run_canlust_commands(const CanlustCommandState& state, std::ostream& standard_out,
                                        std::ostream& err) {
  if (state.canlust == nullptr || !state.canlust->parsed()) return std::nullopt;
  // `--log -` puts the candump log on standard output: what the command prints itself goes to
  // standard error then, so that the log stays a log (candump -L, issue 27.1).
  const std::string& log = state.emulate->parsed() ? state.emulate_options.bus.log : state.client_options.bus.log;
  std::ostream& out = log == "-" ? err : standard_out;
  CanlustEmulateOptions emulate_options = state.emulate_options;
  emulate_options.bus.log_stdout = &standard_out;
  CanlustClientOptions client_options = state.client_options;
  client_options.bus.log_stdout = &standard_out;
  if (state.emulate->parsed()) return emulate(emulate_options, out, err);
  if (state.read->parsed()) {
    // mbpoll's -1 / -l (repeat.hpp): one line or JSON object a reading, the failures counted.
    unsigned timeouts = 0;
    unsigned refused = 0;
    unsigned other = 0;
    std::unique_ptr<FrameRecorder> shared_recorder;  // the readings' one log and capture (Session)
    if (client_options.repeat.repeat != 1) client_options.bus.shared_recorder = &shared_recorder;
    return repeat_readings(
        client_options.repeat, "ibs canlust read", err, kExitCanBadInput,
        [&] {
          cl::OutcomeKind kind = cl::OutcomeKind::done;
          const int rc = client(*state.read, client_options, out, err, &kind);
          out.flush();  // a pipe sees each reading as it comes
          if (rc == kExitCanDevice) {
            if (kind == cl::OutcomeKind::timeout) ++timeouts;
            else if (kind == cl::OutcomeKind::refused) ++refused;
            else ++other;
          }
          return rc;
        },
        [&] {
          std::string s;
          const auto add = [&s](unsigned n, const char* one, const char* many) {
            if (n > 0) s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + (n == 1 ? one : many);
          };
          add(timeouts, "timeout", "timeouts");
          add(refused, "refused", "refused");
          add(other, "other failure", "other failures");
          return s;
        });
  }
  for (const CLI::App* c : {state.start, state.stop, state.write, state.describe, state.download, state.monitor,
                            state.send, state.play}) {
    if (c->parsed()) return client(*c, client_options, out, err);
  }
  return kExitCanBadInput;
}

std::optional<int> run_canlust_commands(const CanlustCommandState& state) {
  return run_canlust_commands(state, std::cout, std::cerr);
}

}  // namespace ibs::cli
