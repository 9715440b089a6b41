// A small fake drive behind the LUSTBUS Responder interface, with a handful of parameters of each
// family — only what the tests need; the real drive tables live in the drive wings. It keeps the
// 85-SIOF/SERR latch of the LUSTBUS manual 6 and 9.2: power-on bit after start, every SELECT refused while
// a bit is set, the cause of a refused SELECT entered, reading 85 clears the bits it returned.
// It never allocates on the byte path.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/responder.hpp"
#include "ibs/lustbus/siof.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::lustbus::test {

struct FakeParam {
  unsigned number = 0;
  DataType type = DataType::usign16;
  std::uint32_t value = 0;
  std::uint32_t min = 0;
  std::uint32_t max = 0xFFFF;
  bool writable = true;
  bool eeprom = false;
  std::string_view name = "P";
  std::string_view unit = "";
  std::vector<std::string_view> texts{};  // value substitution texts (MC, 11.3)
};

class FakeDrive : public Responder {
 public:
  FakeDrive(Family f, std::vector<FakeParam> ps, Duration r = 1ms)
      : family(f), params(std::move(ps)), reaction(r) {
    history.reserve(4096);
  }

  Family family;
  std::vector<FakeParam> params;
  Duration reaction;
  std::uint8_t siof = siof_mask(SiofBit::power_on);  // 6: set at every new start
  Duration vf_eeprom_extra = 120ms;                  // 10, exception 4 (two-byte parameters)
  Duration mc_eeprom_per_byte = 15ms;                // 3: every byte saved three times
  Time eeprom_busy_until{};
  bool defer_selects = false;  // answer SELECTs through Receiver::deliver_select
  // The procedures of 11 a servo offers, through the parameters the MC6000 uses (80-SLOAD,
  // 108-STEXT); a test may move them, and describes them to the host with procedures().
  unsigned handshake_parameter = 80;
  unsigned text_index_parameter = 108;
  // SLOAD (11.4) bookkeeping.
  bool download_mode = false;
  bool download_never_ready = false;
  Time download_ready{};
  std::int16_t download_result = 0;
  Value posmod_reply = make_value("0G10H10");
  Value posmod_last{};

  struct Write {
    unsigned number;
    std::uint32_t value;
  };
  std::vector<Write> history;  // every value taken
  int watchdog_resets = 0;
  int checksum_errors = 0;

  FakeParam* find(unsigned number) {
    for (auto& p : params) {
      if (p.number == number) return &p;
    }
    return nullptr;
  }
  std::uint32_t value_of(unsigned number) { return find(number)->value; }

  // The parameter a value CODE names on this family, or nullptr (NAK: improper CODE).
  FakeParam* resolve(const Code& c, bool& description) {
    description = false;
    if (family == Family::standard) {
      const auto vc = as_vf_code(c);
      if (!vc) return nullptr;
      description = vc->specifier == VfSpecifier::description;
      return find(vc->parameter);
    }
    const auto mc = as_mc_code(c);
    if (!mc) return nullptr;
    switch (mc->kind) {
      case McCodeKind::value:
      case McCodeKind::shared:
        return find(mc->parameter);
      case McCodeKind::description:
        description = true;
        return find(mc->parameter);
      default:
        return nullptr;
    }
  }

  void telegram_received(const Context&) override { ++watchdog_resets; }

