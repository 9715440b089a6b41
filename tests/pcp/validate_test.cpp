// The checks the PCP constructors throw by, as the non-throwing API gives them (docs/embedding.md,
// "An embedded build"): Link::validate, Client::validate, Server::validate and
// ParameterStore::validate return each refusal's code with the very message of the exception, in
// the order the constructors check, and an accepted configuration builds the object it describes.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "pcp_harness.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/base/error.hpp"
#include "ibs/pcp/client.hpp"
#include "ibs/pcp/link.hpp"
#include "ibs/pcp/parameter_store.hpp"
#include "ibs/pcp/server.hpp"

namespace ibs::pcp {
namespace {

using namespace std::chrono_literals;

// What `make` throws ("" when it returns).
std::string thrown(const std::function<void()>& make) {
  try {
    make();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

void expect_refused(const Error& e, ErrorCode code, const std::string& message,
                    const std::function<void()>& make) {
  EXPECT_EQ(e.code, code);
  EXPECT_EQ(e.message, message);
  EXPECT_EQ(e.message, thrown(make));
}

TEST(PcpValidate, Link) {
  for (const int words : {1, 2, 4}) {
    const LinkConfig ok{words, Direction::to_server, 100ms};
    EXPECT_FALSE(Link::validate(ok)) << words;
    EXPECT_EQ(Link(ok).config().channel_words, words);
  }
  for (const int words : {0, 3, 5, -1}) {
    const LinkConfig bad{words, Direction::to_client, 100ms};
    expect_refused(Link::validate(bad), ErrorCode::channel_width_invalid,
                   "PCP channel of " + std::to_string(words) +
                       " words: the MC6000 offers 1, 2 or 4 (405-SUPI, INTERBUS manual 3.2.2)",
                   [&] { const Link l(bad); });
  }
  const LinkConfig no_timeout{2, Direction::to_server, 0ms};
  expect_refused(Link::validate(no_timeout), ErrorCode::channel_timeout_not_positive,
                 "PCP link ack_timeout must be positive", [&] { const Link l(no_timeout); });
}

TEST(PcpValidate, Client) {
  ClientConfig ok;
  ok.channel_words = 4;
  EXPECT_FALSE(Client::validate(ok));
  EXPECT_EQ(thrown([&] { const Client c(ok); }), "");

  ClientConfig bad = ok;
  bad.kbl.max_pdu_sending = 19;
  expect_refused(Client::validate(bad), ErrorCode::channel_pdu_size_invalid,
                 "PCP client KBL: max PDU sizes must be 20..134 bytes (got sending 19, receiving " +
                     std::to_string(ok.kbl.max_pdu_receiving) + ")",
                 [&] { const Client c(bad); });
  bad = ok;
  bad.kbl.max_pdu_receiving = 135;
  EXPECT_EQ(Client::validate(bad).code, ErrorCode::channel_pdu_size_invalid);
  EXPECT_EQ(Client::validate(bad).message, thrown([&] { const Client c(bad); }));

  bad = ok;
  bad.request_timeout = 0ms;
  expect_refused(Client::validate(bad), ErrorCode::channel_timeout_not_positive,
                 "PCP client request_timeout must be positive", [&] { const Client c(bad); });

  // Then the link's own checks, with the link's messages.
  bad = ok;
  bad.channel_words = 3;
  expect_refused(Client::validate(bad), ErrorCode::channel_width_invalid,
                 "PCP channel of 3 words: the MC6000 offers 1, 2 or 4 (405-SUPI, INTERBUS manual 3.2.2)",
                 [&] { const Client c(bad); });
  bad = ok;
  bad.link_ack_timeout = -1ms;
  expect_refused(Client::validate(bad), ErrorCode::channel_timeout_not_positive,
                 "PCP link ack_timeout must be positive", [&] { const Client c(bad); });

  // The client's own check comes first, as in the constructor.
  bad.request_timeout = 0ms;
  EXPECT_EQ(Client::validate(bad).message, "PCP client request_timeout must be positive");
  EXPECT_EQ(Client::validate(bad).message, thrown([&] { const Client c(bad); }));
}

TEST(PcpValidate, Server) {
  const std::span<const ParameterInfo> table = ibs::devices::mc6000::parameters();
  const ServerConfig ok = ibs::devices::mc6000::server_config(2);
  EXPECT_FALSE(Server::validate(ok, table));
  EXPECT_EQ(thrown([&] { test::Served sp; const Server s(ok, sp.served); }), "");

  ServerConfig bad = ok;
  bad.workload = 1.5;
  expect_refused(Server::validate(bad, table), ErrorCode::channel_workload_out_of_range,
                 "PCP server workload " + std::to_string(1.5) + " is outside 0..1",
                 [&] { test::Served sp; const Server s(bad, sp.served); });
  bad = ok;
  LatencyModel inverted;
  inverted.processing_min = 9ms;
  inverted.processing_max = 1ms;
  bad.latency = inverted;
  expect_refused(Server::validate(bad, table), ErrorCode::channel_latency_invalid,
                 "PCP server latency: need 0 <= processing_min <= processing_max",
                 [&] { test::Served sp; const Server s(bad, sp.served); });

  // The table as the store refuses it, then the channel as the link refuses it.
  const std::array<ParameterInfo, 1> out{
      {{2, "C", DataType::usign8, Category::ram_control, 0, 9, 10, 0}}};
  expect_refused(Server::validate(ok, out), ErrorCode::table_default_outside_limits,
                 "parameter table: 2-C: default outside min..max",
                 [&] { test::Served sp(StartMode::running, out); const Server s(ok, sp.served); });
  bad = ok;
  bad.channel_words = 3;
  expect_refused(Server::validate(bad, table), ErrorCode::channel_width_invalid,
                 "PCP channel of 3 words: the MC6000 offers 1, 2 or 4 (405-SUPI, INTERBUS manual 3.2.2)",
                 [&] { test::Served sp; const Server s(bad, sp.served); });
}

TEST(PcpValidate, ParameterStore) {
  const auto store = [](std::span<const ParameterInfo> t) {
    return [t] { const ParameterStore s(t); };
  };
  EXPECT_FALSE(ParameterStore::validate(ibs::devices::mc6000::parameters()));

  std::vector<ParameterInfo> many(kMaxParameters + 1);
  for (std::size_t i = 0; i < many.size(); ++i) {
    many[i] = {
        static_cast<std::uint16_t>(i), "X", DataType::usign8, Category::ram_control, 0, 1, 0, 0};
  }
  expect_refused(ParameterStore::validate(many), ErrorCode::table_too_large,
                 "parameter table has 65 rows; the store holds at most 64", store(many));

  const std::array<ParameterInfo, 1> high{
      {{1000, "H", DataType::usign8, Category::ram_control, 0, 9, 0, 0}}};
  expect_refused(ParameterStore::validate(high), ErrorCode::table_number_out_of_range,
                 "parameter table: 1000-H: number above 999", store(high));
  const std::array<ParameterInfo, 1> unnamed{
      {{3, "", DataType::usign8, Category::ram_control, 0, 9, 0, 0}}};
  expect_refused(ParameterStore::validate(unnamed), ErrorCode::table_bad_name,
                 "parameter table: 3-: name must have 1 to 5 characters", store(unnamed));
  const std::array<ParameterInfo, 1> long_name{
      {{3, "TOOLONG", DataType::usign8, Category::ram_control, 0, 9, 0, 0}}};
  expect_refused(ParameterStore::validate(long_name), ErrorCode::table_bad_name,
                 "parameter table: 3-TOOLONG: name must have 1 to 5 characters", store(long_name));
  const std::array<ParameterInfo, 2> dup{
      {{1, "A", DataType::usign8, Category::ram_control, 0, 9, 0, 0},
       {1, "B", DataType::usign8, Category::ram_control, 0, 9, 0, 0}}};
  expect_refused(ParameterStore::validate(dup), ErrorCode::table_number_repeated,
                 "parameter table: 1-B: number appears twice", store(dup));
  const std::array<ParameterInfo, 1> fit{
      {{4, "D", DataType::usign8, Category::ram_control, 0, 300, 0, 0}}};
  expect_refused(ParameterStore::validate(fit), ErrorCode::table_limits_outside_type,
                 "parameter table: 4-D: a limit or the default does not fit " +
                     std::string(to_string(DataType::usign8)),
                 store(fit));
  const std::array<ParameterInfo, 1> order{
      {{5, "E", DataType::integer16, Category::ram_control, 5, -5, 0, 0}}};
  expect_refused(ParameterStore::validate(order), ErrorCode::table_min_above_max,
                 "parameter table: 5-E: min above max", store(order));
  const std::array<ParameterInfo, 1> out{
      {{2, "C", DataType::usign8, Category::ram_control, 0, 9, 10, 0}}};
  expect_refused(ParameterStore::validate(out), ErrorCode::table_default_outside_limits,
                 "parameter table: 2-C: default outside min..max", store(out));

  // An accepted table: the store holds its defaults.
  const std::array<ParameterInfo, 1> one{
      {{7, "S", DataType::integer16, Category::ram_control, -5, 5, -3, 0}}};
  ASSERT_FALSE(ParameterStore::validate(one));
  const ParameterStore s(one);
  ASSERT_TRUE(s.get(7).has_value());
  EXPECT_EQ(s.get(7)->raw, ParameterStore::to_raw(one[0], -3));
}

}  // namespace
}  // namespace ibs::pcp
