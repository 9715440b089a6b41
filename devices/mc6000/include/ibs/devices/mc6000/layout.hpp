// MC6000 process-data layouts: 405-SUPI splits the four bus words between process data and PCP
// (INTERBUS manual 3.2.2), 406-IBCNF says how the reference and actual words read (3.2.3). The ID code
// each layout reports follows from the table (local and remote bus).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "ibs/base/error.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/base/words.hpp"

#if IBS_EXCEPTIONS
#include <stdexcept>
#endif

namespace ibs::devices::mc6000 {

// One row of the SUPI table of the INTERBUS manual 3.2.2.
struct SupiRow {
  int supi;
  int pd_words;
  int pcp_words;
  Word id_local;
  Word id_remote;
};

// SUPI 0 reads as configuration 4 on the bus (footnote of 3.2.2) but exchanges no data.
inline constexpr std::array<SupiRow, 13> kSupiTable{{
    {0, 1, 0, 0x193, 0x17B},
    {1, 0, 1, 0x1D3, 0x1DB},
    {2, 0, 2, 0x2D0, 0x2D8},
    {3, 0, 4, 0x4D1, 0x4D9},
    {4, 1, 0, 0x193, 0x17B},
    {5, 1, 1, 0x2D3, 0x2DB},
    {6, 1, 2, 0x3D0, 0x3D8},
    {7, 2, 0, 0x293, 0x27B},
    {8, 2, 1, 0x3D3, 0x3DB},
    {9, 2, 2, 0x4D0, 0x4D8},
    {10, 3, 0, 0x393, 0x37B},
    {11, 3, 1, 0x4D3, 0x4DB},
    {12, 4, 0, 0x493, 0x47B},
}};

inline constexpr int kSupiMax = 12;

// 406-IBCNF values (3.2.3).
enum class Ibcnf : int {
  none = 0,          // no reference transfer, all actual words 0
  word16 = 1,        // 16-bit reference and actual
  q16 = 2,           // 32-bit Q16 reference and actual, high word first (the factory default)
  speed_torque = 3,  // 32-bit Q16 speed reference; actual 16-bit speed then 16-bit torque
  lisim = 4,         // modified LISIM software: not supported by this project
};
inline constexpr int kIbcnfMax = 4;

// The SUPI settings 3.2.3 allows for an IBCNF (inclusive range).
struct SupiRange {
  int first;
  int last;
};
SupiRange allowed_supi(Ibcnf c);

// A checked SUPI/IBCNF pair and everything that follows from it.
struct Layout {
  int supi = 11;
  Ibcnf ibcnf = Ibcnf::q16;
  interbus::BusKind bus = interbus::BusKind::remote;
  int pd_words = 3;        // process-data words, the control/status word first
  int pcp_words = 1;       // PCP channel width in words
  bool exchanges_data = true;  // false for SUPI 0 (endless loop, no data exchange)
  Word id_code = 0x4DB;
  int reference_words = 2;  // words after the control word that carry the reference
  int actual_words = 2;     // words after the status word that carry the actual value(s)
};

// Checks the pair against 3.2.2/3.2.3 and builds the layout. Refuses (ErrorCode::layout_*, the
// message naming the value and the rule) a 405-SUPI or 406-IBCNF out of range, 406-IBCNF = 4 and
// a pair 3.2.3 does not allow.
Expected<Layout> try_make_layout(int supi, int ibcnf,
                                 interbus::BusKind bus = interbus::BusKind::remote);

#if IBS_EXCEPTIONS
// Thrown at configuration time for a refused SUPI/IBCNF pair; what() is the Error's message.
class LayoutError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};
// try_make_layout, throwing LayoutError for what it refuses.
Layout make_layout(int supi, int ibcnf, interbus::BusKind bus = interbus::BusKind::remote);
#endif

// Reference and actual values in engineering units of the control mode (rpm in speed control).
// 16-bit words carry integer units (a modelling choice: the manual does not give the 16-bit
// scaling); Q16 words carry units * 65536 as a signed 32-bit value, high word first (5.3.4).
std::int32_t to_q16(double value);
double from_q16(std::int32_t raw);

// Writes the reference into `words` (the words after the control word, reference_words long).
void encode_reference(const Layout& l, double value, std::span<Word> words);
double decode_reference(const Layout& l, std::span<const Word> words);

struct Actual {
  double value = 0.0;   // speed (or torque / position, by control mode)
  double torque = 0.0;  // IBCNF 3 only: the second actual word
};
// Writes the actual value(s) into `words` (the words after the status word); words the layout
// leaves unused are set to 0.
void encode_actual(const Layout& l, const Actual& a, std::span<Word> words);
Actual decode_actual(const Layout& l, std::span<const Word> words);

}  // namespace ibs::devices::mc6000
