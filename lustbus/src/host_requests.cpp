// The requests a host runs and the outcomes it reports, as values: their names (to_string), the
// CODEs a request is built from (parameter_code, text_code), the builders of the LUSTBUS manual's requests and
// procedures (6.1, 6.2, 4.2, 5.2, 11.3, 11.4, 11.6) and the text of an outcome. The host that runs
// them is host.cpp.
#include "ibs/lustbus/host.hpp"

#include <string>

#include "ibs/lustbus/siof.hpp"

namespace ibs::lustbus {

std::string_view to_string(RequestKind k) {
  switch (k) {
    case RequestKind::enquiry:
      return "enquiry";
    case RequestKind::select:
      return "select";
    case RequestKind::broadcast:
      return "broadcast";
    case RequestKind::scan:
      return "scan";
    case RequestKind::download:
      return "download";
    case RequestKind::indexed_text:
      return "indexed_text";
    case RequestKind::block_transfer:
      return "block_transfer";
  }
  return "?";
}

std::string_view to_string(OutcomeKind k) {
  switch (k) {
    case OutcomeKind::value:
      return "value";
    case OutcomeKind::acknowledged:
      return "acknowledged";
    case OutcomeKind::sent:
      return "sent";
    case OutcomeKind::nak:
      return "nak";
    case OutcomeKind::no_answer:
      return "no_answer";
    case OutcomeKind::bad_answer:
      return "bad_answer";
    case OutcomeKind::scan:
      return "scan";
    case OutcomeKind::downloaded:
      return "downloaded";
    case OutcomeKind::download_refused:
      return "download_refused";
    case OutcomeKind::download_rejected:
      return "download_rejected";
    case OutcomeKind::download_timeout:
      return "download_timeout";
    case OutcomeKind::aborted:
      return "aborted";
  }
  return "?";
}

std::string_view to_string(SubmitError e) {
  switch (e) {
    case SubmitError::none:
      return "none";
    case SubmitError::queue_full:
      return "queue full";
    case SubmitError::invalid_address:
      return "invalid address";
    case SubmitError::invalid_request:
      return "invalid request";
  }
  return "?";
}

std::string_view to_string(HostState s) {
  switch (s) {
    case HostState::idle:
      return "idle";
    case HostState::pausing:
      return "pausing";
    case HostState::sending:
      return "sending";
    case HostState::awaiting:
      return "awaiting";
    case HostState::receiving:
      return "receiving";
    case HostState::draining:
      return "draining";
    case HostState::turnaround:
      return "turnaround";
    case HostState::closing:
      return "closing";
  }
  return "?";
}

std::string describe(const Outcome& o) {
  std::string s(to_string(o.kind));
  if (o.kind == OutcomeKind::value) s += " " + std::string(o.value.view());
  if (o.answer_error != AnswerError::none) s += ", " + std::string(to_string(o.answer_error));
  if (o.siof) s += ", 85-SIOF " + describe_siof(*o.siof);
  if (o.kind == OutcomeKind::download_rejected) {
    s += ", first invalid parameter " + std::to_string(o.rejected_parameter);
  }
  if (o.kind == OutcomeKind::download_refused) s += ", step " + std::to_string(o.failed_step);
  if (o.kind == OutcomeKind::scan) s += ", " + std::to_string(o.scan.count) + " devices";
  return s;
}

std::optional<Code> parameter_code(Family f, unsigned parameter, bool description) {
  if (f == Family::standard) return vf_code(parameter, description ? VfSpecifier::description : VfSpecifier::value);
  return mc_code(description ? McCodeKind::description : McCodeKind::value, parameter);
}

std::string_view device_kind(Family f) { return f == Family::standard ? "inverter" : "servo"; }

Request enquiry(Address a, const Code& c) {
  Request r;
  r.kind = RequestKind::enquiry;
  r.address = a;
  r.code = c;
  return r;
}
Request select(Address a, const Code& c, const Value& v) {
  Request r;
  r.kind = RequestKind::select;
  r.address = a;
  r.code = c;
  r.value = v;
  return r;
}
Request broadcast(const Code& c, const Value& v) {
  Request r = select(kAddressBroadcast, c, v);
  r.kind = RequestKind::broadcast;
  return r;
}
Request network_scan() {
  Request r;
  r.kind = RequestKind::scan;
  return r;
}
std::optional<Code> text_code(Family f, unsigned parameter) {
  if (f != Family::enhanced) return std::nullopt;  // 2.4.1 has no text CODEs
  return mc_code(McCodeKind::substitution_text, parameter);
}

Request download(const DownloadProcedure& p, Address a, std::span<const Assignment> records) {
  Request r;
  r.kind = RequestKind::download;
  r.address = a;
  r.records = records;
  r.download = &p;
  return r;
}

Request block_transfer_request(const BlockTransferProcedure& p, Address a,
                               std::string_view user_data) {
  Request r;
  r.kind = RequestKind::block_transfer;
  r.address = a;
  r.code = p.code;
  r.block_transfer = &p;
  const auto v = Value::from(user_data);
  r.value = v.value_or(Value{});
  // A user data the VALUE cannot hold, or longer than the device takes: refused by submit().
  r.unfit = !v || user_data.size() > p.max_user_data;
  return r;
}

Request indexed_text_request(const IndexedTextProcedure& p, Address a, std::uint16_t parameter,
                             std::uint32_t index) {
  Request r;
  r.kind = RequestKind::indexed_text;
  r.address = a;
  r.parameter = parameter;
  r.text_index = index;
  r.indexed_text = &p;
  return r;
}

}  // namespace ibs::lustbus
