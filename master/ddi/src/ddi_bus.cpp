#include "ibs/master/ddi_bus.hpp"

#include <algorithm>
#include <cstdio>

#include "ibs/ddi.h"
#include "ibs/phoenix/ibs_util.h"

namespace ibs::master {

// The board's PCP indications, as the mailbox client knows them.
static_assert(pcp::mailbox::kAbortIndication == S_PCP_ABORT_IND);
static_assert(pcp::mailbox::kInformationReportIndication == S_PCP_INFO_REPORT_IND);

namespace {

constexpr std::uint16_t kRunning = DIAG_RUN | DIAG_ACTIVE | DIAG_READY;
constexpr std::uint16_t confirmed_code(std::uint16_t request) {
  return static_cast<std::uint16_t>(request | DDI_CONFIRMATION_BIT);
}
// DDIUserID of the adapter's own firmware services; a PCP request carries 100H | CR.
constexpr std::uint16_t kServiceUser = 0x0001;

}  // namespace

std::string_view to_string(DdiCall c) {
  switch (c) {
    case DdiCall::open_node: return "DDI_DevOpenNode";
    case DdiCall::close_node: return "DDI_DevCloseNode";
    case DdiCall::read_write_data: return "DDI_DTI_ReadWriteData";
    case DdiCall::read_data: return "DDI_DTI_ReadData";
    case DdiCall::write_data: return "DDI_DTI_WriteData";
    case DdiCall::send_message: return "DDI_MXI_SndMessage";
    case DdiCall::receive_message: return "DDI_MXI_RcvMessage";
    case DdiCall::get_diagnostic: return "GetIBSDiagnostic";
    case DdiCall::get_info: return "DDI_GetInfo";
  }
  return "?";
}

std::string_view ddi_return_name(std::int32_t code) {
  switch (code) {
    case ERR_OK: return "ERR_OK";
    case ERR_INVLD_BOARD_NUM: return "ERR_INVLD_BOARD_NUM";
    case ERR_INVLD_NODE_NUM: return "ERR_INVLD_NODE_NUM";
    case ERR_INVLD_NODE_HD: return "ERR_INVLD_NODE_HD";
    case ERR_INVLD_PERM: return "ERR_INVLD_PERM";
    case ERR_NODE_NOT_READY: return "ERR_NODE_NOT_READY";
    case ERR_INVLD_PARAM: return "ERR_INVLD_PARAM";
    case ERR_AREA_EXCDED: return "ERR_AREA_EXCDED";
    case ERR_INVLD_DATA_CONS: return "ERR_INVLD_DATA_CONS";
    case ERR_MSG_TO_LONG: return "ERR_MSG_TO_LONG";
    case ERR_NO_MSG: return "ERR_NO_MSG";
    case ERR_NO_MORE_MBX: return "ERR_NO_MORE_MBX";
    case ERR_SVR_TIMEOUT: return "ERR_SVR_TIMEOUT";
    case ERR_AVR_TIMEOUT: return "ERR_AVR_TIMEOUT";
    case ERR_IBS_SYSFAIL: return "ERR_IBS_SYSFAIL";
    case ERR_DATA_TIMEOUT: return "ERR_DATA_TIMEOUT";
    case ERR_IB_STOPPED: return "ERR_IB_STOPPED";
    default: return "unknown return code";
  }
}

std::string ddi_call_text(DdiCall call, std::string_view on, std::int32_t code) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "%04XH", static_cast<unsigned>(code) & 0xFFFFU);
  std::string s(to_string(call));
  if (!on.empty()) s += "(" + std::string(on) + ")";
  return s + ": " + std::string(ddi_return_name(code)) + " (" + hex + ")";
}

std::string_view to_string(BoardEvent::Kind k) {
  switch (k) {
    case BoardEvent::Kind::bus_error: return "bus-error";
    case BoardEvent::Kind::bus_ok: return "bus-ok";
    case BoardEvent::Kind::peripheral_fault: return "peripheral-fault";
    case BoardEvent::Kind::peripheral_ok: return "peripheral-ok";
    case BoardEvent::Kind::segment_off: return "segment-off";
    case BoardEvent::Kind::segment_on: return "segment-on";
    case BoardEvent::Kind::sysfail: return "sysfail";
    case BoardEvent::Kind::call_failed: return "call-failed";
    case BoardEvent::Kind::service_refused: return "service-refused";
    case BoardEvent::Kind::user_error: return "user-error";
  }
  return "?";
}

