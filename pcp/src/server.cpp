#include "ibs/pcp/server.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ibs::pcp {

Duration LatencyModel::processing(double workload) const {
  const double w = std::clamp(workload, 0.0, 1.0);
  const auto span = static_cast<double>((processing_max - processing_min).count());
  return processing_min + Duration(static_cast<Duration::rep>(std::llround(w * span)));
}

LatencyModel LatencyModel::for_channel(int channel_words) {
  LatencyModel m;
  switch (channel_words) {
    case 4:
      m.processing_min = 7ms;
      m.processing_max = 27ms;
      break;
    case 2:
      m.processing_min = 0ms;
      m.processing_max = 21ms;
      break;
    default:
      m.processing_min = 0ms;
      m.processing_max = 2ms;
      break;
  }
  return m;
}

LatencyModel LatencyModel::immediate() {
  LatencyModel m;
  m.processing_min = Duration::zero();
  m.processing_max = Duration::zero();
  return m;
}

namespace {

LinkConfig link_config(const ServerConfig& cfg) {
  LinkConfig l;
  l.channel_words = cfg.channel_words;
  l.direction = Direction::to_client;
  l.ack_timeout = cfg.link_ack_timeout;
  l.start_ready = cfg.start == StartMode::running;
  return l;
}

const ServerConfig& checked(const ServerConfig& cfg, std::span<const ParameterInfo> table) {
  detail::require<std::invalid_argument>(Server::validate(cfg, table));
  return cfg;
}

// Whether `number` is the parameter of a role the drive gave (0: none).
constexpr bool is(std::uint16_t number, std::uint16_t role) { return role != 0 && number == role; }

}  // namespace

Error Server::validate(const ServerConfig& cfg, std::span<const ParameterInfo> table) {
  if (!(cfg.workload >= 0.0 && cfg.workload <= 1.0)) {
    return {ErrorCode::channel_workload_out_of_range,
            "PCP server workload " + std::to_string(cfg.workload) + " is outside 0..1"};
  }
  if (cfg.latency && (cfg.latency->processing_min < Duration::zero() ||
                      cfg.latency->processing_max < cfg.latency->processing_min)) {
    return {ErrorCode::channel_latency_invalid,
            "PCP server latency: need 0 <= processing_min <= processing_max"};
  }
  if (Error e = ParameterStore::validate(table)) return e;
  return Link::validate(link_config(cfg));
}

Server::Server(const ServerConfig& cfg, std::span<const ParameterInfo> table)
    : cfg_(checked(cfg, table)),
      latency_(cfg.latency ? *cfg.latency : LatencyModel::for_channel(cfg.channel_words)),
      store_(table),
      link_(link_config(cfg)),
      workload_(cfg.workload) {
  store_.power_on();
  if (cfg.start == StartMode::power_on) set_serr_bits(drive::siof_mask(drive::SiofBit::power_on));
}

void Server::set_workload(double workload) {
  workload_ = std::clamp(workload, 0.0, 1.0);
}

std::uint8_t Server::serr() const {
  const auto v = store_.get(cfg_.roles.serr);
  return v ? static_cast<std::uint8_t>(v->raw & 0xFFU) : 0;
}

void Server::set_serr_bits(std::uint8_t bits) {
  store_.set(cfg_.roles.serr, static_cast<std::uint32_t>(serr() | bits));
}

void Server::power_on(Time now) {
  store_.power_on();  // an unfinished EEPROM save is lost: the EEPROM keeps the old value
  set_serr_bits(drive::siof_mask(drive::SiofBit::power_on));
  eeprom_pending_ = false;
  eeprom_busy_until_ = now;  // idle from now on
  download_active_ = false;
  dataset_checking_ = false;
  job_active_ = false;
  out_pending_ = false;
  associated_ = false;
  link_.abort();
}

void Server::drop_association() {
  associated_ = false;
  job_active_ = false;
  out_pending_ = false;
}

void Server::advance(Time now) {
  if (eeprom_pending_ && now >= eeprom_busy_until_) {
    store_.commit_eeprom(eeprom_number_, eeprom_value_);
    eeprom_pending_ = false;
    ++stats_.eeprom_saves;
  }
  if (dataset_checking_ && now >= dataset_done_at_) {
    // Every value was range-checked when written, so the dataset is plausible: SLOAD = 0.
    dataset_checking_ = false;
    store_.set(cfg_.roles.sload, 0);
  }
}

