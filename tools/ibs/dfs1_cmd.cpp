// The CLI11 wiring of `ibs dfs1 ...`: the emulator serves with serial::serve, the client commands
// ask through serial::transact (transports/serial/dfs1_host.hpp).
#include "dfs1_cmd.hpp"

#include <CLI/CLI.hpp>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <deque>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "ibs/control/channel.hpp"
#include "ibs/devices/dfs1/parameters.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/devices/dfs1/served_controller.hpp"
#include "ibs/devices/dfs1/status.hpp"
#include "ibs/serial/byte_log.hpp"
#include "ibs/serial/dfs1_host.hpp"
#include "ibs/serial/pty.hpp"
#include "ibs/serial/serve.hpp"
#include "ibs/tool/format.hpp"
#include "line_outputs.hpp"
#include "watched_line_device.hpp"
#include "stop_signals.hpp"

namespace ibs::cli {

namespace proto = ::ibs::dfs1;
namespace dev = ::ibs::devices::dfs1;

namespace {

constexpr Duration kInterByteTimeout = 20ms;

serial::PortOptions port_options(const Dfs1PortOptions& o) {
  serial::PortOptions p;
  p.baud = o.baud;
  p.framing = serial::parse_framing(o.framing);
  p.rs485 = o.rs485;
  return p;
}

// "dfs1@UID": the registry's DFS-1 drives.
std::string device_forms() { return devices::drive_names(devices::Bus::dfs1, ", ", " or ", "@UID"); }

// "dfs1@7" -> (the drive's face, 7); throws std::invalid_argument naming the text.
std::pair<const dev::Dfs1Face*, std::uint8_t> parse_device(const std::string& spec) {
  const auto bad = [&]() {
    return std::invalid_argument("device '" + spec + "': expected " + device_forms() + " with UID 1..255");
  };
  const auto at = spec.find('@');
  if (at == std::string::npos) throw bad();
  const devices::Drive* d = devices::find_drive(std::string_view(spec).substr(0, at), devices::Bus::dfs1);
  if (d == nullptr) throw bad();
  const std::string rest = spec.substr(at + 1);
  unsigned v = 0;
  const auto r = std::from_chars(rest.data(), rest.data() + rest.size(), v);
  if (rest.empty() || r.ec != std::errc{} || r.ptr != rest.data() + rest.size() || v < 1 ||
      v > 255) {
    throw bad();
  }
  return {d->dfs1, static_cast<std::uint8_t>(v)};
}

using tool::hex2;

std::string join(const std::vector<std::string_view>& v) {
  if (v.empty()) return "none";
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " ") + std::string(x);
  return s;
}

const char* json_kind(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::object:
      return "an object";
    default:
      return "a value of another kind";
  }
}

// The control channel of `emulate --control`: lines are parsed as they come, their events posted
// to the controller they name and applied at the serve loop's next turn with its time; what each
// did is printed once applied. A bad line is reported and skipped; nothing here ends the run.
class EmulatorControl {
 public:
  EmulatorControl(std::unique_ptr<control::Channel> input, const std::vector<std::string>& names,
                  const std::vector<std::uint8_t>& uids, const std::vector<std::unique_ptr<dev::ServedController>>& served,
                  std::ostream& err, EmulateEvents* events)
      : input_(std::move(input)), names_(names), uids_(uids), served_(served), err_(err), events_(events) {}

  // Called from the serve loop's stop(): what the last turn applied, then the new lines.
  void turn() {
    print_reports();
    input_->poll([this](const control::Origin& from, std::string_view text) { take(from, text); },
                 [this](const control::Origin& from, std::string_view what) { bad(from, what); },
                 [this](std::string_view notice) { err_ << notice << "\n"; });
    while (!waiting_.empty() && served_[waiting_.front().first]->post(waiting_.front().second)) waiting_.pop_front();
  }
  void print_reports() {
    for (std::size_t i = 0; i < served_.size(); ++i) {
      while (const auto r = served_[i]->take_report()) {
        if (events_ != nullptr) {
          nlohmann::ordered_json j =
              EmulateEvents::event(r->at, "control", names_[i], served_[i]->controller().uid());
          j["what"] = dev::to_string(*r);
          j["taken"] = true;
          events_->print(j);
          continue;
        }
        err_ << "ibs dfs1 emulate: " << tool::seconds(r->at) << ": " << names_[i] << ": " << dev::to_string(*r) << "\n";
      }
    }
  }

