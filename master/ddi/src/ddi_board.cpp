#include "ibs/master/ddi_board.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "ibs/ddi.h"
#include "ibs/phoenix/ibs_util.h"

namespace ibs::master {

namespace {

std::string hex4(unsigned v) {
  char b[16];
  std::snprintf(b, sizeof b, "%04XH", v & 0xFFFFU);
  return b;
}

// What a refused open means, for the user who must act on it.
std::string open_hint(std::int32_t code) {
  switch (code) {
    case ERR_INVLD_PARAM: return "not a node name: give the board as IBB<board>N<node> or IBETH<board>N<node>";
    case ERR_INVLD_BOARD_NUM: return "no such board";
    case ERR_INVLD_NODE_NUM: return "no such node on the board";
    case ERR_NODE_NOT_READY:
      return "the board is not ready (ibs's virtual board writes the reason to standard error)";
    default: return "the node does not open";
  }
}

std::string result_text(std::uint16_t result) {
  switch (result) {
    case RES_SERVICE_NOT_SUPPORTED: return "result " + hex4(result) + " (the board does not know the service)";
    case RES_WRONG_STATE: return "result " + hex4(result) + " (not in the board's state now)";
    case RES_INVALID_PARAMETER: return "result " + hex4(result) + " (a parameter the board refuses)";
    case RES_UNKNOWN_DEVICE: return "result " + hex4(result) + " (no such device)";
    default: return "result " + hex4(result);
  }
}

Error call_error(DdiCall call, const std::string& on, std::int32_t code, const std::string& hint) {
  return {ErrorCode::board_call_failed, ddi_call_text(call, on, code) + (hint.empty() ? "" : ": " + hint)};
}

// The device numbers a board gives its ring when it does not list them: a remote-bus device
// (and the ring's first) starts a segment at position 0, the local-bus devices behind it count on.
std::vector<std::uint16_t> numbers_of(const interbus::BusConfig& config) {
  std::vector<std::uint16_t> n;
  std::uint16_t segment = 0;
  std::uint16_t position = 0;
  for (std::size_t i = 0; i < config.devices.size(); ++i) {
    if (i == 0 || config.devices[i].bus == interbus::BusKind::remote) {
      ++segment;
      position = 0;
    } else {
      ++position;
    }
    n.push_back(static_cast<std::uint16_t>((segment << 8U) | position));
  }
  return n;
}

}  // namespace

DdiBoard::DdiBoard(std::string name, const DdiBoardOptions& options) : name_(std::move(name)), options_(options) {}

Expected<std::unique_ptr<DdiBoard>> DdiBoard::open(const interbus::BusConfig& config, const DdiBoardOptions& options) {
  std::unique_ptr<DdiBoard> b(new DdiBoard(options.board, options));
  if (const Error e = b->bring_up(config)) {
    b->close();  // nothing stays half-started (the first error is the one to tell)
    return e;
  }
  return Expected<std::unique_ptr<DdiBoard>>(std::move(b));
}

DdiBoard::~DdiBoard() { close(); }

Error DdiBoard::bring_up(const interbus::BusConfig& config) {
  // Both nodes, read and write.
  for (auto [suffix, handle] : {std::pair{"_D", &data_}, std::pair{"_M", &mailbox_}}) {
    const std::string node = name_ + suffix;
    IBDDIHND h = 0;
    const IBDDIRET rc = DDI_DevOpenNode(node.c_str(), DDI_RW, &h);
    if (rc != ERR_OK) return call_error(DdiCall::open_node, node, rc, open_hint(rc));
    *handle = h;
  }
  // Plug & play must be off: in it the board takes its configuration from the ring and the
  // process data is not the application's.
  auto pnp = service("Read_Value 2240H (plug & play mode)", {S_READ_VALUE, 2, 1, VAR_PLUG_AND_PLAY_MODE});
  if (!pnp) return pnp.error();
  const std::vector<Word>& v = pnp.value();
  if (v.size() < 6 || v[4] != VAR_PLUG_AND_PLAY_MODE) {
    return {ErrorCode::board_service_refused, "Read_Value 2240H (plug & play mode): the confirmation carries no value"};
  }
  if (v[5] != 0) {
    return {ErrorCode::board_plug_and_play,
            "the board " + name_ + " is in plug & play mode (Read_Value 2240H = " + std::to_string(v[5]) +
                "): it reads its configuration from the ring by itself and writes no application's process data; "
                "switch plug & play off on the board (Set_Value 2240H = 0) before a master runs on it"};
  }
  // The cycle time, where the board gives it (for reports and the loop's period).
  if (auto ct = service("Read_Value 2231H (cycle time)", {S_READ_VALUE, 2, 1, VAR_CYCLE_TIME_US});
      ct && ct.value().size() >= 6 && ct.value()[4] == VAR_CYCLE_TIME_US) {
    cycle_time_ = std::chrono::microseconds(ct.value()[5]);
  }
  auto activated = service("Activate_Configuration (0711H)", {S_ACTIVATE_CONFIGURATION, 0});
  if (!activated) return activated.error();
  std::vector<std::uint16_t> numbers;
  if (const Error e = compare(config, numbers)) return e;
  // From here a failure stops the data transfer again (close()), whether or not its confirmation
  // came: the board may run it all the same.
  started_ = true;
  auto started = service("Start_Data_Transfer (0701H)", {S_START_DATA_TRANSFER, 0});
  if (!started) return started.error();
  if (const Error e = running_without_errors()) return e;
  bus_ = std::make_unique<DdiBus>(data_, mailbox_, config, std::move(numbers), options_.bus);
  return {};
}

Error DdiBoard::compare(const interbus::BusConfig& config, std::vector<std::uint16_t>& numbers) {
  std::string names;
  for (const interbus::Device& d : config.devices) names += (names.empty() ? "" : ", ") + d.name;
  auto listed = service("Read_Configuration (0308H)", {S_READ_CONFIGURATION, 0}, true);
  if (!listed) return listed.error();
  if (listed.value()[2] == RES_SERVICE_NOT_SUPPORTED) {
    // A board without the service: its totals (DDI_GetInfo) against the master's.
    T_DDI_INFO info{};
    const IBDDIRET rc = DDI_GetInfo(data_, &info);
    if (rc != ERR_OK) return call_error(DdiCall::get_info, name_ + "_D", rc, "");
    if (info.deviceCount != config.devices.size() || info.inputBytes != config.in_words * 2 ||
        info.outputBytes != config.out_words * 2) {
      return {ErrorCode::board_configuration_mismatch,
              "configuration mismatch: the board's active configuration has " + std::to_string(info.deviceCount) +
                  " devices, " + std::to_string(info.inputBytes) + " input and " + std::to_string(info.outputBytes) +
                  " output bytes; the master's " + std::to_string(config.devices.size()) + " (" + names + "), " +
                  std::to_string(config.in_words * 2) + " and " + std::to_string(config.out_words * 2)};
    }
    numbers = numbers_of(config);
    return {};
  }
  // [count][(device number, ID code) ...] in ring order.
  const std::vector<Word>& c = listed.value();
  if (c[2] != RES_OK) return {ErrorCode::board_service_refused, "Read_Configuration (0308H): " + result_text(c[2])};
  const std::size_t count = c.size() >= 4 ? c[3] : 0;
  if (c.size() < 4 + 2 * count) {
    return {ErrorCode::board_service_refused, "Read_Configuration (0308H): the confirmation is shorter than its count"};
  }
  if (count != config.devices.size()) {
    return {ErrorCode::board_configuration_mismatch,
            "configuration mismatch: the board's active configuration has " + std::to_string(count) +
                " devices, the master's " + std::to_string(config.devices.size()) + " (" + names + ")"};
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint16_t number = c[4 + 2 * i];
    const interbus::IdCode board_id{c[5 + 2 * i]};
    const interbus::Device& d = config.devices[i];
    if (board_id.without_errors() != d.id.without_errors()) {
      return {ErrorCode::board_configuration_mismatch,
              "configuration mismatch at ring position " + std::to_string(i + 1) + " (device " + hex4(number) +
                  "): the board has ID code " + interbus::describe(board_id.without_errors()) + ", the master's '" +
                  d.name + "' " + interbus::describe(d.id.without_errors())};
    }
    numbers.push_back(number);
  }
  return {};
}

Error DdiBoard::running_without_errors() {
  // Once the bus runs, what the start left in the register (a refusal, the first cycles'
  // recovery) is confirmed away; RUN | ACTIVE | READY must remain, without BUS or PF.
  const auto deadline = std::chrono::steady_clock::now() + options_.service_deadline;
  T_IBS_DIAG d{};
  for (;;) {
    const IBDDIRET rc = GetIBSDiagnostic(data_, &d);
    if (rc != ERR_OK) return call_error(DdiCall::get_diagnostic, name_ + "_D", rc, "");
    if ((d.state & DIAG_CTRL) != 0) {
      return call_error(DdiCall::get_diagnostic, name_ + "_D", ERR_IBS_SYSFAIL,
                        "the board's controller failed (register " + hex4(d.state) + ")");
    }
    constexpr std::uint16_t kRunning = DIAG_RUN | DIAG_ACTIVE | DIAG_READY;
    if ((d.state & kRunning) == kRunning && (d.state & (DIAG_BUS | DIAG_PF | DIAG_USER)) == 0) return {};
    if (std::chrono::steady_clock::now() >= deadline) break;
    if ((d.state & (DIAG_BUS | DIAG_PF | DIAG_USER)) != 0) {
      auto confirmed = service("Confirm_Diagnostics (0760H)", {S_CONFIRM_DIAGNOSTICS, 0});
      if (!confirmed) return confirmed.error();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return {ErrorCode::board_no_answer,
          "the board did not run without errors within " + std::to_string(options_.service_deadline / 1ms) +
              " ms of Start_Data_Transfer: diagnostic status register " + hex4(d.state) + ", parameter register " +
              hex4(d.diagPara) + " (RUN | ACTIVE | READY = 00E0H without BUS 0004H, PF 0002H, USER 0001H)"};
}

Expected<std::vector<Word>> DdiBoard::service(const char* what, std::vector<Word> request, bool negative_too) {
  std::vector<std::uint8_t> bytes(DDI_MAX_MESSAGE);
  for (std::size_t k = 0; k < request.size(); ++k) {
    bytes[2 * k] = static_cast<std::uint8_t>(request[k] >> 8U);
    bytes[2 * k + 1] = static_cast<std::uint8_t>(request[k] & 0xFFU);
  }
  T_DDI_MXI_ACCESS s{0, static_cast<std::uint16_t>(2 * request.size()), 1, bytes.data()};
  IBDDIRET rc = DDI_MXI_SndMessage(mailbox_, &s);
  if (rc != ERR_OK) return call_error(DdiCall::send_message, name_ + "_M", rc, std::string("for ") + what);
  const auto confirmation = static_cast<Word>(request[0] | DDI_CONFIRMATION_BIT);
  const auto deadline = std::chrono::steady_clock::now() + options_.service_deadline;
  while (std::chrono::steady_clock::now() < deadline) {
    T_DDI_MXI_ACCESS r{0, static_cast<std::uint16_t>(bytes.size()), 0, bytes.data()};
    rc = DDI_MXI_RcvMessage(mailbox_, &r);
    if (rc == ERR_NO_MSG) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    if (rc != ERR_OK) return call_error(DdiCall::receive_message, name_ + "_M", rc, std::string("waiting for ") + what);
    std::vector<Word> w(r.msgLength / 2U);
    for (std::size_t k = 0; k < w.size(); ++k) w[k] = static_cast<Word>((bytes[2 * k] << 8U) | bytes[2 * k + 1]);
    if (w.size() < 3 || w[0] != confirmation) continue;  // an indication, or someone else's
    if (w[2] != RES_OK && !negative_too) return Error{ErrorCode::board_service_refused, std::string(what) + ": " + result_text(w[2])};
    return w;
  }
  return Error{ErrorCode::board_no_answer, std::string(what) + ": no confirmation within " +
                                               std::to_string(options_.service_deadline / 1ms) + " ms"};
}

void DdiBoard::attach(MasterLoop& loop) {
  for (std::size_t i = 0; i < loop.size() && i < loop.config().devices.size(); ++i) {
    if (pcp::MailboxClient* c = bus_->pcp_client(i)) loop.driver(i).use_pcp_client(*c);
  }
}

Error DdiBoard::close() {
  if (closed_) return {};
  closed_ = true;
  Error first;
  if (started_ && !(bus_ && bus_->failed())) {
    auto stopped = service("Stop_Data_Transfer (0702H)", {S_STOP_DATA_TRANSFER, 0});
    if (!stopped) first = stopped.error();
  }
  for (auto [suffix, handle] : {std::pair{"_M", &mailbox_}, std::pair{"_D", &data_}}) {
    if (*handle == 0) continue;
    const IBDDIRET rc = DDI_DevCloseNode(*handle);
    *handle = 0;
    if (rc != ERR_OK && !first) first = call_error(DdiCall::close_node, name_ + suffix, rc, "");
  }
  return first;
}

bool stop_drives(MasterLoop& loop, Bus& bus, interbus::ProcessImage& image, const std::function<Time()>& next_cycle,
                 const StopOptions& options) {
  using drivecom::State;
  const auto powered = [](std::optional<State> s) { return s == State::enabled || s == State::on; };
  // Safe: the power stage off and nothing under way that keeps it on.
  const auto safe = [](std::optional<State> s) {
    return !(s == State::enabled || s == State::on || s == State::emergency_stop_active ||
             s == State::fault_response_active);
  };
  struct Plan {
    bool ramp = false;   // let come to rest, then SHUTDOWN
    bool shut = false;   // SHUTDOWN sent
    double from = 0.0;   // the speed it came from
  };
  std::vector<Plan> plan(loop.size());
  Time t = next_cycle();
  const Time ramp_end = t + options.ramp;
  const Time end = ramp_end + options.settle;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    devices::DeviceDriver& d = loop.driver(i);
    const drivecom::Report& r = d.sequencer().report();
    if (powered(r.state_seen) && r.phase != drivecom::Phase::failed) {
      plan[i].ramp = true;
      plan[i].from = std::max(std::fabs(d.reference()), std::fabs(d.actual()));
      d.set_reference(0.0);
    } else {
      d.sequencer().request_block_power(t);  // resets no fault
    }
  }
  for (;;) {
    loop.cycle(bus, image, t);
    bool all = true;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      devices::DeviceDriver& d = loop.driver(i);
      const drivecom::Report& r = d.sequencer().report();
      Plan& p = plan[i];
      if (p.ramp && !p.shut) {
        const bool rest = std::fabs(d.actual()) <= 0.01 * p.from + 0.1;
        if (rest || t >= ramp_end || !powered(r.state_seen) || r.phase == drivecom::Phase::failed) {
          p.shut = true;
          // SHUTDOWN only to a drive still on and not failed: a request would reset a fault.
          if (powered(r.state_seen) && r.phase != drivecom::Phase::failed) {
            d.sequencer().request(drivecom::Target::ready, t);
          } else {
            d.sequencer().request_block_power(t);
          }
        }
      }
      const bool done = (!p.ramp || p.shut) && safe(r.state_seen);
      all = all && done;
    }
    if (all || t >= end) return all;
    t = next_cycle();
  }
}

}  // namespace ibs::master