DdiBus::DdiBus(std::int32_t data_node, std::int32_t mailbox_node, interbus::BusConfig config,
               std::vector<std::uint16_t> device_numbers, const DdiBusOptions& options)
    : data_(data_node),
      mailbox_(mailbox_node),
      config_(std::move(config)),
      numbers_(std::move(device_numbers)),
      options_(options),
      in_bytes_(config_.in_words * 2),
      out_bytes_(config_.out_words * 2) {
  const std::size_t n = config_.devices.size();
  numbers_.resize(n);
  links_.resize(n);
  pf_.assign(n, false);
  switched_off_.assign(n, false);
  clients_.resize(n);
  client_of_cr_.fill(-1);
  std::uint8_t cr = 2;  // the board's numbering: the PCP devices in ring order from 2
  for (std::size_t i = 0; i < n; ++i) {
    if (config_.devices[i].pcp_words == 0) continue;
    pcp::MailboxConfig c;
    c.communication_reference = cr;
    c.request_timeout = options_.pcp_timeout;
    clients_[i] = std::make_unique<pcp::MailboxClient>(c);
    client_of_cr_[cr] = static_cast<std::int16_t>(i);
    ++cr;
  }
}

pcp::MailboxClient* DdiBus::pcp_client(std::size_t i) noexcept { return i < clients_.size() ? clients_[i].get() : nullptr; }

bool DdiBus::switch_segment(std::size_t i, bool on) noexcept {
  if (i >= numbers_.size() || (numbers_[i] & 0xFFU) != 0) return false;
  segment_request_ = std::pair{i, on};
  return true;
}

void DdiBus::clear_events() noexcept { event_count_ = 0; }

void DdiBus::log(BoardEvent e) noexcept {
  if (event_count_ == events_.size()) {
    ++lost_events_;
    return;
  }
  events_[event_count_++] = e;
}

std::optional<std::size_t> DdiBus::position_of(std::uint16_t number) const noexcept {
  for (std::size_t i = 0; i < numbers_.size(); ++i) {
    if (numbers_[i] == number) return i;
  }
  return std::nullopt;
}

void DdiBus::lose_every_device(interbus::ProcessImage& image, Time now, DdiCall call, std::int32_t code) noexcept {
  // The bus is gone: every device delivers nothing, as a lost device does on the simulator
  // (0000H with a module error): the drivers stop asking and no drive is enabled again by itself.
  if (!failed_) {
    failed_ = true;
    BoardEvent e;
    e.kind = code == ERR_IBS_SYSFAIL ? BoardEvent::Kind::sysfail : BoardEvent::Kind::call_failed;
    e.at = now;
    e.code = code;
    e.call = call;
    log(e);
  }
  std::fill_n(image.in.begin(), config_.in_words, Word{0});
  for (LinkState& l : links_) l = LinkState{true, true};
}

Exchange DdiBus::exchange(interbus::ProcessImage& image, Time now) noexcept {
  ++exchanges_;
  if (failed_) {
    lose_every_device(image, now, DdiCall::read_write_data, ERR_IBS_SYSFAIL);
    return {true, links_};
  }
  // One consistent access: the drivers' outputs go, the devices' inputs come.
  for (std::size_t k = 0; k < config_.out_words; ++k) {
    out_buffer_[2 * k] = static_cast<std::uint8_t>(image.out[k] >> 8U);
    out_buffer_[2 * k + 1] = static_cast<std::uint8_t>(image.out[k] & 0xFFU);
  }
  T_DDI_DTI_ACCESS w{static_cast<std::uint16_t>(out_bytes_), 0, DDI_WORD, out_buffer_.data()};
  T_DDI_DTI_ACCESS r{static_cast<std::uint16_t>(in_bytes_), 0, DDI_WORD, in_buffer_.data()};
  IBDDIRET rc = ERR_OK;
  DdiCall call = DdiCall::read_write_data;
  if (out_bytes_ > 0 && in_bytes_ > 0) {
    rc = DDI_DTI_ReadWriteData(data_, &w, &r);
  } else if (in_bytes_ > 0) {
    call = DdiCall::read_data;
    rc = DDI_DTI_ReadData(data_, &r);
  } else if (out_bytes_ > 0) {
    call = DdiCall::write_data;
    rc = DDI_DTI_WriteData(data_, &w);
  }
  if (rc != ERR_OK) {
    lose_every_device(image, now, call, rc);
    return {true, links_};
  }
  read_diagnostics(now);
  if (failed_) {
    lose_every_device(image, now, DdiCall::get_diagnostic, ERR_IBS_SYSFAIL);
    return {true, links_};
  }
  pump_mailbox(now);
  // Valid: the board runs its data transfer and saw no bus error (BUS stays set until the
  // adapter's Confirm_Diagnostics finds its cause gone).
  const bool valid = (diag_status_ & kRunning) == kRunning && (diag_status_ & (DIAG_BUS | DIAG_CTRL)) == 0;
  if (valid) {
    ++valid_exchanges_;
    for (std::size_t k = 0; k < config_.in_words; ++k) {
      image.in[k] = static_cast<Word>((in_buffer_[2 * k] << 8U) | in_buffer_[2 * k + 1]);
    }
  }
  for (std::size_t i = 0; i < links_.size(); ++i) {
    links_[i].data_valid = !switched_off_[i];
    links_[i].module_error = pf_[i] && !switched_off_[i];
    if (valid && switched_off_[i]) {
      for (Word& x : interbus::in_slice(image, config_.devices[i])) x = 0;
    }
  }
  return {valid, links_};
}

