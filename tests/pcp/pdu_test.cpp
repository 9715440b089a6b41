// PMS message layouts (public-facts.md, PCP; docs/pcp.md, "Messages"): word-exact vectors.
#include "ibs/pcp/pdu.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace ibs::pcp {
namespace {

using namespace ibs::devices::mc6000;

std::vector<Word> words_of(const Pdu& p) {
  std::vector<Word> w;
  for (std::size_t i = 0; i + 1 < p.size; i += 2)
    w.push_back(make_word(p.bytes[i], p.bytes[i + 1]));
  return w;
}

std::vector<std::uint8_t> bytes_of(const std::vector<Word>& words) {
  std::vector<std::uint8_t> b;
  for (const Word w : words) {
    b.push_back(high_byte(w));
    b.push_back(low_byte(w));
  }
  return b;
}

RequestPdu request(ServiceCode s) {
  RequestPdu r;
  r.service = s;
  r.invoke_id = 7;
  r.cr = 2;
  return r;
}

ResponsePdu confirmation(ServiceCode s) {
  ResponsePdu r;
  r.service = s;
  r.invoke_id = 7;
  r.cr = 2;
  return r;
}

TEST(Pdu, ClearZeroTailGivesAFreshDataBytesForEverySize) {
  // clear_zero_tail() zeros only the first size bytes, by 8-byte stores: for a DataBytes filled
  // by assign() from fresh, or emptied so before, of every size, the result is a fresh one.
  DataBytes d;
  for (int round = 0; round < 2; ++round) {
    for (std::size_t n = 0; n <= kMaxDataSize; ++n) {
      std::vector<std::uint8_t> v(n);
      for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>(0x80U | (i + n));
      ASSERT_TRUE(d.assign(v));
      d.clear_zero_tail();
      EXPECT_EQ(d.size, 0U) << n;
      EXPECT_EQ(d.data, DataBytes{}.data) << "size " << n;
    }
  }
}

TEST(Pdu, ReadRequestFollowsThePublicLayout) {
  RequestPdu r = request(ServiceCode::read);
  r.index = 0x5D97;  // 407-IBSTU (INTERBUS manual 4.2.1)
  Pdu p;
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x0081, 0x0003, 0x0702, 0x5D97, 0x0000}));
  RequestPdu back;
  ASSERT_EQ(decode(p.view(), back), PduError::none);
  EXPECT_EQ(back.service, ServiceCode::read);
  EXPECT_EQ(back.invoke_id, 7);
  EXPECT_EQ(back.cr, 2);
  EXPECT_EQ(back.index, 0x5D97);
  EXPECT_EQ(back.subindex, 0);
}

TEST(Pdu, ReadConfirmationsPositiveAndNegative) {
  ResponsePdu r = confirmation(ServiceCode::read);
  const std::array<std::uint8_t, 2> v{0x12, 0x34};
  r.data.assign(v);
  Pdu p;
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x8081, 0x0004, 0x0702, 0x0000, 0x0002, 0x1234}));
  const std::array<std::uint8_t, 1> one{0x05};
  r.data.assign(one);
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x8081, 0x0004, 0x0702, 0x0000, 0x0001, 0x0500}));
  ResponsePdu back;
  ASSERT_EQ(decode(p.view(), back), PduError::none);
  EXPECT_TRUE(back.positive);
  EXPECT_EQ(back.data.size, 1U);
  EXPECT_EQ(back.data.data[0], 0x05);

  ResponsePdu n = confirmation(ServiceCode::read);
  n.positive = false;
  n.error = errors::kObjectDoesNotExist;
  ASSERT_TRUE(encode(n, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x8081, 0x0003, 0x0702, 0x0607, 0x0000}));
  ASSERT_EQ(decode(p.view(), back), PduError::none);
  EXPECT_FALSE(back.positive);
  EXPECT_EQ(back.error, errors::kObjectDoesNotExist);
}

TEST(Pdu, WriteRequestCarriesSubindexAndLengthThenData) {
  RequestPdu r = request(ServiceCode::write);
  r.index = 0x5DA0;  // 416-SCTL1
  const std::array<std::uint8_t, 2> v{0x00, 0x01};
  r.data.assign(v);
  Pdu p;
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x0082, 0x0004, 0x0702, 0x5DA0, 0x0002, 0x0001}));
  const std::array<std::uint8_t, 4> q16{0x00, 0x84, 0x26, 0x66};
  r.data.assign(q16);
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(words_of(p),
            (std::vector<Word>{0x0082, 0x0005, 0x0702, 0x5DA0, 0x0004, 0x0084, 0x2666}));
}

