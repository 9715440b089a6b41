#include "ibs/lustbus/timing.hpp"

namespace ibs::lustbus {

// 10.1.1: 8 characters, reaction, 9 + VALUE + ... characters, host reaction, EOT.
TelegramTime enquiry_time(std::size_t value_length, std::uint32_t baud, Duration reaction,
                          Duration host_reaction) {
  return {transfer_time(kEnquiryLength, baud), reaction,
          transfer_time(text_answer_length(value_length), baud), host_reaction,
          transfer_time(1, baud)};
}

// 10.1.2: the SELECT, reaction, ADR ACK, host reaction, EOT.
TelegramTime select_time(std::size_t value_length, std::uint32_t baud, Duration reaction,
                         Duration host_reaction) {
  return {transfer_time(select_length(value_length), baud), reaction,
          transfer_time(kShortAnswerLength, baud), host_reaction, transfer_time(1, baud)};
}

}  // namespace ibs::lustbus