void DdiBus::set_peripheral_fault(std::size_t i, bool on, Time now) noexcept {
  if (i >= pf_.size() || pf_[i] == on) return;
  pf_[i] = on;
  BoardEvent e;
  e.kind = on ? BoardEvent::Kind::peripheral_fault : BoardEvent::Kind::peripheral_ok;
  e.at = now;
  e.device = i;
  e.number = numbers_[i];
  log(e);
}

void DdiBus::read_diagnostics(Time now) noexcept {
  T_IBS_DIAG d{};
  const IBDDIRET rc = GetIBSDiagnostic(data_, &d);
  if (rc != ERR_OK || (d.state & DIAG_CTRL) != 0) {
    failed_ = true;
    BoardEvent e;
    e.kind = rc == ERR_OK || rc == ERR_IBS_SYSFAIL ? BoardEvent::Kind::sysfail : BoardEvent::Kind::call_failed;
    e.at = now;
    e.code = rc == ERR_OK ? ERR_IBS_SYSFAIL : rc;
    e.call = DdiCall::get_diagnostic;
    log(e);
    return;
  }
  diag_status_ = d.state;
  diag_parameter_ = d.diagPara;
  const bool bus = (d.state & DIAG_BUS) != 0;
  if (bus != bus_error_) {
    bus_error_ = bus;
    log({bus ? BoardEvent::Kind::bus_error : BoardEvent::Kind::bus_ok, now, 0, 0, 0, DdiCall::get_diagnostic});
  }
  const bool bsa = (d.state & DIAG_BSA) != 0;
  if (bsa != bsa_) {
    bsa_ = bsa;
    // Which segment is the switch's own business (switch_segment): logged there.
    if (std::find(switched_off_.begin(), switched_off_.end(), true) == switched_off_.end()) {
      log({bsa ? BoardEvent::Kind::segment_off : BoardEvent::Kind::segment_on, now, 0, 0, 0,
           DdiCall::get_diagnostic});
    }
  }
  const bool user = (d.state & DIAG_USER) != 0;
  if (user && !user_) log({BoardEvent::Kind::user_error, now, 0, 0, d.diagPara, DdiCall::get_diagnostic});
  user_ = user;
  if ((d.state & DIAG_PF) != 0) {
    // The parameter register names the device of the first peripheral fault (unless USER has
    // put a service's result there); Get_Diag_Info names them all.
    if (!user) {
      if (const auto i = position_of(d.diagPara)) set_peripheral_fault(*i, true, now);
    }
  } else if (!bus) {
    // Gone, as far as a cycle with valid data can tell (during a bus error the board sees no
    // device's module error, so PF says nothing then).
    for (std::size_t i = 0; i < pf_.size(); ++i) set_peripheral_fault(i, false, now);
  }
}

bool DdiBus::send(std::span<const Word> words, std::uint16_t user_id, Time now) noexcept {
  const std::size_t n = std::min(words.size(), message_.size() / 2);
  for (std::size_t k = 0; k < n; ++k) {
    message_[2 * k] = static_cast<std::uint8_t>(words[k] >> 8U);
    message_[2 * k + 1] = static_cast<std::uint8_t>(words[k] & 0xFFU);
  }
  T_DDI_MXI_ACCESS a{0, static_cast<std::uint16_t>(2 * n), user_id, message_.data()};
  const IBDDIRET rc = DDI_MXI_SndMessage(mailbox_, &a);
  if (rc == ERR_OK) return true;
  // A full mailbox is a matter of the next cycle; anything else is worth a report (a SysFail
  // shows in the register of the next cycle).
  if (rc != ERR_NO_MORE_MBX) log({BoardEvent::Kind::call_failed, now, 0, 0, rc, DdiCall::send_message});
  return false;
}