TEST(Pdu, WriteConfirmations) {
  Pdu p;
  ASSERT_TRUE(encode(confirmation(ServiceCode::write), p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x8082, 0x0002, 0x0702, 0x0000}));
  ResponsePdu n = confirmation(ServiceCode::write);
  n.positive = false;
  n.error = errors::kValueTooHigh;
  ASSERT_TRUE(encode(n, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x8082, 0x0003, 0x0702, 0x0800, 0x0031}));
}

TEST(Pdu, InitiateCarriesPasswordAccessGroupsAndTheKbl) {
  RequestPdu r = request(ServiceCode::initiate);
  r.invoke_id = 0;
  r.kbl = kDefaultClientKbl;
  Pdu p;
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x008B, 0x0008, 0x0002, 0x0000, 0x0000, 0x0086, 0x0086,
                                            0x0403, 0x0000, 0x0000}));
  ResponsePdu c = confirmation(ServiceCode::initiate);
  c.invoke_id = 0;
  c.kbl = ibs::devices::mc6000::kKbl;
  ASSERT_TRUE(encode(c, p));
  // INTERBUS manual 4.2.2: server for Get-OV long (byte 4), Read and Write (byte 5), Info Report (6).
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x808B, 0x0007, 0x0002, 0x0000, 0x0086, 0x0086, 0x0000,
                                            0x0004, 0x0304}));
  c.positive = false;
  c.error = errors::kServiceNotExecutable;
  ASSERT_TRUE(encode(c, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x808B, 0x0008, 0x0002, 0x0800, 0x0000, 0x0086, 0x0086,
                                            0x0000, 0x0004, 0x0304}));
  ResponsePdu back;
  ASSERT_EQ(decode(p.view(), back), PduError::none);
  EXPECT_FALSE(back.positive);
  EXPECT_EQ(back.kbl, ibs::devices::mc6000::kKbl) << "the negative confirmation reports sizes and services";
}

TEST(Pdu, AbortIsUnconfirmedAndCarriesItsReason) {
  RequestPdu r = request(ServiceCode::abort);
  r.reason = AbortReason::kbl_mismatch;
  Pdu p;
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x088D, 0x0002, 0x0002, 0x0003}));
  ResponsePdu back;
  ASSERT_EQ(decode(p.view(), back), PduError::none);
  EXPECT_EQ(back.kind, ResponsePdu::Kind::abort);
  EXPECT_EQ(back.reason, AbortReason::kbl_mismatch);
}

TEST(Pdu, GetOvIdentifyStatusLayouts) {
  RequestPdu g = request(ServiceCode::get_ov);
  g.index = 0x5D97;
  Pdu p;
  ASSERT_TRUE(encode(g, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x0088, 0x0002, 0x0702, 0x5D97}));
  ASSERT_TRUE(encode(request(ServiceCode::identify), p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x0087, 0x0001, 0x0702}));
  ASSERT_TRUE(encode(request(ServiceCode::status), p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x0086, 0x0001, 0x0702}));

  ResponsePdu s = confirmation(ServiceCode::status);
  s.status = {0, 1, 0x0041};
  ASSERT_TRUE(encode(s, p));
  EXPECT_EQ(words_of(p), (std::vector<Word>{0x8086, 0x0004, 0x0702, 0x0000, 0x0001, 0x0041}));

  ResponsePdu i = confirmation(ServiceCode::identify);
  i.identity = {Name::from("Lust"), Name::from("MC6000"), Name::from("PCP 2.0")};
  ASSERT_TRUE(encode(i, p));
  EXPECT_EQ(words_of(p),
            (std::vector<Word>{0x8087, 0x000C, 0x0702, 0x0000, 0x044C, 0x7573, 0x7406, 0x4D43,
                               0x3630, 0x3030, 0x0750, 0x4350, 0x2032, 0x2E30}));
  ResponsePdu back;
  ASSERT_EQ(decode(p.view(), back), PduError::none);
  EXPECT_EQ(back.identity, i.identity);
}

TEST(Pdu, ObjectDescriptionRoundTrips) {
  const ParameterInfo* p = find_parameter(ibs::devices::mc6000::kParameters, kIbstu);
  ASSERT_NE(p, nullptr);
  const ObjectDescription d = describe(*p);
  std::array<std::uint8_t, kObjectDescriptionSize> b{};
  ASSERT_EQ(encode(d, b), kObjectDescriptionSize);
  EXPECT_EQ(b[0], 0x5D);
  EXPECT_EQ(b[1], 0x97);
  EXPECT_EQ(b[3], static_cast<std::uint8_t>(DataType::usign16));
  EXPECT_EQ(b[5], '1');  // RAM control value (LUSTBUS manual 11.2.1)
  EXPECT_EQ(b[20], 'I');
  EXPECT_EQ(b[25], 0);
  ObjectDescription back;
  ASSERT_TRUE(decode(b, back));
  EXPECT_EQ(back, d);
  EXPECT_EQ(back.name.view(), "IBSTU");
  b[5] = '7';
  EXPECT_FALSE(decode(b, back));
}