  EnquiryAnswer enquiry(const Code& code, const Context& ctx) override {
    if (family == Family::enhanced) {
      const auto mc = as_mc_code(code);
      if (mc && mc->kind == McCodeKind::posmod) return EnquiryAnswer::text(posmod_reply, reaction);
      if (mc && mc->kind == McCodeKind::substitution_text) {  // 11.3
        FakeParam* p = find(mc->parameter);
        FakeParam* stext = find(text_index_parameter);
        if (p == nullptr || p->texts.empty() || stext == nullptr ||
            stext->value >= p->texts.size() || stext->value > p->max) {
          return EnquiryAnswer::nak(reaction);
        }
        return EnquiryAnswer::text(make_value(p->texts[stext->value]), reaction);
      }
    }
    bool description = false;
    FakeParam* p = resolve(code, description);
    if (p == nullptr) return EnquiryAnswer::nak(reaction);  // 6.1 note: nothing in 85
    if (description) {
      std::optional<Value> d;
      if (family == Family::standard) {
        d = format_vf_description(p->name, p->unit, p->eeprom ? '2' : (p->writable ? '0' : '1'),
                                  p->type == DataType::fixpoint16 ? '2' : '3',
                                  static_cast<std::uint16_t>(p->min),
                                  static_cast<std::uint16_t>(p->max),
                                  static_cast<std::uint16_t>(p->value));
      } else {
        McDescription m;
        for (std::size_t i = 0; i < p->name.size() && i < kMcNameLength; ++i) m.name[i] = p->name[i];
        m.kind = p->eeprom ? '2' : (p->writable ? '1' : '0');
        m.type = static_cast<std::uint8_t>('0' + static_cast<int>(p->type));
        m.min = p->min;
        m.max = p->max;
        m.reference = p->value;
        m.level = 0x21;
        m.attribute = p->texts.empty() ? 0 : kAttrShowText;
        d = format_mc_description(m);
      }
      if (!d) return EnquiryAnswer::nak(reaction);
      return EnquiryAnswer::text(*d, reaction);
    }
    if (p->number == handshake_parameter && family == Family::enhanced && download_mode &&
        ctx.now >= download_ready) {
      p->value = static_cast<std::uint16_t>(download_result);
      download_mode = false;
    }
    std::uint32_t v = p->value;
    if (p->number == 85) {
      v = siof;
      siof = 0;  // 9.2: reading erases the bits it returned
    }
    const auto f = format_typed(family, p->type, v);
    return EnquiryAnswer::text(f.value, reaction);
  }

  SelectAnswer select(const Code& code, const Value& value, const Context& ctx) override {
    auto refuse = [this](SiofBit b) {
      siof = static_cast<std::uint8_t>(siof | siof_mask(b));
      return SelectAnswer::nak(reaction);
    };
    if (family == Family::enhanced && as_mc_code(code) &&
        as_mc_code(code)->kind == McCodeKind::posmod) {
      posmod_last = value;
      return SelectAnswer::ack(reaction);
    }
    if (siof != 0) return SelectAnswer::nak(reaction);  // 6: refused while a bit is set
    bool description = false;
    FakeParam* p = resolve(code, description);
    if (p == nullptr || description) return refuse(SiofBit::no_parameter);
    if (!p->writable) return refuse(SiofBit::no_change);
    const auto bits = parse_typed(family, p->type, value.view());
    if (!bits.ok()) return refuse(SiofBit::invalid_value);
    const bool in_download = download_mode && p->number != handshake_parameter;
    if (!in_download && p->type == DataType::integer16) {
      const auto s = static_cast<std::int16_t>(bits.value);
      if (s < static_cast<std::int16_t>(p->min) || s > static_cast<std::int16_t>(p->max)) {
        return refuse(SiofBit::invalid_value);
      }
    } else if (!in_download && (bits.value < p->min || bits.value > p->max)) {
      return refuse(SiofBit::invalid_value);
    }
    Duration r = reaction;
    if (p->eeprom) {
      if (family == Family::enhanced) {
        if (ctx.now < eeprom_busy_until) return refuse(SiofBit::eeprom_busy);  // 3, 10.2.2
        eeprom_busy_until = ctx.now + mc_eeprom_per_byte * (width_bits(p->type) / 8);
      } else if (bits.value != p->value) {
        r += vf_eeprom_extra;  // 3: the VF1000 answers once the EEPROM holds the value
      }
    }
    if (family == Family::enhanced && p->number == handshake_parameter) {  // 11.4
      const auto s = static_cast<std::int16_t>(bits.value);
      if (s == -1) {
        download_mode = true;
        download_ready = Time::max();
      } else if (s == -2 && download_mode) {
        download_ready = download_never_ready ? Time::max() : ctx.now + 300ms;
        download_result = 0;
        for (const auto& w : history) {
          if (w.number == 428 && w.value > 0x10000000U) download_result = 428;
        }
      }
      p->value = bits.value;
      return SelectAnswer::ack(r);
    }
    p->value = bits.value;
    history.push_back({p->number, bits.value});
    if (defer_selects) return SelectAnswer::deferred();
    return SelectAnswer::ack(r);
  }