void Server::step(Time now, std::span<const Word> m2s, std::span<Word> s2m) {
  advance(now);
  const LinkEvents ev = link_.receive(now, m2s);
  if (ev.reset) {
    ++stats_.link_resets;
    drop_association();
  }
  if (link_.has_message()) {
    handle_message(now, link_.message());
    link_.release_message();
  }
  if (out_pending_ && now >= out_at_ && link_.can_send()) {
    if (link_.send(out_.view())) out_pending_ = false;
  }
  if (job_active_ && now >= job_at_ && !out_pending_) {
    execute(now);
    if (out_pending_ && now >= out_at_ && link_.can_send() && link_.send(out_.view()))
      out_pending_ = false;
  }
  link_.transmit(now, s2m);
}

void Server::queue_abort(AbortReason reason, std::uint8_t cr) {
  ResponsePdu r;
  r.kind = ResponsePdu::Kind::abort;
  r.cr = cr;
  r.reason = reason;
  drop_association();
  if (encode(r, out_)) {
    out_pending_ = true;
    out_is_report_ = false;
    out_at_ = Time{};
    ++stats_.aborts_sent;
  }
}

void Server::handle_message(Time now, std::span<const std::uint8_t> msg) {
  RequestPdu req;
  const PduError e = decode(msg, req);
  if (e != PduError::none) {
    PduHeader h;
    queue_abort(AbortReason::protocol, decode_header(msg, h) == PduError::none ? h.cr : 0);
    return;
  }
  if (req.service == ServiceCode::abort) {
    ++stats_.aborts_received;
    drop_association();
    return;
  }
  if (job_active_ || (out_pending_ && !out_is_report_)) {
    // One outstanding request per communication reference: a second one breaks the protocol.
    // (A queued Information Report is the servo's own message and no reason to refuse.)
    queue_abort(AbortReason::protocol, req.cr);
    return;
  }
  if (!associated_ && req.service != ServiceCode::initiate) {
    queue_abort(AbortReason::not_initiated, req.cr);
    return;
  }
  ++stats_.requests;
  job_ = req;
  job_active_ = true;
  job_at_ = now + latency_.processing(workload_);
}

PcpError Server::do_read(ResponsePdu& r) {
  const ParameterInfo* p = find_by_index(store_.table(), job_.index);
  if (p == nullptr) return errors::kObjectDoesNotExist;
  if (job_.subindex != 0) return errors::kInvalidSubindex;
  const Value v = *store_.get(p->number);
  std::array<std::uint8_t, kMaxValueSize> b{};
  const std::size_t n = encode(v, b);
  r.data.assign(std::span<const std::uint8_t>(b.data(), n));
  // Seed 000, 6 and 9.2: reading 85-SERR clears it. Read errors never enter SERR (6.1).
  if (p->number == cfg_.roles.serr) store_.set(cfg_.roles.serr, 0);
  return {};
}

