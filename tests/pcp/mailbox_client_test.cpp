// The PCP client through a controller board's mailbox (pcp/mailbox_client.hpp): the messages it
// hands the board, word by word in the layouts of docs/ddi.md ("PCP over the mailbox"), and how
// it ends each request on the board's answers -- positive and negative confirmations, Abort
// indications, no confirmation (timeout), a confirmation for another invoke ID -- with the next
// transaction working after each.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/pcp/client.hpp"
#include "ibs/pcp/mailbox_client.hpp"

namespace ibs::pcp {
namespace {

using Words = std::vector<Word>;

constexpr std::uint8_t kCr = 2;

Words out(const MailboxClient& c) {
  const auto w = c.outgoing();
  return {w.begin(), w.end()};
}

Word id_cr(std::uint8_t invoke_id) { return static_cast<Word>((invoke_id << 8U) | kCr); }

class Mailbox : public ::testing::Test {
 protected:
  MailboxClient client{MailboxConfig{}};
  Time now{0};

  // Sends what waits, checks it, and hands `answer` back (when not empty).
  void exchange(const Words& expected, const Words& answer) {
    EXPECT_EQ(out(client), expected);
    client.sent();
    EXPECT_TRUE(out(client).empty());
    now += 2ms;
    if (!answer.empty()) client.receive(now, answer);
    client.step(now, {}, {});
  }
  // An association, as the board confirms it (the device's 134-byte KBL), with invoke ID 0.
  void associate() {
    ASSERT_EQ(client.initiate(now), SubmitStatus::accepted);
    exchange({0x008B, 3, id_cr(0), 0, 0}, {0x808B, 4, id_cr(0), 0, 134, 134});
    const Result* r = client.take_result_view();
    ASSERT_NE(r, nullptr);
    ASSERT_EQ(r->kind, ResultKind::ok);
    EXPECT_EQ(r->peer_kbl.max_pdu_sending, 134);
    EXPECT_TRUE(client.associated());
  }
  const Result& result() {
    const Result* r = client.take_result_view();
    EXPECT_NE(r, nullptr);
    static const Result none{};
    return r != nullptr ? *r : none;
  }
};

TEST_F(Mailbox, ReadsAndWritesInTheBoardsLayouts) {
  EXPECT_EQ(client.read(now, ParameterRef::number(406)), SubmitStatus::not_initiated);
  EXPECT_TRUE(out(client).empty());  // nothing goes for a refused submission
  associate();
  // 406-IBCNF, typed USIGN8: [id,CR][index][subindex << 8]; the confirmation [0][length][data].
  ASSERT_EQ(client.read(now, ParameterRef::number(406), DataType::usign8), SubmitStatus::accepted);
  EXPECT_TRUE(client.busy());
  EXPECT_EQ(client.read(now, ParameterRef::number(85)), SubmitStatus::busy);
  exchange({0x0081, 3, id_cr(1), 0x5C00 + 406, 0}, {0x8081, 4, id_cr(1), 0, 1, 0x0200});
  const Result& r = result();
  EXPECT_EQ(r.kind, ResultKind::ok);
  ASSERT_TRUE(r.value.has_value());
  EXPECT_EQ(r.value->raw, 2U);
  EXPECT_EQ(r.index, 0x5C00 + 406);
  // A Write of 409 = 100 (USIGN16): [subindex << 8 | length][data], confirmed with the result alone.
  ASSERT_EQ(client.write(now, ParameterRef::number(409), Value{DataType::usign16, 100}), SubmitStatus::accepted);
  exchange({0x0082, 4, id_cr(2), 0x5C00 + 409, 0x0002, 0x0064}, {0x8082, 2, id_cr(2), 0});
  EXPECT_EQ(result().kind, ResultKind::ok);
  // An odd length pads the last word.
  const std::array<std::uint8_t, 3> three{1, 2, 3};
  ASSERT_EQ(client.write_bytes(now, ParameterRef::object(0x6000), three, 4), SubmitStatus::accepted);
  exchange({0x0082, 5, id_cr(3), 0x6000, 0x0403, 0x0102, 0x0300}, {0x8082, 2, id_cr(3), 0});
  EXPECT_EQ(result().kind, ResultKind::ok);
  EXPECT_FALSE(client.busy());
  EXPECT_EQ(client.stats().confirmations, 4U);
}

TEST_F(Mailbox, DescribesAnObjectByGetOv) {
  associate();
  const ParameterInfo* info = find_parameter(devices::mc6000::kParameters, 406);
  ASSERT_NE(info, nullptr);
  std::array<std::uint8_t, kObjectDescriptionSize> d{};
  ASSERT_EQ(encode(describe(*info), d), d.size());
  Words conf{0x8088, 0, id_cr(1), 0, static_cast<Word>(d.size())};
  for (std::size_t i = 0; i < d.size(); i += 2) conf.push_back(static_cast<Word>((d[i] << 8U) | d[i + 1]));
  conf[1] = static_cast<Word>(conf.size() - 2);
  ASSERT_EQ(client.get_ov(now, ParameterRef::number(406)), SubmitStatus::accepted);
  exchange({0x0088, 2, id_cr(1), 0x5C00 + 406}, conf);
  const Result& r = result();
  EXPECT_EQ(r.kind, ResultKind::ok);
  EXPECT_EQ(r.description, describe(*info));
}

TEST_F(Mailbox, ANegativeConfirmationEndsTheRequestAndKeepsTheAssociation) {
  associate();
  ASSERT_EQ(client.write(now, ParameterRef::number(406), Value{DataType::usign8, 99}), SubmitStatus::accepted);
  exchange({0x0082, 4, id_cr(1), 0x5C00 + 406, 0x0001, 0x6300}, {0x8082, 3, id_cr(1), 0x0800, 0x0031});
  const Result& r = result();
  EXPECT_EQ(r.kind, ResultKind::negative);
  EXPECT_EQ(r.error, errors::kValueTooHigh);
  EXPECT_TRUE(client.associated());
  ASSERT_EQ(client.read(now, ParameterRef::number(406)), SubmitStatus::accepted);
  exchange({0x0081, 3, id_cr(2), 0x5C00 + 406, 0}, {0x8081, 4, id_cr(2), 0, 1, 0x0200});
  EXPECT_EQ(result().kind, ResultKind::ok);
}

TEST_F(Mailbox, AnAbortIndicationEndsTheRequestWithItsReason) {
  const std::array<std::pair<Word, ResultKind>, 5> reasons{{{1, ResultKind::timeout},
                                                            {2, ResultKind::link_reset},
                                                            {3, ResultKind::protocol_error},
                                                            {4, ResultKind::aborted},
                                                            {5, ResultKind::aborted}}};
  std::uint8_t id = 0;
  for (const auto& [reason, kind] : reasons) {
    ASSERT_EQ(client.initiate(now), SubmitStatus::accepted);
    exchange({0x008B, 3, id_cr(id), 0, 0}, {0x808B, 4, id_cr(id), 0, 134, 134});
    ASSERT_EQ(result().kind, ResultKind::ok);
    ++id;
    ASSERT_EQ(client.read(now, ParameterRef::number(85)), SubmitStatus::accepted);
    exchange({0x0081, 3, id_cr(id), 0x5C00 + 85, 0}, {0x408D, 2, kCr, reason});
    EXPECT_EQ(result().kind, kind) << "reason " << reason;
    EXPECT_FALSE(client.associated());
    EXPECT_TRUE(out(client).empty());  // the board ended it: no Abort of ours
    ++id;
  }
  EXPECT_EQ(client.stats().abort_indications, 5U);
}

TEST_F(Mailbox, WithoutAConfirmationTheRequestTimesOutAndTheNextWorks) {
  associate();
  ASSERT_EQ(client.read(now, ParameterRef::number(85), 100ms), SubmitStatus::accepted);
  exchange({0x0081, 3, id_cr(1), 0x5C00 + 85, 0}, {});
  for (int k = 0; k < 60 && client.busy(); ++k) {
    now += 2ms;
    client.step(now, {}, {});
  }
  const Result& r = result();
  EXPECT_EQ(r.kind, ResultKind::timeout);
  EXPECT_GE(r.completed_at - r.submitted_at, 100ms);
  EXPECT_FALSE(client.associated());
  // Abort for the CR, so that the board drops the request: [00,CR][reason 0].
  ASSERT_EQ(client.initiate(now), SubmitStatus::accepted);
  EXPECT_EQ(out(client), (Words{0x088D, 2, kCr, 0}));
  client.sent();
  // The old confirmation, come too late, answers nothing and ends nothing.
  EXPECT_EQ(out(client), (Words{0x008B, 3, id_cr(2), 0, 0}));
  client.sent();
  client.receive(now, Words{0x8081, 4, id_cr(1), 0, 1, 0x0100});
  EXPECT_TRUE(client.busy());
  EXPECT_EQ(client.stats().late_confirmations, 1U);
  client.receive(now, Words{0x808B, 4, id_cr(2), 0, 134, 134});
  EXPECT_EQ(result().kind, ResultKind::ok);
  ASSERT_EQ(client.read(now, ParameterRef::number(85)), SubmitStatus::accepted);
  exchange({0x0081, 3, id_cr(3), 0x5C00 + 85, 0}, {0x8081, 4, id_cr(3), 0, 1, 0x0100});
  EXPECT_EQ(result().kind, ResultKind::ok);
}

TEST_F(Mailbox, AConfirmationForAnUnknownInvokeIdIsAProtocolError) {
  associate();
  ASSERT_EQ(client.read(now, ParameterRef::number(85)), SubmitStatus::accepted);
  exchange({0x0081, 3, id_cr(1), 0x5C00 + 85, 0}, {0x8081, 4, id_cr(0x77), 0, 1, 0x0100});
  EXPECT_EQ(result().kind, ResultKind::protocol_error);
  EXPECT_FALSE(client.associated());
  EXPECT_EQ(out(client), (Words{0x088D, 2, kCr, 0}));
  client.sent();
  // A confirmation of another service for the request's own invoke ID, likewise.
  ASSERT_EQ(client.initiate(now), SubmitStatus::accepted);
  exchange({0x008B, 3, id_cr(2), 0, 0}, {0x8081, 4, id_cr(2), 0, 1, 0x0100});
  EXPECT_EQ(result().kind, ResultKind::protocol_error);
  client.sent();  // its Abort (the board had the Initiate)
  // The next transaction works.
  ASSERT_EQ(client.initiate(now), SubmitStatus::accepted);
  exchange({0x008B, 3, id_cr(3), 0, 0}, {0x808B, 4, id_cr(3), 0, 134, 134});
  EXPECT_EQ(result().kind, ResultKind::ok);
  ASSERT_EQ(client.read(now, ParameterRef::number(85)), SubmitStatus::accepted);
  exchange({0x0081, 3, id_cr(4), 0x5C00 + 85, 0}, {0x8081, 4, id_cr(4), 0, 1, 0x0100});
  EXPECT_EQ(result().kind, ResultKind::ok);
  EXPECT_EQ(client.stats().protocol_errors, 2U);
}

TEST_F(Mailbox, AbortEndsTheRequestAndTellsTheBoardOnlyWhatItKnows) {
  // A request the board never had: dropped, no Abort.
  ASSERT_EQ(client.initiate(now), SubmitStatus::accepted);
  client.abort(now);
  EXPECT_EQ(result().kind, ResultKind::aborted);
  EXPECT_TRUE(out(client).empty());
  // An association: Abort.
  client.abort(now);
  EXPECT_TRUE(out(client).empty());
  ASSERT_EQ(client.initiate(now), SubmitStatus::accepted);
  exchange({0x008B, 3, id_cr(1), 0, 0}, {0x808B, 4, id_cr(1), 0, 134, 134});
  EXPECT_EQ(result().kind, ResultKind::ok);
  ASSERT_EQ(client.read(now, ParameterRef::number(85)), SubmitStatus::accepted);
  client.sent();
  client.abort(now);
  EXPECT_EQ(result().kind, ResultKind::aborted);
  EXPECT_EQ(out(client), (Words{0x088D, 2, kCr, 0}));
}

TEST_F(Mailbox, ReportsAndRoutesByCommunicationReference) {
  EXPECT_EQ(mailbox::communication_reference(Words{0x8081, 4, 0x0103, 0, 1, 0}), 3);
  EXPECT_EQ(mailbox::communication_reference(Words{0x408D, 2, 4, 1}), 4);
  EXPECT_EQ(mailbox::communication_reference(Words{0x4085, 4, 2, 0x5C55, 1, 0}), 2);
  EXPECT_FALSE(mailbox::communication_reference(Words{0x8351, 4, 0, 1, 0x2240, 0}).has_value());  // Read_Value
  EXPECT_FALSE(mailbox::communication_reference(Words{0x8081, 1}).has_value());
  associate();
  client.receive(now, Words{0x4085, 4, kCr, 0x5C00 + 407, 2, 0x1234});
  const auto report = client.take_information_report();
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->index, 0x5C00 + 407);
  EXPECT_EQ(report->data.size, 2U);
  EXPECT_EQ(report->data.data[0], 0x12);
}

TEST_F(Mailbox, RefusesAReferenceBelowTwoAndNoTimeout) {
  MailboxConfig c;
  c.communication_reference = 1;
  EXPECT_EQ(MailboxClient::validate(c).code, ErrorCode::channel_reference_invalid);
  c.communication_reference = 2;
  c.request_timeout = Duration::zero();
  EXPECT_EQ(MailboxClient::validate(c).code, ErrorCode::channel_timeout_not_positive);
  EXPECT_THROW(MailboxClient{c}, std::invalid_argument);
}

// One interface for both carriers: what a driver calls.
TEST(ParameterClientInterface, BothClientsAreOne) {
  Client words{ClientConfig{}};
  MailboxClient board{MailboxConfig{}};
  for (ParameterClient* c : {static_cast<ParameterClient*>(&words), static_cast<ParameterClient*>(&board)}) {
    EXPECT_FALSE(c->associated());
    EXPECT_EQ(c->read(Time{0}, ParameterRef::number(85)), SubmitStatus::not_initiated);
    EXPECT_EQ(c->initiate(Time{0}), SubmitStatus::accepted);
    EXPECT_TRUE(c->busy());
  }
}

}  // namespace
}  // namespace ibs::pcp