 private:
  void bad(const control::Origin& n, std::string_view what) { err_ << n << ": " << what << "\n"; }

  void take(const control::Origin& n, std::string_view text) {
    const dev::ParsedControl p = parse_dfs1_control_line(text);
    if (!p.event) return bad(n, p.error);
    std::optional<std::size_t> which;
    if (!p.event->uid) {
      if (served_.size() != 1) {
        return bad(n, "no \"device\": " + std::to_string(served_.size()) + " controllers are served (" + served() +
                          "); name one");
      }
      which = 0;
    } else {
      // The UID the controller answers to now (parameter 1 may have changed it, D5), else the one
      // of the command line.
      for (std::size_t i = 0; i < served_.size() && !which; ++i) {
        if (served_[i]->controller().uid() == *p.event->uid) which = i;
      }
      for (std::size_t i = 0; i < uids_.size() && !which; ++i) {
        if (uids_[i] == *p.event->uid) which = i;
      }
      if (!which) {
        return bad(n, "\"device\": UID " + std::to_string(*p.event->uid) + " is not served here; served: " + served());
      }
    }
    waiting_.emplace_back(*which, p.event->event);
  }

  std::string served() const {
    std::string s;
    for (const auto& n : names_) s += (s.empty() ? "" : ", ") + n;
    return s;
  }

  std::unique_ptr<control::Channel> input_;
  const std::vector<std::string>& names_;
  const std::vector<std::uint8_t>& uids_;
  const std::vector<std::unique_ptr<dev::ServedController>>& served_;
  std::ostream& err_;
  EmulateEvents* events_;  // --json: the reports as events; nullptr: as text on err_
  std::deque<std::pair<std::size_t, dev::Event>> waiting_;  // posted once their controller has room
};