void DdiBus::pump_mailbox(Time now) noexcept {
  // The cycle's firmware service: a segment switch asked for, else what the register calls for.
  if (service_ != Service::none && now - service_sent_ >= options_.service_timeout) service_ = Service::none;
  if (service_ == Service::none) {
    std::array<Word, 5> w{};
    std::size_t n = 0;
    Service next = Service::none;
    if (segment_request_) {
      const auto [head, on] = *segment_request_;
      w = {S_CONTROL_ACTIVE_CONFIGURATION, 3, static_cast<Word>(on ? CTRL_SWITCH_ON : CTRL_SWITCH_OFF), 1,
           numbers_[head]};
      n = 5;
      next = Service::segment;
    } else if ((diag_status_ & DIAG_PF) != 0 && !confirm_due_) {
      w = {S_GET_DIAG_INFO, 0};
      n = 2;
      next = Service::get_diag_info;
    } else if (confirm_due_ || (diag_status_ & (DIAG_BUS | DIAG_USER)) != 0) {
      w = {S_CONFIRM_DIAGNOSTICS, 0};
      n = 2;
      next = Service::confirm;
    }
    if (n > 0 && send({w.data(), n}, kServiceUser, now)) {
      service_ = next;
      service_sent_ = now;
    }
  }
  // The PCP devices' requests (an Abort first where one is due).
  for (const auto& c : clients_) {
    if (!c) continue;
    for (std::span<const Word> m = c->outgoing(); !m.empty(); m = c->outgoing()) {
      if (!send(m, static_cast<std::uint16_t>(0x0100U | c->config().communication_reference), now)) break;
      c->sent();
    }
  }
  // Everything the board has for us.
  for (std::size_t k = 0; k < kMaxReceivesPerCycle; ++k) {
    T_DDI_MXI_ACCESS a{0, static_cast<std::uint16_t>(message_.size()), 0, message_.data()};
    const IBDDIRET rc = DDI_MXI_RcvMessage(mailbox_, &a);
    if (rc == ERR_NO_MSG) break;
    if (rc != ERR_OK) {
      log({BoardEvent::Kind::call_failed, now, 0, 0, rc, DdiCall::receive_message});
      break;
    }
    const std::size_t n = std::min<std::size_t>(a.msgLength / 2U, words_.size());
    for (std::size_t i = 0; i < n; ++i) {
      words_[i] = static_cast<Word>((message_[2 * i] << 8U) | message_[2 * i + 1]);
    }
    dispatch({words_.data(), n}, now);
  }
}

void DdiBus::dispatch(std::span<const Word> m, Time now) noexcept {
  if (const auto cr = pcp::mailbox::communication_reference(m)) {
    const std::int16_t i = client_of_cr_[*cr];
    if (i >= 0) clients_[static_cast<std::size_t>(i)]->receive(now, m);
    return;
  }
  if (m.size() < 3) return;
  const std::uint16_t code = m[0];
  if (code == confirmed_code(S_GET_DIAG_INFO) || code == confirmed_code(S_CONFIRM_DIAGNOSTICS) ||
      code == confirmed_code(S_CONTROL_ACTIVE_CONFIGURATION)) {
    service_confirmed(m, now);
  }
  // Anything else answers a service someone else sent on the node: not the adapter's.
}

void DdiBus::service_confirmed(std::span<const Word> m, Time now) noexcept {
  const std::uint16_t code = m[0];
  const std::uint16_t result = m[2];
  if (result != RES_OK) log({BoardEvent::Kind::service_refused, now, 0, 0, result, DdiCall::receive_message});
  if (code == confirmed_code(S_GET_DIAG_INFO)) {
    if (service_ == Service::get_diag_info) service_ = Service::none;
    if (result != RES_OK || m.size() < 4) return;
    // [entries][(device number, code) ...]: the devices with a peripheral fault since the last
    // Confirm_Diagnostics; then the confirmation, to learn which of them are still faulty.
    const std::size_t entries = std::min<std::size_t>(m[3], (m.size() - 4) / 2);
    for (std::size_t i = 0; i < pf_.size(); ++i) {
      bool listed = false;
      for (std::size_t e = 0; e < entries; ++e) {
        listed = listed || (m[4 + 2 * e] == numbers_[i] && m[5 + 2 * e] == DIAG_CODE_MODULE_ERROR);
      }
      if (listed || !bus_error_) set_peripheral_fault(i, listed, now);
    }
    confirm_due_ = true;
  } else if (code == confirmed_code(S_CONFIRM_DIAGNOSTICS)) {
    if (service_ == Service::confirm) service_ = Service::none;
    confirm_due_ = false;
  } else if (service_ == Service::segment) {
    service_ = Service::none;
    const auto request = segment_request_;
    segment_request_.reset();
    if (result != RES_OK || !request) return;
    const auto [head, on] = *request;
    const std::uint16_t segment = numbers_[head] >> 8U;
    for (std::size_t i = head; i < numbers_.size() && (numbers_[i] >> 8U) == segment; ++i) {
      if (switched_off_[i] == !on) continue;
      switched_off_[i] = !on;
      log({on ? BoardEvent::Kind::segment_on : BoardEvent::Kind::segment_off, now, i, numbers_[i], 0,
           DdiCall::send_message});
    }
  }
}

}  // namespace ibs::master