  // The fake's procedures as a wing describes them to the host (11.3, 11.4, 11.6).
  [[nodiscard]] DeviceProcedures procedures() const {
    DeviceProcedures d;
    d.download = DownloadProcedure{Family::enhanced,
                                   static_cast<std::uint16_t>(handshake_parameter), -1, -2};
    d.indexed_text =
        IndexedTextProcedure{Family::enhanced, static_cast<std::uint16_t>(text_index_parameter)};
    d.block_transfer = posmod_procedure();
    return d;
  }
  // 11.6 as the MC6000 offers it: CODE 49999, 80 characters, the error read 1%RDF.
  static BlockTransferProcedure posmod_procedure() {
    BlockTransferProcedure b;
    b.code = kPosmodCode;
    b.max_user_data = 80;
    b.error_read = make_value("1%RDF");
    b.asks_answer = &posmod_asks_answer;
    return b;
  }

  void checksum_error(const Context&) override {
    ++checksum_errors;
    siof = static_cast<std::uint8_t>(siof | siof_mask(SiofBit::checksum));
  }
};

// A VF1000 with the parameters the seed's examples use (6.1.1.1, 6.2.2, 7.1.1, 8.1.1).
inline FakeDrive make_vf1000(Duration reaction = 1ms) {
  return FakeDrive(Family::standard,
                   {
                       {1, DataType::usign8, 4, 0, 4, true, true, "MODE"},
                       {2, DataType::usign8, 5, 0, 5, true, true, "CSEL"},
                       {3, DataType::binary8, 0, 0, 0xFF, true, false, "CNTL"},
                       {4, DataType::usign8, 25, 0, 25, true, true, "FSSEL"},
                       {5, DataType::fixpoint16, 0, 0, 19999, true, false, "FSSIO", "Hz"},
                       {11, DataType::binary8, 0, 0, 0xFF, true, false, "STAT"},
                       {12, DataType::fixpoint16, 0x03E8, 0, 0xFFFF, false, false, "FIST", "Hz"},
                       {22, DataType::fixpoint16, 1000, 0, 19999, true, true, "FMAX1", "Hz"},
                       {81, DataType::usign8, 2, 0, 2, true, true, "SIOC"},
                       {82, DataType::usign8, 1, 1, 30, true, true, "SIOA"},
                       {83, DataType::usign16, 0, 0, 0xFFFF, true, false, "SIOW"},
                       {84, DataType::usign16, 0, 0, 0xFFFF, true, true, "SIOT", "ms"},
                       {85, DataType::binary8, 0, 0, 0xFF, false, false, "SIOF"},
                       {91, DataType::usign16, 1000, 0, 0xFFFF, false, false, "TYPE"},
                   },
                   reaction);
}

// An MC6000 with the parameters of 6.1.1.2, 6.2.3, 7.2.1, 11.3, 11.4.
inline FakeDrive make_mc6000(Duration reaction = 1ms) {
  return FakeDrive(
      Family::enhanced,
      {
          {77, DataType::int32q16, 0x04FA4000, 0, 0xFFFFFFFF, false, false, "SPEED"},
          {80, DataType::integer16, 0, 0xFFFE, 999, true, false, "SLOAD"},
          {81, DataType::usign8, 2, 0, 5, true, true, "SBAUD"},
          {82, DataType::usign8, 1, 1, 30, true, true, "SADDR"},
          {83, DataType::usign16, 0, 0, 0xFFFF, true, false, "SDMMY"},
          {84, DataType::usign16, 0, 0, 0xFFFF, true, true, "SWDGT"},
          {85, DataType::usign8, 0, 0, 0xFF, false, false, "SERR"},
          {91, DataType::usign16, 6000, 0, 0xFFFF, false, false, "TYPE"},
          {107, DataType::usign8, 0, 0, 3, true, false, "UNIT", "", {"", "1/min", "Hz", "V"}},
          {108, DataType::usign16, 0, 0, 0xFFFF, true, false, "STEXT"},
          {300, DataType::usign8, 1, 0, 5, true, true, "CFCON", "", {"TCON", "VFCON", "SCON"}},
          {402, DataType::usign8, 0, 0, 4, true, true, "CLSEL"},
          {416, DataType::usign16, 0, 0, 0xFFFF, true, false, "SCTL1"},
          {417, DataType::usign8, 0, 0, 7, true, true, "RSSL1"},
          {418, DataType::usign8, 0, 0, 7, true, true, "RSSL2"},
          {419, DataType::usign8, 0, 0, 7, true, true, "RSSL3"},
          {420, DataType::usign8, 0, 0, 7, true, true, "RSSL4"},
          {428, DataType::int32q16, 0, 0, 0xFFFFFFFF, true, false, "RSIO"},
          {500, DataType::int32q16, 0, 0, 0xFFFFFFFF, true, true, "EEP32"},
      },
      reaction);
}

}  // namespace ibs::lustbus::test