PcpError Server::do_write(Time now, Duration& extra_delay) {
  const ParameterInfo* p = find_by_index(store_.table(), job_.index);
  // Checks from the most to the least specific; each failure also sets its SERR bit (seed 000,
  // 9.2), which then refuses every further write until 85-SERR is read (seed 000, 6).
  if (p == nullptr) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::no_parameter));
    return errors::kObjectDoesNotExist;
  }
  if (job_.subindex != 0) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::no_parameter));
    return errors::kInvalidSubindex;
  }
  if (!p->writable()) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::no_change));
    return errors::kNoAccess;
  }
  const auto v = decode(p->type, job_.data.view());
  if (!v) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::invalid_value));
    return errors::kDataLength;
  }
  const std::uint32_t lo = ParameterStore::to_raw(*p, p->min);
  const std::uint32_t hi = ParameterStore::to_raw(*p, p->max);
  if (compare(p->type, v->raw, hi) > 0) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::invalid_value));
    return errors::kValueTooHigh;
  }
  if (compare(p->type, v->raw, lo) < 0) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::invalid_value));
    return errors::kValueTooLow;
  }
  const std::int64_t number = signed_raw(*v);
  // Seed 000, 11.4: the master writes only -1 (begin) and -2 (end); 0.. are the servo's answers.
  if (is(p->number, cfg_.roles.sload) && number >= 0) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::invalid_value));
    return errors::kValueTooHigh;
  }
  if (serr() != 0) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::no_change));
    return errors::kNotExecutableNow;
  }
  if (is(p->number, cfg_.roles.sload) &&
      (running_ || (number == drive::kDownloadEnd && !download_active_) || dataset_checking_)) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::no_change));
    return errors::kNotExecutableNow;  // seed 000, 11.4: "only when the system is in a stillstand"
  }
  if (p->category == Category::eeprom && eeprom_busy(now)) {
    set_serr_bits(drive::siof_mask(drive::SiofBit::eeprom_busy));
    return errors::kNotExecutableNow;  // seed 000, 3: repeat until the value is accepted
  }

  store_.set(p->number, v->raw);
  if (p->category == Category::eeprom) {
    // Seed 000, 10.2.2: memory time = data width * 3 * 5 ms; RAM is valid at once.
    eeprom_pending_ = true;
    eeprom_number_ = p->number;
    eeprom_value_ = v->raw;
    eeprom_busy_until_ =
        now + latency_.eeprom_byte_time * static_cast<Duration::rep>(size_of(p->type));
  }
  const ParameterRoles& roles = cfg_.roles;
  if (is(p->number, roles.prog)) {
    if (number == drive::kLoadDefaults) {
      store_.factory_defaults();
      eeprom_pending_ = false;
      extra_delay = latency_.factory_defaults_time;
    }
    // 111 activates a new LUSTBUS baud rate (seed 000, 11.5): nothing to do on INTERBUS.
    store_.set(roles.prog, 0);  // a command, not a setting
  } else if (is(p->number, roles.plrdy)) {
    if (number == 1) ++plrdy_requests_;
  } else if (is(p->number, roles.sload)) {
    if (number == drive::kDownloadBegin) {
      download_active_ = true;
    } else {
      download_active_ = false;
      dataset_checking_ = true;
      dataset_done_at_ = now + latency_.dataset_check_time;
      store_.set(roles.sload, value_from_signed_raw(DataType::integer16, -1)->raw);
    }
  }
  return {};
}

void Server::execute(Time now) {
  job_active_ = false;
  ResponsePdu r;
  r.service = job_.service;
  r.invoke_id = job_.invoke_id;
  r.cr = job_.cr;
  PcpError err{};
  Duration extra_delay = Duration::zero();
  switch (job_.service) {
    case ServiceCode::initiate:
      r.kbl = cfg_.kbl;
      if (cfg_.password != 0 && job_.password != cfg_.password) {
        err = errors::kNoAccess;
      } else if (check_kbl(job_.kbl, cfg_.kbl) != KblMismatch::none) {
        err = errors::kServiceNotExecutable;
      } else {
        associated_ = true;
        cr_ = job_.cr;
      }
      break;
    case ServiceCode::read:
      err = do_read(r);
      break;
    case ServiceCode::write:
      err = do_write(now, extra_delay);
      break;
    case ServiceCode::get_ov: {
      const ParameterInfo* p = find_by_index(store_.table(), job_.index);
      if (p == nullptr) {
        err = errors::kObjectDoesNotExist;
      } else {
        std::array<std::uint8_t, kObjectDescriptionSize> b{};
        encode(describe(*p), b);
        r.data.assign(b);
      }
      break;
    }
    case ServiceCode::identify:
      r.identity = cfg_.identity;
      break;
    case ServiceCode::status:
      r.status.logical = 0;
      r.status.physical = fault_ ? 1 : 0;
      r.status.local_detail = serr();
      break;
    case ServiceCode::abort:
    case ServiceCode::information_report:
      return;
  }
  r.positive = err == PcpError{};
  r.error = err;
  if (r.positive) {
    ++stats_.positive;
  } else {
    ++stats_.negative;
  }
  if (encode(r, out_)) {
    out_pending_ = true;
    out_is_report_ = false;
    out_at_ = now + extra_delay;
  }
}

bool Server::information_report(std::uint16_t number) {
  const auto v = store_.get(number);
  if (!associated_ || job_active_ || out_pending_ || !v) return false;
  ResponsePdu r;
  r.kind = ResponsePdu::Kind::information_report;
  r.cr = cr_;
  r.index = index_of(number);
  std::array<std::uint8_t, kMaxValueSize> b{};
  r.data.assign(std::span<const std::uint8_t>(b.data(), encode(*v, b)));
  if (!encode(r, out_)) return false;
  out_pending_ = true;
  out_is_report_ = true;
  out_at_ = Time{};
  return true;
}

}  // namespace ibs::pcp
