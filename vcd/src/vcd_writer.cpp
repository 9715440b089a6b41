#include "ibs/vcd/vcd_writer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <utility>

#ifndef IBS_VERSION
#define IBS_VERSION "unknown"
#endif

namespace ibs::vcd {

namespace {

constexpr std::size_t kIdBase = 94;  // '!'..'~'
constexpr char kIdFirst = '!';
constexpr std::size_t kSpillBytes = std::size_t{1} << 16U;

bool valid_name(std::string_view name) {
  return !name.empty() && std::ranges::all_of(name, [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

bool valid_state_name(std::string_view name) {
  return !name.empty() && name.front() != ' ' && name.back() != ' ' &&
         std::ranges::all_of(name, [](char c) { return c >= ' ' && c <= '~'; });
}

std::string quoted(std::string_view s) {
  return "'" + std::string(s) + "'";
}

// Width of a state vector: enough bits for the highest state number, rounded up to whole hex
// digits so the translate filter's keys match gtkwave's hex display exactly.
unsigned state_width(std::size_t states) {
  const auto bits = static_cast<unsigned>(std::bit_width(states - 1));
  const unsigned digits = bits == 0 ? 1U : (bits + 3U) / 4U;
  return digits * 4U;
}

std::string hex_digits(std::uint64_t v, unsigned digits) {
  constexpr std::string_view kHex = "0123456789ABCDEF";
  std::string s(digits, '0');
  for (unsigned i = 0; i < digits; ++i) {
    s[digits - 1U - i] = kHex[(v >> (4U * i)) & 0x0FU];
  }
  return s;
}

void append_number(std::string& buf, std::int64_t v) {
  std::array<char, 24> tmp{};
  const auto r = std::to_chars(tmp.data(), tmp.data() + tmp.size(), v);
  buf.append(tmp.data(), r.ptr);
}

}  // namespace

std::string identifier_code(std::size_t index) {
  std::string s;
  for (;;) {
    s += static_cast<char>(kIdFirst + static_cast<char>(index % kIdBase));
    if (index < kIdBase) break;
    index = index / kIdBase - 1;
  }
  return s;
}

VcdWriter::VcdWriter(std::ostream& out, VcdHeader header) : out_(out), header_(std::move(header)) {
  if (header_.version.empty()) header_.version = std::string("ibs ") + IBS_VERSION;
  buf_.reserve(kSpillBytes + 256);
}

VcdWriter::~VcdWriter() {
  if (finished_) return;
  try {
    finish();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw
  }
}

const VcdWriter::Signal& VcdWriter::info(std::uint32_t index) const {
  if (index >= signals_.size()) {
    throw VcdError("vcd: signal handle " + std::to_string(index) + " is not from this writer");
  }
  return signals_[index];
}

VcdWriter::Signal& VcdWriter::checked(std::uint32_t index, Kind kind, const char* what) {
  if (index >= signals_.size() || signals_[index].kind != kind) {
    throw VcdError(std::string("vcd: ") + what + " handle " + std::to_string(index) +
                   " is not from this writer");
  }
  return signals_[index];
}

void VcdWriter::require_declaring(std::string_view what) const {
  if (header_written_) {
    throw VcdError("vcd: cannot declare " + std::string(what) +
                   " after recording started (declare every signal first)");
  }
}

void VcdWriter::require_recording() {
  if (finished_) throw VcdError("vcd: the dump is finished");
  if (!header_written_) end_definitions();
}

void VcdWriter::begin_scope(std::string_view name) {
  require_declaring("scope " + quoted(name));
  if (!valid_name(name)) {
    throw VcdError("vcd: scope name " + quoted(name) +
                   " must be letters, digits and '_' only, not empty");
  }
  std::string p;
  for (const std::string& s : scope_stack_) p += s + '.';
  p += name;
  // A scope may be reopened (its signals then join the same module in the viewer), but it must
  // not share its path with a signal.
  if (paths_.contains(p) && !paths_.contains(p + '.')) {
    throw VcdError("vcd: scope " + quoted(p) + " has the name of a signal");
  }
  paths_.insert(p);
  paths_.insert(p + '.');
  scope_stack_.emplace_back(name);
  decls_.push_back({Decl::What::scope, std::string(name), 0});
}

void VcdWriter::end_scope() {
  require_declaring("the end of a scope");
  if (scope_stack_.empty()) throw VcdError("vcd: end_scope() without an open scope");
  scope_stack_.pop_back();
  decls_.push_back({Decl::What::upscope, {}, 0});
}

std::uint32_t VcdWriter::declare(std::string_view name, Kind kind, unsigned width,
                                 std::uint64_t initial) {
  if (!valid_name(name)) {
    throw VcdError("vcd: signal name " + quoted(name) +
                   " must be letters, digits and '_' only, not empty");
  }
  std::string p;
  for (const std::string& s : scope_stack_) p += s + '.';
  p += name;
  if (paths_.contains(p)) throw VcdError("vcd: signal " + quoted(p) + " is declared twice");
  paths_.insert(p);
  const auto index = static_cast<std::uint32_t>(signals_.size());
  Signal s;
  s.kind = kind;
  s.width = width;
  s.pending = initial;
  s.written = initial;
  s.id = identifier_code(index);
  s.path = std::move(p);
  s.name = std::string(name);
  signals_.push_back(std::move(s));
  decls_.push_back({Decl::What::var, {}, index});
  return index;
}

WireSignal VcdWriter::add_wire(std::string_view name, unsigned width, std::uint64_t initial) {
  require_declaring("wire " + quoted(name));
  if (width < 1 || width > kMaxWireWidth) {
    throw VcdError("vcd: wire " + quoted(name) + " is " + std::to_string(width) +
                   " bits wide, the range is 1..64");
  }
  if (width < 64 && (initial >> width) != 0) {
    throw VcdError("vcd: initial value " + std::to_string(initial) + " of wire " + quoted(name) +
                   " does not fit its " + std::to_string(width) + " bits");
  }
  return WireSignal{declare(name, Kind::wire, width, initial)};
}

RealSignal VcdWriter::add_real(std::string_view name, double initial) {
  require_declaring("real " + quoted(name));
  return RealSignal{declare(name, Kind::real, 64, std::bit_cast<std::uint64_t>(initial))};
}

StateSignal VcdWriter::add_state(std::string_view name, std::vector<std::string> state_names,
                                 std::uint64_t initial) {
  require_declaring("state " + quoted(name));
  if (state_names.empty()) throw VcdError("vcd: state " + quoted(name) + " has no states");
  for (const std::string& n : state_names) {
    if (!valid_state_name(n)) {
      throw VcdError("vcd: state " + quoted(name) + ": state name " + quoted(n) +
                     " must be printable ASCII without leading or trailing blanks, not empty");
    }
  }
  if (initial >= state_names.size()) {
    throw VcdError("vcd: initial state " + std::to_string(initial) + " of " + quoted(name) +
                   " is not one of its " + std::to_string(state_names.size()) + " states");
  }
  const std::uint32_t i = declare(name, Kind::state, state_width(state_names.size()), initial);
  signals_[i].states = std::move(state_names);
  return StateSignal{i};
}

void VcdWriter::end_definitions() {
  if (header_written_) return;
  if (!scope_stack_.empty()) {
    throw VcdError("vcd: scope " + quoted(scope_stack_.back()) +
                   " is still open at the end of the definitions");
  }
  header_written_ = true;
  if (!header_.date.empty()) buf_ += "$date\n\t" + header_.date + "\n$end\n";
  buf_ += "$version\n\t" + header_.version + "\n$end\n";
  if (!header_.comment.empty()) buf_ += "$comment\n\t" + header_.comment + "\n$end\n";
  buf_ += "$timescale ";
  buf_ += kTimescale;
  buf_ += " $end\n";
  for (const Decl& d : decls_) {
    switch (d.what) {
      case Decl::What::scope:
        buf_ += "$scope module " + d.scope_name + " $end\n";
        break;
      case Decl::What::upscope:
        buf_ += "$upscope $end\n";
        break;
      case Decl::What::var: {
        const Signal& s = signals_[d.signal];
        buf_ += s.kind == Kind::real ? "$var real " : "$var wire ";
        buf_ += std::to_string(s.width) + ' ' + s.id + ' ' + s.name + " $end\n";
        break;
      }
    }
  }
  buf_ += "$enddefinitions $end\n";
  decls_.clear();
  decls_.shrink_to_fit();
  spill(false);
}

void VcdWriter::mark(std::uint32_t index, std::uint64_t bits) {
  Signal& s = signals_[index];
  s.pending = bits;
  if (!s.dirty) {
    s.dirty = true;
    dirty_.push_back(index);
  }
}

void VcdWriter::change(WireSignal s, std::uint64_t value) {
  require_recording();
  const Signal& sig = checked(s.index, Kind::wire, "wire");
  if (sig.width < 64 && (value >> sig.width) != 0) {
    throw VcdError("vcd: value " + std::to_string(value) + " does not fit the " +
                   std::to_string(sig.width) + "-bit wire " + quoted(sig.path));
  }
  mark(s.index, value);
}

void VcdWriter::change(RealSignal s, double value) {
  require_recording();
  checked(s.index, Kind::real, "real");
  mark(s.index, std::bit_cast<std::uint64_t>(value));
}

void VcdWriter::change(StateSignal s, std::uint64_t state) {
  require_recording();
  const Signal& sig = checked(s.index, Kind::state, "state");
  if (state >= sig.states.size()) {
    throw VcdError("vcd: state " + std::to_string(state) + " is not one of the " +
                   std::to_string(sig.states.size()) + " states of " + quoted(sig.path));
  }
  mark(s.index, state);
}

void VcdWriter::write_time(Time t) {
  buf_ += '#';
  append_number(buf_, t.count());
  buf_ += '\n';
  last_time_written_ = t;
}

void VcdWriter::write_value(const Signal& s, std::uint64_t bits) {
  switch (s.kind) {
    case Kind::real: {
      std::array<char, 32> tmp{};
      const auto r =
          std::to_chars(tmp.data(), tmp.data() + tmp.size(), std::bit_cast<double>(bits));
      buf_ += 'r';
      buf_.append(tmp.data(), r.ptr);
      buf_ += ' ';
      break;
    }
    case Kind::wire:
    case Kind::state:
      if (s.width == 1) {
        buf_ += bits != 0 ? '1' : '0';
      } else {
        buf_ += 'b';
        const unsigned digits = bits == 0 ? 1U : static_cast<unsigned>(std::bit_width(bits));
        for (unsigned i = digits; i-- > 0;) buf_ += ((bits >> i) & 1U) != 0 ? '1' : '0';
        buf_ += ' ';
      }
      break;
  }
  buf_ += s.id;
  buf_ += '\n';
}

void VcdWriter::flush_step() {
  if (!dumped_) {
    // $dumpvars: the initial value of every variable, at the first time written.
    write_time(now_);
    buf_ += "$dumpvars\n";
    for (Signal& s : signals_) {
      write_value(s, s.pending);
      s.written = s.pending;
      s.dirty = false;
    }
    buf_ += "$end\n";
    dirty_.clear();
    dumped_ = true;
    spill(false);
    return;
  }
  bool stamped = false;
  for (const std::uint32_t i : dirty_) {
    Signal& s = signals_[i];
    s.dirty = false;
    if (s.pending == s.written) continue;
    if (!stamped) {
      write_time(now_);
      stamped = true;
    }
    write_value(s, s.pending);
    s.written = s.pending;
    ++changes_written_;
  }
  dirty_.clear();
  spill(false);
}

void VcdWriter::advance(Time t) {
  require_recording();
  if (t < now_) {
    throw VcdError("vcd: advance to " + std::to_string(t.count()) +
                   " ns goes back from the current time " + std::to_string(now_.count()) + " ns");
  }
  if (t == now_) return;
  flush_step();
  now_ = t;
}

void VcdWriter::finish() {
  if (finished_) return;
  require_recording();
  flush_step();
  if (last_time_written_ < now_) write_time(now_);
  finished_ = true;
  spill(true);
  out_.flush();
  if (!out_) throw VcdError("vcd: writing the dump failed");
}

void VcdWriter::spill(bool force) {
  if (buf_.empty() || (!force && buf_.size() < kSpillBytes)) return;
  out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
  buf_.clear();
}

std::string VcdWriter::translate_filter(StateSignal s) const {
  const Signal& sig = info(s.index);
  if (sig.kind != Kind::state) {
    throw VcdError("vcd: state handle " + std::to_string(s.index) + " is not from this writer");
  }
  const unsigned digits = sig.width / 4U;
  std::string text = "# gtkwave translate filter for " + sig.path + " (" +
                     std::to_string(sig.width) + "-bit vector, hex display)\n";
  text += "# Edit > Data Format > Translate Filter File > Enable and Select (docs/vcd.md)\n";
  for (std::size_t i = 0; i < sig.states.size(); ++i) {
    text += hex_digits(i, digits) + ' ' + sig.states[i] + '\n';
  }
  return text;
}

}  // namespace ibs::vcd
