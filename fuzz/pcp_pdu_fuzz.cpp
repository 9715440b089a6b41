// PMS message decoding of the PCP channel (pcp/pdu.hpp, docs/pcp.md "Messages") from arbitrary
// bytes: requests as the servo reads them, responses as the master reads them, the header, the
// object description, the administrative byte, data-type values, and the explanations for logs.
//
// Asserts:
// - decode_header accepts exactly the sizes 6..134 whose count word gives the size, and reads
//   code, count, InvokeID and CR from their places;
// - a request or response the decoder accepts has a valid header, encodes again, and what it
//   encodes to decodes and encodes to the same bytes (nothing is lost or invented between the
//   decoder and the encoder);
// - an object description that decodes encodes to the same description;
// - decode_admin accepts exactly the bytes of odd parity that are not the invalid control code,
//   and encode_admin gives the same byte back;
// - a value decodes only from exactly size_of(type) bytes and encodes back to them;
// - explain_pdu and explain_frame never fail and say something.
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/explain.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/pcp/pdu.hpp"

namespace {

using namespace ibs;
using namespace ibs::pcp;
using ibs::fuzz::fail;

std::string hex(std::span<const std::uint8_t> b) {
  std::string s;
  for (const std::uint8_t x : b) {
    char t[4];
    std::snprintf(t, sizeof t, "%02X", x);
    s += t;
  }
  return s;
}

template <typename Message>
void round_trip(std::span<const std::uint8_t> in, const char* what) {
  Message m;
  const PduError e = decode(in, m);
  if (e != PduError::none) return;
  PduHeader h;
  if (decode_header(in, h) != PduError::none) fail(std::string(what) + " decoded from a bad header: " + hex(in));
  Pdu first;
  if (!encode(m, first)) fail(std::string(what) + " decoded but does not encode: " + hex(in));
  Message again;
  const PduError e2 = decode(first.view(), again);
  if (e2 != PduError::none) {
    fail(std::string(what) + " " + hex(in) + " encodes to " + hex(first.view()) + ", which does not decode (" +
         std::string(to_string(e2)) + ")");
  }
  Pdu second;
  if (!encode(again, second) || second.size != first.size ||
      !std::equal(first.bytes.begin(), first.bytes.begin() + static_cast<std::ptrdiff_t>(first.size), second.bytes.begin())) {
    fail(std::string(what) + " " + hex(in) + " encodes to " + hex(first.view()) + ", which decodes and encodes to " +
         hex(second.view()));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> in(data, size);

  // The header.
  PduHeader h;
  const PduError he = decode_header(in, h);
  const bool size_ok = size >= kMinPduSize && size <= kMaxPduSize &&
                       size == 4U + 2U * ((static_cast<std::size_t>(data[2]) << 8U) | data[3]);
  if ((he == PduError::none) != size_ok) {
    fail("decode_header says " + std::string(to_string(he)) + " for " + std::to_string(size) + " bytes " + hex(in));
  }
  if (he == PduError::none &&
      (h.code != ((data[0] << 8U) | data[1]) || h.count != ((data[2] << 8U) | data[3]) || h.invoke_id != data[4] ||
       h.cr != data[5])) {
    fail("decode_header read the wrong fields of " + hex(in));
  }

  round_trip<RequestPdu>(in, "request");
  round_trip<ResponsePdu>(in, "response");

  ObjectDescription d;
  if (decode(in, d)) {
    std::array<std::uint8_t, kObjectDescriptionSize> b{};
    const std::size_t n = encode(d, b);
    ObjectDescription d2;
    if (n == 0 || !decode(std::span<const std::uint8_t>(b.data(), n), d2) || !(d2 == d)) {
      fail("object description " + hex(in) + " does not survive encoding");
    }
  }

  for (const std::uint8_t x : in.first(std::min<std::size_t>(size, 8))) {
    const auto a = decode_admin(x);
    const bool odd = std::popcount(static_cast<unsigned>(x)) % 2 == 1;
    const bool invalid_control = ((x >> 5U) & 3U) == 0 && ((x >> 3U) & 3U) == 3;
    if (a.has_value() != (odd && !invalid_control)) {
      fail("decode_admin(" + std::to_string(x) + ") " + (a ? "accepts" : "refuses") + " it");
    }
    if (a && encode_admin(*a) != x) fail("encode_admin(decode_admin(" + std::to_string(x) + ")) is " + std::to_string(encode_admin(*a)));
  }

  if (size >= 1) {
    const std::uint8_t code = data[0];
    if (const auto t = data_type_from_code(code)) {
      const auto bytes = in.subspan(1);
      const auto v = decode(*t, bytes);
      if (v.has_value() != (bytes.size() == size_of(*t))) fail("a value of type " + std::string(to_string(*t)) + " from " + std::to_string(bytes.size()) + " bytes");
      if (v) {
        std::array<std::uint8_t, kMaxValueSize> b{};
        const std::size_t n = encode(*v, b);
        if (n != bytes.size() || !std::equal(bytes.begin(), bytes.end(), b.begin())) fail("a value does not encode back: " + hex(in));
        const auto back = value_from_signed_raw(*t, signed_raw(*v));
        if (!back || !(*back == *v)) fail("signed_raw / value_from_signed_raw do not round-trip " + hex(in));
      }
    }
  }

  if (explain_pdu(in).empty()) fail("explain_pdu says nothing for " + hex(in));
  std::vector<Word> words;
  for (std::size_t i = 0; i + 1 < size && words.size() < 4; i += 2) words.push_back(static_cast<Word>(data[i] << 8U | data[i + 1]));
  if (explain_frame(words, Direction::to_server).empty() || explain_frame(words, Direction::to_client).empty()) {
    fail("explain_frame says nothing for " + hex(in));
  }
  return 0;
}
