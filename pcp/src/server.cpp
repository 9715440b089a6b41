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

LatencyModel LatencyModel::immediate() {
  LatencyModel m;
  m.processing_min = Duration::zero();
  m.processing_max = Duration::zero();
  return m;
}

namespace {

LatencyModel latency_of(const ServerConfig& cfg) {
  if (cfg.latency) return *cfg.latency;
  if (cfg.latency_for != nullptr) return cfg.latency_for(cfg.channel_words);
  return LatencyModel{};
}

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

Server::Server(const ServerConfig& cfg, ServedParameters& served)
    : cfg_(checked(cfg, served.table())),
      latency_(latency_of(cfg)),
      served_(&served),
      link_(link_config(cfg)),
      workload_(cfg.workload),
      processing_(latency_.processing(workload_)) {}

void Server::set_workload(double workload) {
  workload_ = std::clamp(workload, 0.0, 1.0);
  processing_ = latency_.processing(workload_);
}

void Server::power_on(Time now) {
  (void)now;
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

void Server::receive(Time now, std::span<const Word> m2s) {
  const LinkEvents ev = link_.receive(now, m2s);
  if (ev.reset) {
    ++stats_.link_resets;
    drop_association();
  }
}

void Server::cycle(Time now, std::span<const Word> m2s, std::span<Word> s2m) {
  receive(now, m2s);
  link_.transmit(now, s2m);
}

void Server::step(Time now, std::span<const Word> m2s, std::span<Word> s2m) {
  served_->advance(now);
  receive(now, m2s);
  serve(now);
  link_.transmit(now, s2m);
}

void Server::sample(Time now) {
  served_->advance(now);
  serve(now);
}

void Server::serve(Time now) {
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
  // Decoded straight into job_, without a copy: job_ is read only while job_active_, and every way
  // below that does not make the request the job drops the job (drop_association, queue_abort).
  RequestPdu& req = job_;
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
  job_active_ = true;
  job_at_ = now + processing_;  // docs/pcp.md, "Latency model"
}

PcpError Server::do_read(Time now, ResponsePdu& r) {
  Value v{};
  const PcpError e = served_->read(now, job_.index, job_.subindex, v);
  if (e != PcpError{}) return e;
  std::array<std::uint8_t, kMaxValueSize> b{};
  const std::size_t n = encode(v, b);
  r.data.assign(std::span<const std::uint8_t>(b.data(), n));
  return {};
}

void Server::execute(Time now) {
  job_active_ = false;
  if (job_.service == ServiceCode::read) {
    // A Read's confirmation (INTERBUS manual 4.2) in a member kept for Read confirmations only, rather
    // than a fresh ResponsePdu that clears its ~250 bytes on every request: only a Read
    // confirmation's fields are ever written to it (InvokeID, CR, the result, the data), and the
    // last value's bytes are cleared before the next one, so it always equals a fresh one.
    ResponsePdu& r = read_answer_;
    r.invoke_id = job_.invoke_id;
    r.cr = job_.cr;
    r.data.clear_zero_tail();
    answer(r, do_read(now, r), now);
    return;
  }
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
    case ServiceCode::read:  // above
      break;
    case ServiceCode::write: {
      const WriteAnswer a = served_->write(now, job_.index, job_.subindex, job_.data.view());
      err = a.error;
      extra_delay = a.confirm_after;
      break;
    }
    case ServiceCode::get_ov: {
      const ParameterInfo* p = find_by_index(served_->table(), job_.index);
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
      r.status.physical = served_->fault() ? 1 : 0;
      r.status.local_detail = served_->status_detail();
      break;
    case ServiceCode::abort:
    case ServiceCode::information_report:
      return;
  }
  answer(r, err, now + extra_delay);
}

void Server::answer(ResponsePdu& r, PcpError err, Time at) {
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
    out_at_ = at;
  }
}

bool Server::information_report(std::uint16_t number) {
  const auto v = served_->value(number);
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
