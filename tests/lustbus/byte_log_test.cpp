// Reading a byte log of `--log` (docs/lustbus.md, "Reading a byte log"): the host's side found by
// its first EOT whichever direction it is, telegrams and answers explained with the parameters the
// caller's lookup names, and malformed lines refused with their line number and what is wrong.
#include "ibs/lustbus/byte_log.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace ibs::lustbus {
namespace {

using Lines = std::vector<std::string>;

// A table of two parameters, as a wing would answer.
std::optional<ParameterFacts> two_parameters(Family f, std::uint16_t number) {
  if (f == Family::standard && number == 5) return ParameterFacts{5, "FSSIO", "Hz", DataType::fixpoint16};
  if (f == Family::enhanced && number == 77) return ParameterFacts{77, "SPEED", "", DataType::int32q16};
  return std::nullopt;
}

TEST(LustbusByteLog, HostOnRxAsInTheEmulatorsLog) {
  const Lines lines = {
      "0.000100 rx /dev/pts/4 04 41 30 30 31 30 35 05",  // EOT, ENQUIRY A 00105 (6.1)
      "0.030000 tx /dev/pts/4 41 02 30 30 31 30 35 3D 30 33 45 38 03 74",
      "",
      "0.031000 rx /dev/pts/4 04",
      "0.040000 rx /dev/pts/4 04 41 30 30 31 39 39 05",  // a parameter the table lacks
      "0.050000 rx /dev/pts/4 04 41 30",                  // cut off
  };
  const ByteLogReading r = read_byte_log(lines, two_parameters);
  ASSERT_FALSE(r.error) << r.error->what;
  EXPECT_FALSE(r.host_tx);
  EXPECT_EQ(r.host_port, "/dev/pts/4");
  EXPECT_EQ(r.text,
            "0.000100 host  EOT\n"
            "0.000100 host  ENQUIRY A (address 1) 00105: VF1000 5-FSSIO\n"
            "0.030000 drive A 00105=03E8 BCC ok: VF1000 5-FSSIO = 50.00 Hz\n"
            "0.031000 host  EOT\n"
            "0.040000 host  EOT\n"
            "0.040000 host  ENQUIRY A (address 1) 00199: VF1000 99 (not in the table)\n"
            "0.050000 host  EOT\n"
            "0.050000 host  broken telegram (cut off at the end of the log): A0\n");
}

TEST(LustbusByteLog, HostOnTxWithSelectAndWrongBcc) {
  const Lines lines = {
      // 6.1.1.2: ENQUIRY 20077 via address 0, the answer 04FA4000 (BCC 0BH).
      "0.000100 tx /dev/pts/9 04 40 32 30 30 37 37 05",
      "0.030000 rx /dev/pts/9 40 02 32 30 30 37 37 3D 30 34 46 41 34 30 30 30 03 0B",
      // A SELECT with a wrong BCC (74H would be right), answered NAK.
      "0.060000 tx /dev/pts/9 04 41 02 30 30 31 30 35 3D 30 33 45 38 03 75",
      "0.070000 rx /dev/pts/9 41 15",
  };
  const ByteLogReading r = read_byte_log(lines, two_parameters);
  ASSERT_FALSE(r.error) << r.error->what;
  EXPECT_TRUE(r.host_tx);
  EXPECT_EQ(r.text,
            "0.000100 host  EOT\n"
            "0.000100 host  ENQUIRY @ (address 0) 20077: MC6000 77-SPEED\n"
            "0.030000 drive @ 20077=04FA4000 BCC ok: MC6000 77-SPEED = 1274.25\n"
            "0.060000 host  EOT\n"
            "0.060000 host  SELECT A (address 1) 00105=03E8 BCC WRONG (75, should be 74): VF1000 5-FSSIO := 50.00 Hz\n"
            "0.070000 drive A NAK (the cause is in 85-SIOF/SERR, 9.2)\n");
}

TEST(LustbusByteLog, WithoutALookupParametersAreNotInTheTable) {
  const ByteLogReading r = read_byte_log(Lines{"0.1 tx p 04 41 30 30 31 30 35 05"}, {});
  ASSERT_FALSE(r.error);
  EXPECT_NE(r.text.find("00105: VF1000 5 (not in the table)"), std::string::npos) << r.text;
}

TEST(LustbusByteLog, MalformedLinesNameTheirNumberHeaderCounted) {
  const auto error_of = [](const Lines& lines) {
    const ByteLogReading r = read_byte_log(lines, two_parameters);
    EXPECT_TRUE(r.text.empty());
    return r.error ? std::to_string(r.error->line) + ": " + r.error->what : std::string("no error");
  };
  EXPECT_EQ(error_of({"0.1 tx p 04", "0.2 up p 06"}), "3: 'up' is neither tx nor rx");
  EXPECT_EQ(error_of({"0.1 tx p 04 4G"}), "2: '4G' is not a byte in two hex digits");
  EXPECT_EQ(error_of({"0.1 tx p 04 406"}), "2: '406' is not a byte in two hex digits");
  EXPECT_EQ(error_of({"", "soon tx p 04"}), "3: 'soon' is no time in seconds");
  EXPECT_EQ(error_of({"0.1 rx p"}), "2: a line without bytes");
  // A DFS-1 log: no EOT anywhere.
  EXPECT_EQ(error_of({"0.1 tx p 10 02 01 81 10 03 7E"}),
            "0: no EOT in the log: not a LUSTBUS byte log (3: every telegram begins with EOT)");
}

TEST(LustbusByteLog, EngineeringTextOfTheTypes) {
  EXPECT_EQ(engineering_text(DataType::fixpoint16, 463), "23.15");
  EXPECT_EQ(engineering_text(DataType::integer16, 0xFFFF), "-1");
  EXPECT_EQ(engineering_text(DataType::int32q16, 0x04FA4000), "1274.25");
  EXPECT_EQ(engineering_text(DataType::usign16, 1000), "1000");
  EXPECT_EQ(engineering_text(DataType::vf_error, 0x0102), "");  // an error structure: no number
}

}  // namespace
}  // namespace ibs::lustbus
