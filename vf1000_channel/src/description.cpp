#include "ibs/vf1000_channel/description.hpp"

namespace ibs::vf1000_channel {

DescriptionRecord make_description(const drive::ParameterInfo& p) {
  DescriptionRecord r{};
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = description_byte(p, i);
  return r;
}

Description decode_description(const DescriptionRecord& record) {
  const auto text = [&record](std::size_t from) {
    std::string s;
    for (std::size_t i = from; i < from + 5; ++i) s.push_back(static_cast<char>(record[i]));
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
  };
  Description d;
  d.name = text(0);
  d.unit = text(5);
  d.category = drive::category_from_code(static_cast<char>(record[10]));
  d.type = drive::data_type_from_code(static_cast<char>(record[11]));
  d.min = make_word(record[12], record[13]);
  d.max = make_word(record[14], record[15]);
  d.default_value = make_word(record[16], record[17]);
  return d;
}

}  // namespace ibs::vf1000_channel
