#include "firmware.hpp"

#include <algorithm>
#include <array>

#include "ibs/ddi.h"
#include "ibs/devices/mc6000/driver.hpp"

namespace ibs::ddi {

namespace {

// Abort indication reasons (ibs's codes, docs/ddi.md).
constexpr std::uint16_t kAbortTimeout = 1;
constexpr std::uint16_t kAbortLinkReset = 2;
constexpr std::uint16_t kAbortProtocol = 3;
constexpr std::uint16_t kAbortByDevice = 4;
constexpr std::uint16_t kAbortTransferStopped = 5;

// PCP refusals the board makes itself (public-facts.md, PCP error classes): a request the
// association or the bus cannot carry now, a communication reference nobody has.
constexpr pcp::PcpError kNoAssociation = pcp::errors::kServiceNotExecutable;
constexpr pcp::PcpError kBusyOrStopped = pcp::errors::kNotExecutableNow;
constexpr pcp::PcpError kUnknownCr{1, 2, 0};

std::uint16_t pcp_error_word(const pcp::PcpError& e) {
  return static_cast<std::uint16_t>((e.error_class << 8U) | e.error_code);
}

// Bytes into big-endian words, the last one padded with 0.
void push_bytes(std::vector<std::uint16_t>& w, std::span<const std::uint8_t> bytes) {
  for (std::size_t k = 0; k < bytes.size(); k += 2) {
    const std::uint8_t lo = k + 1 < bytes.size() ? bytes[k + 1] : 0;
    w.push_back(static_cast<std::uint16_t>((bytes[k] << 8U) | lo));
  }
}

}  // namespace

Firmware::Firmware(sim::Simulator& sim, const interbus::BusConfig& config, Duration cycle_time)
    : sim_(sim), config_(config), cycle_time_(cycle_time) {
  // Device numbers: a remote-bus device (or the ring's first) starts a segment at position 0,
  // the local-bus devices behind it count 1, 2, ...
  std::uint16_t segment = 0;
  std::uint16_t position = 0;
  for (std::size_t i = 0; i < config_.devices.size(); ++i) {
    const interbus::Device& d = config_.devices[i];
    if (i == 0 || d.bus == interbus::BusKind::remote) {
      ++segment;
      position = 0;
    } else {
      ++position;
    }
    numbers_.push_back(static_cast<std::uint16_t>((segment << 8U) | position));
    if (d.pcp_words > 0) {
      Cr c;
      c.device = i;
      c.cr = static_cast<std::uint8_t>(2 + crs_.size());
      crs_.push_back(std::move(c));
    }
  }
  pf_latched_.assign(config_.devices.size(), false);
  pf_now_.assign(config_.devices.size(), false);
  reset_clients(0);
  sim_.set_bus_running(false);  // the board starts READY: no configuration active, no data
}

Duration Firmware::pcp_timeout() const {
  // As ibs's own MC6000 driver: a one-word channel on a long ring needs many cycles per message.
  return std::max<Duration>(500ms, cycle_time_ * devices::Mc6000Driver::kTimeoutCycles);
}

void Firmware::reset_clients(std::uint16_t abort_reason) {
  for (Cr& c : crs_) {
    const bool had = c.client && (c.client->associated() || c.pending);
    if (had && abort_reason != 0) {
      const std::array<std::uint16_t, 2> p{c.cr, abort_reason};
      indicate(S_PCP_ABORT_IND, p);
    }
    pcp::ClientConfig cfg;
    cfg.channel_words = static_cast<int>(config_.devices[c.device].pcp_words);
    cfg.communication_reference = c.cr;
    cfg.request_timeout = pcp_timeout();
    c.client.emplace(cfg);
    c.pending = false;
  }
}

std::uint16_t Firmware::diag_status() const {
  std::uint16_t s = 0;
  if (sysfail_) return DIAG_CTRL;
  s |= DIAG_READY;
  if (active_) s |= DIAG_ACTIVE;
  if (running_) s |= DIAG_RUN;
  if (user_error_) s |= DIAG_USER;
  if (bus_error_) s |= DIAG_BUS;
  if (std::find(pf_latched_.begin(), pf_latched_.end(), true) != pf_latched_.end()) s |= DIAG_PF;
  if (any_switched_off()) s |= DIAG_BSA;
  return s;
}

bool Firmware::any_switched_off() const {
  for (std::size_t i = 0; i < config_.devices.size(); ++i) {
    if (sim_.switched_off(i)) return true;
  }
  return false;
}

void Firmware::cycle(interbus::ProcessImage& image, Time now, const master::Exchange& exchange) {
  ++cycles_;
  if (!running_) return;
  bus_error_now_ = !exchange.data_valid;
  if (bus_error_now_) {
    bus_error_ = true;
    diag_parameter_ = 0;  // a transmission error has no one device to name
  }
  for (std::size_t i = 0; i < config_.devices.size(); ++i) {
    const interbus::Device& d = config_.devices[i];
    const master::LinkState link = exchange.link(i);
    pf_now_[i] = exchange.data_valid && link.module_error;
    if (pf_now_[i] && !pf_latched_[i]) {
      pf_latched_[i] = true;
      diag_parameter_ = numbers_[i];
    }
    // Inputs: a valid cycle brings the device's words (zeros from a device with a module error
    // or switched off); an invalid one leaves the last ones.
    if (exchange.data_valid) {
      const auto in = interbus::in_slice(image, d);
      std::copy(in.begin(), in.end(), user_.in.begin() + static_cast<std::ptrdiff_t>(d.in.offset));
    }
  }
  std::copy(user_.out.begin(), user_.out.begin() + static_cast<std::ptrdiff_t>(config_.out_words), image.out.begin());
  if (start_confirmation_) {
    confirm(S_START_DATA_TRANSFER, *start_confirmation_, RES_OK);
    start_confirmation_.reset();
  }
  for (Cr& c : crs_) {
    const interbus::Device& d = config_.devices[c.device];
    c.client->step(now, interbus::pcp_in_slice(image, d), interbus::pcp_out_slice(image, d));
    pcp_results(c);
  }
}

void Firmware::restart(Time /*now*/) {
  // The scenario's master restart is the board's controller failing: SysFail until the nodes
  // are closed and opened again (the board starts anew).
  sysfail_ = true;
  start_confirmation_.reset();
  running_ = false;
  active_ = false;
  sim_.set_bus_running(false);
  reset_clients(0);
}

void Firmware::read_inputs(std::size_t address, std::span<std::uint8_t> dst) const {
  user_.read_bytes(interbus::Area::in, address, dst);
}

void Firmware::write_outputs(std::size_t address, std::span<const std::uint8_t> src) {
  user_.write_bytes(interbus::Area::out, address, src);
}

void Firmware::post(std::uint16_t type, std::uint16_t user_id, std::span<const std::uint16_t> words) {
  Message m;
  m.type = type;
  m.user_id = user_id;
  m.bytes.reserve(words.size() * 2);
  for (const std::uint16_t w : words) {
    m.bytes.push_back(static_cast<std::uint8_t>(w >> 8U));
    m.bytes.push_back(static_cast<std::uint8_t>(w & 0xFFU));
  }
  outbox_.push_back(std::move(m));
}

void Firmware::confirm(std::uint16_t code, std::uint16_t user_id, std::uint16_t result,
                       std::span<const std::uint16_t> more) {
  std::vector<std::uint16_t> w{static_cast<std::uint16_t>(code | DDI_CONFIRMATION_BIT),
                               static_cast<std::uint16_t>(1 + more.size()), result};
  w.insert(w.end(), more.begin(), more.end());
  post(DDI_MSG_CONFIRMATION, user_id, w);
  if (result != RES_OK) {
    user_error_ = true;
    diag_parameter_ = result;
  }
}

void Firmware::indicate(std::uint16_t code, std::span<const std::uint16_t> params) {
  std::vector<std::uint16_t> w{code, static_cast<std::uint16_t>(params.size())};
  w.insert(w.end(), params.begin(), params.end());
  post(DDI_MSG_INDICATION, 0, w);
}

Accept Firmware::request(std::span<const std::uint16_t> words, std::uint16_t user_id, Time now) {
  if (outbox_.size() >= kMailboxCapacity) return Accept::mailbox_full;
  const std::uint16_t code = words[0];
  if (code == S_PCP_READ || code == S_PCP_WRITE || code == S_PCP_GET_OV || code == S_PCP_INITIATE ||
      code == S_PCP_ABORT) {
    pcp_service(words, user_id, now);
  } else {
    service(words, user_id);
  }
  return Accept::ok;
}

std::optional<std::size_t> Firmware::segment_head(std::uint16_t number) const {
  if ((number & 0xFFU) != 0) return std::nullopt;  // only whole segments are switched
  for (std::size_t i = 0; i < numbers_.size(); ++i) {
    if (numbers_[i] == number) return i;
  }
  return std::nullopt;
}

void Firmware::set_segment(std::size_t head, bool off) {
  const std::uint16_t segment = numbers_[head] >> 8U;
  for (std::size_t i = head; i < numbers_.size() && (numbers_[i] >> 8U) == segment; ++i) {
    sim_.set_switched_off(i, off);
  }
}

void Firmware::stop_transfer(std::uint16_t abort_reason) {
  if (start_confirmation_) confirm(S_START_DATA_TRANSFER, *start_confirmation_, RES_OK);  // it did start
  start_confirmation_.reset();
  running_ = false;
  bus_error_now_ = false;
  std::fill(pf_now_.begin(), pf_now_.end(), false);
  sim_.set_bus_running(false);
  reset_clients(abort_reason);
}

void Firmware::service(std::span<const std::uint16_t> words, std::uint16_t user_id) {
  const std::uint16_t code = words[0];
  const std::span<const std::uint16_t> p = words.subspan(2);
  switch (code) {
    case S_CREATE_CONFIGURATION:
    case S_ACTIVATE_CONFIGURATION: {
      // The configuration is the scenario's ring (loaded with the board); Create reads it from
      // the ring anew, which switches every segment on. An optional parameter: frame 1.
      if (running_) return confirm(code, user_id, RES_WRONG_STATE);
      if (p.size() > 1 || (p.size() == 1 && p[0] != 1)) return confirm(code, user_id, RES_INVALID_PARAMETER);
      if (code == S_CREATE_CONFIGURATION) {
        for (std::size_t i = 0; i < numbers_.size(); ++i) sim_.set_switched_off(i, false);
      }
      active_ = true;
      const std::array<std::uint16_t, 1> count{static_cast<std::uint16_t>(config_.devices.size())};
      return confirm(code, user_id, RES_OK, count);
    }
    case S_START_DATA_TRANSFER:
      if (!p.empty()) return confirm(code, user_id, RES_INVALID_PARAMETER);
      if (!active_ || running_) return confirm(code, user_id, RES_WRONG_STATE);
      // Running from now (RUN in the register); confirmed when the first data cycle has brought
      // the devices' inputs (cycle()), so that what the application reads after it is theirs.
      running_ = true;
      sim_.set_bus_running(true);
      start_confirmation_ = user_id;
      return;
    case S_STOP_DATA_TRANSFER:
      if (!p.empty()) return confirm(code, user_id, RES_INVALID_PARAMETER);
      if (!running_) return confirm(code, user_id, RES_WRONG_STATE);
      stop_transfer(kAbortTransferStopped);
      return confirm(code, user_id, RES_OK);
    case S_READ_VALUE: {
      // [count][variable IDs]; confirmed with [count] and (ID, value) per variable: the layout a
      // public sample program reads (the first value as parameter 4, after result, count and ID;
      // docs/ddi.md, "Legacy headers").
      if (p.empty() || p[0] == 0 || p[0] != p.size() - 1) return confirm(code, user_id, RES_INVALID_PARAMETER);
      std::vector<std::uint16_t> values{p[0]};
      for (const std::uint16_t id : p.subspan(1)) {
        values.push_back(id);
        switch (id) {
          case VAR_DIAG_STATUS: values.push_back(diag_status()); break;
          case VAR_DIAG_PARAMETER: values.push_back(diag_parameter_); break;
          case VAR_DEVICE_COUNT: values.push_back(static_cast<std::uint16_t>(config_.devices.size())); break;
          // The configuration is the scenario's ring, never read in by plug & play: the mode is off,
          // so the application may write process data.
          case VAR_PLUG_AND_PLAY_MODE: values.push_back(0); break;
          case VAR_CYCLE_TIME_US:
            values.push_back(static_cast<std::uint16_t>(std::min<std::int64_t>(
                std::chrono::duration_cast<std::chrono::microseconds>(cycle_time_).count(), 0xFFFF)));
            break;
          default: return confirm(code, user_id, RES_INVALID_PARAMETER);
        }
      }
      return confirm(code, user_id, RES_OK, values);
    }
    case S_GET_DIAG_INFO: {
      // [entries][(device number, code) ...]: the devices with a peripheral fault since the last
      // Confirm_Diagnostics, and device 0 for a bus error.
      if (p.size() > 1) return confirm(code, user_id, RES_INVALID_PARAMETER);
      std::vector<std::uint16_t> list{0};
      if (bus_error_) list.insert(list.end(), {0, DIAG_CODE_TRANSMISSION});
      for (std::size_t i = 0; i < numbers_.size(); ++i) {
        if (pf_latched_[i]) list.insert(list.end(), {numbers_[i], DIAG_CODE_MODULE_ERROR});
      }
      list[0] = static_cast<std::uint16_t>((list.size() - 1) / 2);
      return confirm(code, user_id, RES_OK, list);
    }
    case S_READ_CONFIGURATION: {
      // [count][(device number, ID code) ...]: the active configuration in ring order, what a
      // master compares with its own before it writes process data (ibs's service, docs/ddi.md).
      if (!p.empty()) return confirm(code, user_id, RES_INVALID_PARAMETER);
      if (!active_) return confirm(code, user_id, RES_WRONG_STATE);
      std::vector<std::uint16_t> list{static_cast<std::uint16_t>(config_.devices.size())};
      for (std::size_t i = 0; i < numbers_.size(); ++i) list.insert(list.end(), {numbers_[i], config_.devices[i].id.raw});
      return confirm(code, user_id, RES_OK, list);
    }
    case S_CONFIRM_DIAGNOSTICS: {
      if (!p.empty()) return confirm(code, user_id, RES_INVALID_PARAMETER);
      // What is still there stays reported; the rest is forgotten.
      user_error_ = false;
      bus_error_ = bus_error_now_;
      diag_parameter_ = 0;
      for (std::size_t i = 0; i < numbers_.size(); ++i) {
        pf_latched_[i] = pf_now_[i];
        if (pf_now_[i] && diag_parameter_ == 0) diag_parameter_ = numbers_[i];
      }
      return confirm(code, user_id, RES_OK);
    }
    case S_CONTROL_ACTIVE_CONFIGURATION: {
      // [sub-command][count][device numbers]: whole segments, named by their first device.
      if (p.size() < 2 || p[1] == 0 || p[1] != p.size() - 2 || (p[0] != CTRL_SWITCH_OFF && p[0] != CTRL_SWITCH_ON)) {
        return confirm(code, user_id, RES_INVALID_PARAMETER);
      }
      if (!active_) return confirm(code, user_id, RES_WRONG_STATE);
      std::vector<std::size_t> heads;
      for (const std::uint16_t n : p.subspan(2)) {
        const auto h = segment_head(n);
        if (!h) return confirm(code, user_id, RES_UNKNOWN_DEVICE);
        heads.push_back(*h);
      }
      for (const std::size_t h : heads) set_segment(h, p[0] == CTRL_SWITCH_OFF);
      return confirm(code, user_id, RES_OK);
    }
    default:
      return confirm(code, user_id, RES_SERVICE_NOT_SUPPORTED);
  }
}

void Firmware::pcp_negative(const Cr& c, std::uint16_t code, const pcp::PcpError& e) {
  const std::array<std::uint16_t, 5> w{static_cast<std::uint16_t>(code | DDI_CONFIRMATION_BIT), 3,
                                       static_cast<std::uint16_t>((c.invoke_id << 8U) | c.cr), pcp_error_word(e),
                                       e.additional_code};
  post(DDI_MSG_CONFIRMATION, c.user_id, w);
}

void Firmware::pcp_service(std::span<const std::uint16_t> words, std::uint16_t user_id, Time now) {
  const std::uint16_t code = words[0];
  const std::span<const std::uint16_t> p = words.subspan(2);
  if (code == S_PCP_ABORT) {  // [CR] or [CR][reason]; unconfirmed
    if (p.empty() || p.size() > 2) return confirm(code, user_id, RES_INVALID_PARAMETER);
    for (Cr& c : crs_) {
      if (c.cr != (p[0] & 0xFFU)) continue;
      c.client->abort(now);
      c.pending = false;
      while (c.client->take_result()) {
      }
      return;
    }
    return confirm(code, user_id, RES_UNKNOWN_DEVICE);
  }
  // Initiate [id,CR][password][access groups]; Read [id,CR][index][subindex << 8];
  // Write [id,CR][index][subindex << 8 | length][data]; Get-OV [id,CR][index].
  if (p.empty()) return confirm(code, user_id, RES_INVALID_PARAMETER);
  Cr probe;
  probe.cr = static_cast<std::uint8_t>(p[0] & 0xFFU);
  probe.invoke_id = static_cast<std::uint8_t>(p[0] >> 8U);
  probe.user_id = user_id;
  auto it = std::find_if(crs_.begin(), crs_.end(), [&](const Cr& c) { return c.cr == probe.cr; });
  if (it == crs_.end()) return pcp_negative(probe, code, kUnknownCr);
  Cr& c = *it;
  const bool shape = (code == S_PCP_INITIATE && p.size() == 3) || (code == S_PCP_READ && p.size() == 3) ||
                     (code == S_PCP_GET_OV && p.size() == 2) ||
                     (code == S_PCP_WRITE && p.size() >= 3 && (p[2] & 0xFFU) > 0 &&
                      p.size() == 3 + ((p[2] & 0xFFU) + 1U) / 2U);
  if (!shape) return confirm(code, user_id, RES_INVALID_PARAMETER);
  if (c.pending || !running_) return pcp_negative(probe, code, kBusyOrStopped);
  const pcp::ParameterRef ref = pcp::ParameterRef::object(code == S_PCP_INITIATE ? 0 : p[1]);
  const auto subindex = static_cast<std::uint8_t>(code == S_PCP_INITIATE || code == S_PCP_GET_OV ? 0 : p[2] >> 8U);
  pcp::SubmitStatus s = pcp::SubmitStatus::invalid_argument;
  if (code == S_PCP_INITIATE) {
    s = c.client->initiate(now);
  } else if (code == S_PCP_GET_OV) {
    s = c.client->get_ov(now, ref);
  } else if (code == S_PCP_READ) {
    s = subindex == 0 ? c.client->read(now, ref) : c.client->read_subindex(now, ref, subindex);
  } else {
    std::vector<std::uint8_t> data;
    for (const std::uint16_t w : p.subspan(3)) {
      data.push_back(static_cast<std::uint8_t>(w >> 8U));
      data.push_back(static_cast<std::uint8_t>(w & 0xFFU));
    }
    data.resize(p[2] & 0xFFU);
    s = c.client->write_bytes(now, ref, data, subindex);
  }
  switch (s) {
    case pcp::SubmitStatus::accepted:
      c.pending = true;
      c.code = code;
      c.invoke_id = probe.invoke_id;
      c.user_id = user_id;
      return;
    case pcp::SubmitStatus::busy: return pcp_negative(probe, code, kBusyOrStopped);
    case pcp::SubmitStatus::not_initiated: return pcp_negative(probe, code, kNoAssociation);
    case pcp::SubmitStatus::invalid_argument: return pcp_negative(probe, code, pcp::errors::kDataLength);
  }
}

void Firmware::pcp_results(Cr& c) {
  while (auto report = c.client->take_information_report()) {
    std::vector<std::uint16_t> p{c.cr, report->index, static_cast<std::uint16_t>(report->data.size)};
    push_bytes(p, report->data.view());
    indicate(S_PCP_INFO_REPORT_IND, p);
  }
  while (auto r = c.client->take_result()) {
    if (!c.pending) continue;  // the result of a request the user aborted
    c.pending = false;
    const auto id_cr = static_cast<std::uint16_t>((c.invoke_id << 8U) | c.cr);
    std::vector<std::uint16_t> w{static_cast<std::uint16_t>(c.code | DDI_CONFIRMATION_BIT), 0, id_cr};
    switch (r->kind) {
      case pcp::ResultKind::ok:
        w.push_back(0);
        if (c.code == S_PCP_READ) {
          w.push_back(static_cast<std::uint16_t>(r->data.size));
          push_bytes(w, r->data.view());
        } else if (c.code == S_PCP_INITIATE) {
          w.insert(w.end(), {r->peer_kbl.max_pdu_sending, r->peer_kbl.max_pdu_receiving});
        } else if (c.code == S_PCP_GET_OV) {
          // The object description as the channel carried it (docs/pcp.md, 26 bytes).
          std::array<std::uint8_t, pcp::kObjectDescriptionSize> d{};
          const std::size_t n = pcp::encode(r->description, d);
          w.push_back(static_cast<std::uint16_t>(n));
          push_bytes(w, {d.data(), n});
        }
        break;
      case pcp::ResultKind::negative:
      case pcp::ResultKind::type_mismatch:
        w.insert(w.end(), {pcp_error_word(r->error), r->error.additional_code});
        break;
      case pcp::ResultKind::incompatible:
        // The server's KBL does not fit: the sizes it offers, as a negative Initiate.
        w.insert(w.end(), {pcp_error_word(pcp::errors::kServiceNotExecutable), 0, r->peer_kbl.max_pdu_sending,
                           r->peer_kbl.max_pdu_receiving});
        break;
      case pcp::ResultKind::aborted:
      case pcp::ResultKind::link_reset:
      case pcp::ResultKind::timeout:
      case pcp::ResultKind::protocol_error: {
        // The association is gone: no confirmation, an Abort indication instead.
        const std::uint16_t reason = r->kind == pcp::ResultKind::timeout      ? kAbortTimeout
                                     : r->kind == pcp::ResultKind::link_reset ? kAbortLinkReset
                                     : r->kind == pcp::ResultKind::protocol_error ? kAbortProtocol
                                                                                  : kAbortByDevice;
        const std::array<std::uint16_t, 2> ind{c.cr, reason};
        indicate(S_PCP_ABORT_IND, ind);
        continue;
      }
    }
    w[1] = static_cast<std::uint16_t>(w.size() - 2);
    post(DDI_MSG_CONFIRMATION, c.user_id, w);
  }
}

}  // namespace ibs::ddi