TEST(Pdu, DecodeErrorsAreNamed) {
  RequestPdu r;
  EXPECT_EQ(decode(bytes_of({0x0081, 0x0001}), r), PduError::too_short);
  EXPECT_EQ(decode(bytes_of({0x0081, 0x0004, 0x0702, 0x5D97, 0x0000}), r),
            PduError::count_mismatch);
  EXPECT_EQ(decode(bytes_of({0x0083, 0x0001, 0x0702}), r), PduError::unknown_service);
  EXPECT_EQ(decode(bytes_of({0x0081, 0x0002, 0x0702, 0x5D97}), r), PduError::malformed);
  EXPECT_EQ(decode(bytes_of({0x0081, 0x0003, 0x0702, 0x5D97, 0x0001}), r), PduError::malformed)
      << "the read request's low byte is zero";
  EXPECT_EQ(decode(bytes_of({0x0082, 0x0004, 0x0702, 0x5DA0, 0x0004, 0x0001}), r),
            PduError::malformed)
      << "length says 4 bytes, 2 follow";
  std::vector<std::uint8_t> big(kMaxPduSize + 2, 0);
  EXPECT_EQ(decode(big, r), PduError::too_long);
  ResponsePdu c;
  EXPECT_EQ(decode(bytes_of({0x0081, 0x0003, 0x0702, 0x5D97, 0x0000}), c),
            PduError::unknown_service)
      << "a request is not a confirmation";
  EXPECT_EQ(decode(bytes_of({0x8081, 0x0004, 0x0702, 0x0607, 0x0000, 0x0000}), c),
            PduError::malformed);
  EXPECT_EQ(std::string(to_string(PduError::count_mismatch)), "size does not match the count word");
}

TEST(Pdu, WriteDataUpToThePduLimit) {
  RequestPdu r = request(ServiceCode::write);
  std::vector<std::uint8_t> data(kMaxDataSize, 0xAB);
  ASSERT_TRUE(r.data.assign(data));
  Pdu p;
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(p.size, kMaxPduSize);
  data.push_back(0);
  EXPECT_FALSE(r.data.assign(data));
}

TEST(Kbl, CheckNamesTheMismatch) {
  EXPECT_EQ(check_kbl(kDefaultClientKbl, ibs::devices::mc6000::kKbl), KblMismatch::none);
  Kbl small = kDefaultClientKbl;
  small.max_pdu_receiving = 64;  // a Lenze-sized buffer (public-facts.md)
  EXPECT_EQ(check_kbl(small, ibs::devices::mc6000::kKbl), KblMismatch::server_sends_too_much);
  Kbl server = ibs::devices::mc6000::kKbl;
  server.max_pdu_receiving = 64;
  EXPECT_EQ(check_kbl(kDefaultClientKbl, server), KblMismatch::client_sends_too_much);
  Kbl put = kDefaultClientKbl;
  put.services.client(kSvcPutOv);
  EXPECT_EQ(check_kbl(put, ibs::devices::mc6000::kKbl), KblMismatch::service_not_supported);
  Kbl tiny = kDefaultClientKbl;
  tiny.max_pdu_sending = 4;
  EXPECT_EQ(check_kbl(tiny, ibs::devices::mc6000::kKbl), KblMismatch::pdu_size_out_of_range);
}

TEST(Pdu, ExplainNamesServiceAndParameter) {
  RequestPdu r = request(ServiceCode::read);
  r.index = 0x5D97;
  Pdu p;
  ASSERT_TRUE(encode(r, p));
  EXPECT_EQ(explain_pdu(p.view()), "0081 Read.req, InvokeID 7, CR 2: index 5D97H (parameter 407)");
  ResponsePdu n = confirmation(ServiceCode::write);
  n.positive = false;
  n.error = errors::kValueTooLow;
  ASSERT_TRUE(encode(n, p));
  EXPECT_EQ(
      explain_pdu(p.view()),
      "8082 Write.conf, InvokeID 7, CR 2: negative, class 8 code 0 additional 32H (value too low)");
}

}  // namespace
}  // namespace ibs::pcp