int emulate(const Dfs1EmulateOptions& o, std::ostream& out, std::ostream& err) {
  const bool pty = o.pty || !o.pty_link.empty();  // --pty-link implies --pty
  if (pty == !o.port.port.empty()) {
    err << "ibs dfs1 emulate: give either --port PATH or --pty (or --pty-link PATH)\n";
    return kExitDfs1BadInput;
  }
  if (o.devices.empty()) {
    err << "ibs dfs1 emulate: no device: give " << device_forms() << " (one or more)\n";
    return kExitDfs1BadInput;
  }
  std::vector<std::unique_ptr<dev::Controller>> controllers;
  std::vector<std::unique_ptr<dev::ServedController>> served;
  std::vector<base::LineDevice*> raw;
  std::set<std::uint8_t> uids;
  std::vector<std::uint8_t> uid_order;
  serial::PortOptions popts;
  try {
    popts = port_options(o.port);
    for (const std::string& spec : o.devices) {
      const auto [face, uid] = parse_device(spec);
      if (!uids.insert(uid).second) {
        throw std::invalid_argument("device '" + spec + "': UID " + std::to_string(uid) +
                                    " is given twice");
      }
      uid_order.push_back(uid);
      controllers.push_back(face->make(uid, o.port.baud));
      served.push_back(std::make_unique<dev::ServedController>(*controllers.back()));
      raw.push_back(served.back().get());
    }
  } catch (const std::invalid_argument& e) {
    err << "ibs dfs1 emulate: " << e.what() << "\n";
    return kExitDfs1BadInput;
  }

  EmulateEvents events(out);
  // The control channel exists before `pty: PATH` is printed: whoever reads that line may connect.
  std::optional<EmulatorControl> control;
  if (!o.control.empty()) {
    std::string why;
    auto input = control::Channel::open(o.control, why);
    if (!input) {
      err << "ibs dfs1 emulate: --control " << o.control << ": " << why << "\n";
      return kExitDfs1BadInput;
    }
    control.emplace(std::move(input), o.devices, uid_order, served, err, o.json ? &events : nullptr);
  }

  // Blocked before `pty: PATH` is printed: whoever reads that line may signal at once.
  StopSignals signals;
  std::optional<serial::PtyPair> pair;
  std::optional<serial::PtyLink> link;
  std::optional<serial::SerialPort> opened;
  try {
    if (pty) {
      pair.emplace(serial::PtyPair::open(popts));
      if (!o.pty_link.empty()) link.emplace(o.pty_link, pair->slave_path());
    } else {
      opened.emplace(serial::SerialPort::open(o.port.port, popts));
    }
  } catch (const std::exception& e) {
    err << "ibs dfs1 emulate: " << e.what() << "\n";
    return kExitDfs1BadInput;
  }
  serial::SerialPort& port = pair ? pair->master() : *opened;
  // The first line says where it serves: the new pty, or the port it opened.
  events.serving(o.json, pair ? "pty" : "port", pair ? pair->slave_path() : o.port.port,
                 link ? link->path() : std::string());
  for (const std::string& n : port.notes()) err << "ibs dfs1 emulate: " << n << "\n";

  std::unique_ptr<serial::ByteLog> log;
  try {
    log = open_byte_log(o.port.log, o.port.log_stream);
  } catch (const std::exception& e) {
    err << "ibs dfs1 emulate: " << e.what() << "\n";
    return kExitDfs1BadInput;
  }
  port.set_log(log.get());
  port.set_tap(o.port.tap);

  // With --json each controller's line is watched: after each byte, what its receiver counted
  // (a request, a frame for another UID, a corrupt frame, a fragment dropped after silence, D13).
  std::vector<std::vector<std::uint8_t>> frames(controllers.size());
  std::vector<proto::ControllerReceiver::Counters> seen(controllers.size());
  std::vector<std::unique_ptr<WatchedLineDevice>> watched;
  const auto watch_byte = [&](std::size_t i, std::uint8_t b, Time now) {
    constexpr std::size_t kMaxFrame = 128;  // longer than any frame of the DFS-1: a host's frame unended
    std::vector<std::uint8_t>& bytes = frames[i];
    const auto& n = controllers[i]->counters();
    const auto print = [&](std::string_view what, const char* key, std::string_view value, bool with_bytes) {
      nlohmann::ordered_json j = EmulateEvents::event(now, what, o.devices[i], controllers[i]->uid());
      if (key != nullptr) j[key] = std::string(value);
      if (with_bytes) j["bytes"] = serial::format_bytes(bytes);
      events.print(j);
    };
    if (n.fragments != seen[i].fragments) {  // this byte came after a silence: the fragment before it went
      print("corrupt", "what", "fragment", true);
      bytes.clear();
    }
    if (bytes.size() < kMaxFrame) bytes.push_back(b);
    if (n.dropped_replies != seen[i].dropped_replies) print("answer-cut", nullptr, "", false);
    if (n.requests != seen[i].requests) {
      print("telegram", "kind", n.globals != seen[i].globals ? "global" : "request", true);
      bytes.clear();
    } else if (n.decode_errors != seen[i].decode_errors) {
      print("corrupt", "what", "decode", true);
      bytes.clear();
    } else if (n.foreign != seen[i].foreign) {
      bytes.clear();  // a frame for another UID: that controller tells it
    }
    seen[i] = n;
  };
  if (o.json) {
    raw.clear();
    for (std::size_t i = 0; i < served.size(); ++i) {
      watched.push_back(std::make_unique<WatchedLineDevice>(
          *served[i], events, o.devices[i], [&controllers, i] { return unsigned{controllers[i]->uid()}; },
          [&watch_byte, i](std::uint8_t b, Time now) { watch_byte(i, b, now); }));
      raw.push_back(watched.back().get());
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  serial::serve(port, raw, [&signals, &control]() {
    if (control) control->turn();
    return signals.raised();
  });
  if (control) control->print_reports();
  // What each controller heard, and what it threw away (D13: fragments a silent host left).
  for (std::size_t i = 0; i < controllers.size(); ++i) {
    const auto& c = controllers[i];
    const auto& n = c->counters();
    if (o.json) {
      const Time end{std::chrono::duration_cast<Duration>(std::chrono::steady_clock::now() - t0)};
      nlohmann::ordered_json j = EmulateEvents::event(end, "summary", o.devices[i], c->uid());
      j["counters"] = {{"requests", n.requests},           {"globals", n.globals},
                       {"foreign", n.foreign},             {"decode_errors", n.decode_errors},
                       {"fragments", n.fragments},         {"dropped_replies", n.dropped_replies}};
      events.print(j);
      continue;
    }
    err << "ibs dfs1 emulate: UID " << static_cast<unsigned>(c->uid()) << ": " << n.requests << " request(s), "
        << n.decode_errors << " corrupt frame(s), " << n.fragments << " fragment(s) dropped after silence, "
        << n.dropped_replies << " reply(ies) cut by a new request\n";
  }
  return kExitDfs1Ok;
}

struct ClientPlan {
  proto::Frame request;
  std::string what;
};

int client(const CLI::App& which, const Dfs1ClientOptions& o, std::ostream& out,
           std::ostream& err) {
  const std::string name = which.get_name();
  const auto bad = [&](const std::string& what) {
    err << "ibs dfs1 " << name << ": " << what << "\n";
    return kExitDfs1BadInput;
  };
  if (o.uid < 0 || o.uid > 255) return bad("--uid must be 0..255");
  const auto uid = static_cast<std::uint8_t>(o.uid);
  const bool execute_global = name == "speed" && o.execute_only;
  if (uid == 0 && !execute_global) {
    return bad("UID 0 is the global address, only for `speed --execute` (command 83)");
  }
  if (o.timeout_ms <= 0) return bad("--timeout-ms must be positive");

  ClientPlan plan;
  if (name == "status") {
    plan = {proto::request::status(uid), "status"};
  } else if (name == "read" || name == "write") {
    if (!o.parameter || *o.parameter < 0 || *o.parameter > 255) return bad("PARAM must be 0..255");
    const auto p = static_cast<std::uint8_t>(*o.parameter);
    if (name == "read") {
      plan = {proto::request::read_parameter(uid, p), "read parameter " + std::to_string(p)};
    } else {
      if (!o.value || *o.value < 0 || *o.value > 0xFFFFFFFFLL)
        return bad("VALUE must be 0..4294967295");
      const auto v = static_cast<std::uint32_t>(*o.value);
      plan = {proto::request::write_parameter(uid, p, v),
              "write parameter " + std::to_string(p) + " = " + std::to_string(v)};
    }
  } else {  // speed
    if (o.set_only && o.execute_only) return bad("--set and --execute exclude each other");
    if (o.execute_only) {
      if (o.value) return bad("--execute takes no RPM: it runs the speed set before");
      plan = {proto::request::execute_speed(uid), "execute speed"};
    } else {
      if (!o.value) return bad("RPM is required (or --execute)");
      if (*o.value < INT32_MIN || *o.value > INT32_MAX) return bad("RPM does not fit 32 bits");
      const auto rpm = static_cast<std::int32_t>(*o.value);
      plan = o.set_only ? ClientPlan{proto::request::set_speed(uid, rpm),
                                     "set speed " + std::to_string(rpm)}
                        : ClientPlan{proto::request::set_and_execute_speed(uid, rpm),
                                     "set and execute speed " + std::to_string(rpm)};
    }
  }

  std::optional<serial::SerialPort> port;
  std::unique_ptr<serial::ByteLog> log;
  try {
    if (o.port.port.empty()) return bad("--port PATH is required");
    port.emplace(serial::SerialPort::open(o.port.port, port_options(o.port)));
    std::unique_ptr<serial::ByteLog>& kept = o.port.shared_log != nullptr ? *o.port.shared_log : log;
    if (!kept) kept = open_byte_log(o.port.log, o.port.log_stream);
    port->set_log(kept.get());
  } catch (const std::exception& e) {
    return bad(e.what());
  }
  port->set_tap(o.port.tap);

  const proto::HostResult r = serial::transact(
      *port, plan.request, {std::chrono::milliseconds(o.timeout_ms), kInterByteTimeout});

  nlohmann::json j;
  j["uid"] = o.uid;
  j["command"] = std::string(proto::to_string(static_cast<proto::Command>(plan.request.code)));
  j["outcome"] = std::string(proto::to_string(r.outcome));
  j["elapsed_ms"] = to_ms(r.elapsed);
  if (plan.request.code == static_cast<std::uint8_t>(proto::Command::read_parameter) ||
      plan.request.code == static_cast<std::uint8_t>(proto::Command::write_parameter)) {
    j["parameter"] = *o.parameter;
  }
  const std::string who = "uid " + std::to_string(o.uid) + " " + plan.what;

  if (r.outcome == proto::Outcome::nak) {
    j["error"] = r.error;
    j["error_name"] = std::string(proto::error_name(r.error));
    if (o.json) out << j.dump() << "\n";
    err << "ibs dfs1 " << name << ": " << who << ": NAK " << hex2(r.error) << "H "
        << proto::error_name(r.error) << "\n";
    return kExitDfs1Device;
  }
  if (r.outcome != proto::Outcome::ack && r.outcome != proto::Outcome::sent) {
    if (r.last_decode_error)
      j["last_decode_error"] = std::string(proto::to_string(*r.last_decode_error));
    j["bytes_heard"] = r.bytes_heard;
    j["other_frames"] = r.other_frames;
    j["corrupt_frames"] = r.corrupt_frames;
    if (o.json) out << j.dump() << "\n";
    err << "ibs dfs1 " << name << ": " << who << ": " << proto::to_string(r.outcome);
    if (r.outcome == proto::Outcome::timeout)
      err << " (no answer within " << o.timeout_ms << " ms)";
    if (r.outcome == proto::Outcome::line_busy) {
      err << " (no response ended within " << to_ms(r.elapsed) << " ms, the overall deadline, while the line kept carrying bytes)";
    }
    if (r.bytes_heard > 0) {
      err << "; heard " << r.bytes_heard << " byte(s), " << r.other_frames << " frame(s) not our response, "
          << r.corrupt_frames << " corrupt frame(s)";
    }
    if (r.last_decode_error)
      err << ", last corrupt frame: " << proto::to_string(*r.last_decode_error);
    err << "\n";
    return kExitDfs1Device;
  }

  if (name == "status") {
    const auto& f = r.response;
    const auto commanded = proto::to_signed(f.value_at(0));
    const auto actual = proto::to_signed(f.value_at(4));
    const std::uint32_t load = f.value_at(8);
    const std::uint8_t st2 = f.data[14];
    const std::uint8_t st1 = f.data[15];
    j["value"] = f.value_at(12);
    j["commanded_speed"] = commanded;
    j["actual_speed"] = actual;
    j["load_percent"] = load;
    j["st2"] = st2;
    j["st1"] = st1;
    j["st2_flags"] = dev::st2_flags(st2);
    j["st1_flags"] = dev::st1_flags(st1);
    if (o.json) {
      out << j.dump() << "\n";
    } else {
      out << "uid " << o.uid << ": commanded " << commanded << " rpm, actual " << actual
          << " rpm, load " << load << " %\n"
          << "ST2 " << hex2(st2) << "H: " << join(dev::st2_flags(st2)) << "\n"
          << "ST1 " << hex2(st1) << "H: " << join(dev::st1_flags(st1)) << "\n";
    }
  } else if (name == "read") {
    const std::uint32_t v = r.value();
    j["value"] = v;
    const dev::ParameterInfo* p = dev::find_parameter(static_cast<std::uint8_t>(*o.parameter));
    if (p != nullptr) j["name"] = std::string(p->name);
    if (o.json) {
      out << j.dump() << "\n";
    } else {
      out << "uid " << o.uid << " parameter " << *o.parameter;
      if (p != nullptr) out << " (" << p->name << ")";
      out << ": " << v;
      if (p != nullptr && !p->unit.empty()) out << " " << p->unit;
      out << "\n";
    }
  } else {
    if (o.value) j["value"] = *o.value;
    if (o.json) {
      out << j.dump() << "\n";
    } else {
      out << who << ": " << proto::to_string(r.outcome) << "\n";
    }
  }
  return kExitDfs1Ok;
}

void add_port_options(CLI::App* cmd, Dfs1PortOptions& p) {
  cmd->add_option("--baud", p.baud, "baud rate (default 9600; a pty ignores it)");
  cmd->add_option("--framing", p.framing, "data bits, parity, stop bits (default 8N1)");
  cmd->add_flag("--rs485", p.rs485, "let the driver switch the RS-485 transmitter (TIOCSRS485)");
  add_line_output_options(cmd, p.log, p.pcap);
}

void add_client_options(CLI::App* cmd, Dfs1ClientOptions& o) {
  cmd->add_option("-p,--port", o.port.port, "the serial port (e.g. /dev/ttyUSB0 or a pty)")
      ->required();
  cmd->add_option("-a,--address,--uid", o.uid, "the controller's unit ID, 1..255")->required();
  cmd->add_option("--timeout-ms", o.timeout_ms, "response timeout in ms (default 200)");
  cmd->add_flag("-j,--json", o.json, "print JSON");
  add_port_options(cmd, o.port);
}

}  // namespace

void add_dfs1_commands(CLI::App& app, Dfs1CommandState& state) {
  state.dfs1 = app.add_subcommand("dfs1",
                                  "PowerTec DFS-1 over a serial port: emulate controllers, "
                                  "or ask one (docs/dfs1.md)");
  state.dfs1->require_subcommand(1);

  Dfs1EmulateOptions& eo = state.emulate_options;
  state.emulate = state.dfs1->add_subcommand(
      "emulate", "emulate DFS-1 controllers on a port or a new pty until SIGINT/SIGTERM");
  state.emulate->add_option("DEVICE", eo.devices, device_forms() + ", one per controller")->required();
  state.emulate->add_option("-p,--port", eo.port.port, "the serial port to serve");
  state.emulate->add_flag("--pty", eo.pty, "create a pseudo-terminal and print `pty: PATH` first");
  state.emulate->add_option("--pty-link", eo.pty_link,
                            "with --pty (implied): a symbolic link PATH to the pty, as socat's pty,link=PATH; "
                            "a PATH that exists is refused, the link is removed at exit");
  add_port_options(state.emulate, eo.port);
  state.emulate->add_flag("-j,--json", eo.json,
                          "one JSON object a line per event: serving, telegram, answer, corrupt, answer-cut, "
                          "control, summary (docs/dfs1.md)");
  state.emulate->add_option("--control", eo.control,
                            "faults and plant events as JSON lines from - (standard input) or unix:PATH "
                            "(a socket it creates); docs/dfs1.md, \"Faults on demand\"");

  Dfs1ClientOptions& co = state.client_options;
  state.status = state.dfs1->add_subcommand("status", "command 81: speeds, load, ST2 and ST1");
  add_client_options(state.status, co);
  add_repeat_options(state.status, co.repeat);

  state.read = state.dfs1->add_subcommand("read", "command 85: read a parameter");
  state.read
      ->add_option_function<long long>(
          "PARAM", [&co](const long long& v) { co.parameter = v; }, "parameter number")
      ->required();
  add_client_options(state.read, co);
  add_repeat_options(state.read, co.repeat);

  state.write = state.dfs1->add_subcommand("write", "command 86: write a parameter");
  state.write
      ->add_option_function<long long>(
          "PARAM", [&co](const long long& v) { co.parameter = v; }, "parameter number")
      ->required();
  state.write
      ->add_option_function<long long>(
          "VALUE", [&co](const long long& v) { co.value = v; }, "the value (4 bytes)")
      ->required();
  add_client_options(state.write, co);

  state.speed = state.dfs1->add_subcommand(
      "speed", "84 set and execute RPM; --set: 82 only; --execute: 83 (UID 0: every controller)");
  state.speed->add_option_function<long long>(
      "RPM", [&co](const long long& v) { co.value = v; }, "speed in rpm, negative reverse");
  state.speed->add_flag("--set", co.set_only, "command 82: set the speed, do not run it");
  state.speed->add_flag("--execute", co.execute_only, "command 83: run the speed set before");
  add_client_options(state.speed, co);
}

std::optional<int> run_dfs1_commands(const Dfs1CommandState& state, std::ostream& out,
                                     std::ostream& err) {
  if (state.dfs1 == nullptr || !state.dfs1->parsed()) return std::nullopt;
  // `--log -` (issue 27.1) and `--pcap -`: that is standard output, and what the command prints
  // itself goes to standard error, as `ibs run --pcap -` does (line_outputs.hpp).
  Dfs1EmulateOptions eo = state.emulate_options;
  Dfs1ClientOptions co = state.client_options;
  const Dfs1PortOptions& port = state.emulate->parsed() ? eo.port : co.port;
  if (port.log == "-") eo.port.log_stream = co.port.log_stream = &out;
  const std::vector<CLI::App*> chosen = state.dfs1->get_subcommands();  // the one parsed (require_subcommand(1))
  if (chosen.empty()) return kExitDfs1BadInput;
  const CLI::App& c = *chosen.front();
  const LineOutputs outputs{port.log, port.pcap, serial::LineProtocol::dfs1, state.emulate->parsed(),
                            "ibs dfs1 " + c.get_name(), kExitDfs1BadInput};
  return run_with_line_outputs(outputs, out, err, [&](serial::ByteTap* tap, std::ostream& say) {
    eo.port.tap = co.port.tap = tap;
    if (state.emulate->parsed()) return emulate(eo, say, err);
    if (&c != state.status && &c != state.read) return client(c, co, say, err);
    std::unique_ptr<serial::ByteLog> shared_log;  // the readings' one byte log (client)
    if (co.repeat.repeat != 1) co.port.shared_log = &shared_log;
    return repeat_readings(co.repeat, "ibs dfs1 " + c.get_name(), err, kExitDfs1BadInput, [&] {
      const int rc = client(c, co, say, err);
      say.flush();  // a pipe sees each reading as it comes
      return rc;
    });
  });
}

dev::ParsedControl parse_dfs1_control_line(std::string_view text) {
  dev::ParsedControl bad;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // A syntax error, or a number no double holds (out_of_range.406, "1e400"): the line is bad,
    // the emulator goes on. nlohmann's message begins "[json.exception.parse_error.101] ...".
    std::string what = e.what();
    const auto at = what.find("] ");
    if (at != std::string::npos) what = what.substr(at + 2);
    bad.error = "not JSON: " + what;
    return bad;
  }
  if (!j.is_object()) {
    bad.error = std::string("expected a JSON object like {\"fault\": \"device\", \"cause\": \"IOC\"}, got ") +
                (j.is_string() ? "a string" : j.is_number() ? "a number" : json_kind(j));
    return bad;
  }
  dev::ControlFields fields;
  for (const auto& [key, v] : j.items()) {
    if (v.is_string()) {
      fields.emplace_back(key, dev::ControlValue::string(v.get<std::string>()));
    } else if (v.is_number()) {
      fields.emplace_back(key, dev::ControlValue::of_number(v.get<double>()));
    } else {
      fields.emplace_back(key, dev::ControlValue::other(json_kind(v)));
    }
  }
  return dev::parse_event(fields);
}

std::optional<int> run_dfs1_commands(const Dfs1CommandState& state) {
  return run_dfs1_commands(state, std::cout, std::cerr);
}

}  // namespace ibs::cli
