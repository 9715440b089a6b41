// JSON scenarios: nlohmann's SAX parser drives a handler that builds the line-carrying document
// tree. SAX callbacks carry no position, so the parser reads through an iterator that publishes
// how far it has read; a callback comes right after its token was read (numbers: plus one
// character of look-ahead), so the line of the last character read is the token's line.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ibs/sim/scenario.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim {

namespace detail {

namespace {

constexpr std::size_t kMaxDepth = 32;

// An input iterator over the text that writes its position to `*cursor` as it advances.
class TrackingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator() = default;
  TrackingIterator(const char* p, const char** cursor) : p_(p), cursor_(cursor) {}

  reference operator*() const { return *p_; }
  TrackingIterator& operator++() {
    ++p_;
    if (cursor_ != nullptr) *cursor_ = p_;
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator old = *this;
    ++*this;
    return old;
  }
  friend bool operator==(const TrackingIterator& a, const TrackingIterator& b) {
    return a.p_ == b.p_;
  }

 private:
  const char* p_ = nullptr;
  const char** cursor_ = nullptr;
};

class TreeBuilder {
 public:
  TreeBuilder(const std::string& text, const std::string& file, const char** cursor)
      : text_(text), file_(file), cursor_(cursor) {
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') newlines_.push_back(i);
    }
  }

  Node take_root() { return std::move(root_); }

  // The line of the character at `index` (1-based lines).
  std::size_t line_at(std::size_t index) const {
    return 1 + static_cast<std::size_t>(
                   std::lower_bound(newlines_.begin(), newlines_.end(), index) - newlines_.begin());
  }

  // The line of the token just read: that of the last character read. A token never spans
  // lines, and the one character of look-ahead after a number, if it is a line break, still
  // belongs to the line it ends.
  std::size_t token_line() const {
    const auto read = static_cast<std::size_t>(*cursor_ - text_.data());
    return line_at(read == 0 ? 0 : read - 1);
  }

  // nlohmann's SAX interface.
  bool null() { return add(scalar(Node::Kind::null)); }
  bool boolean(bool v) {
    Node n = scalar(Node::Kind::boolean);
    n.boolean = v;
    return add(std::move(n));
  }
  bool number_integer(std::int64_t v) {
    Node n = scalar(Node::Kind::integer);
    n.integer = v;
    return add(std::move(n));
  }
  bool number_unsigned(std::uint64_t v) {
    Node n = scalar(Node::Kind::integer);
    if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      throw ScenarioError(file_, n.line,
                          "the integer " + std::to_string(v) + " is too large (at most 2^63-1)");
    }
    n.integer = static_cast<std::int64_t>(v);
    return add(std::move(n));
  }
  bool number_float(double v, const std::string&) {
    Node n = scalar(Node::Kind::floating);
    n.floating = v;
    return add(std::move(n));
  }
  bool string(std::string& v) {
    Node n = scalar(Node::Kind::string);
    n.text = std::move(v);
    return add(std::move(n));
  }
  bool binary(nlohmann::json::binary_t&) { return add(scalar(Node::Kind::null)); }
  bool start_object(std::size_t) { return open(Node::Kind::table); }
  bool end_object() { return close(); }
  bool start_array(std::size_t) { return open(Node::Kind::array); }
  bool end_array() { return close(); }
  bool key(std::string& k) {
    Node& table = *stack_.back();
    const std::size_t line = token_line();
    const auto it = std::find(table.keys.begin(), table.keys.end(), k);
    if (it != table.keys.end()) {
      const auto first = static_cast<std::size_t>(it - table.keys.begin());
      throw ScenarioError(file_, line,
                          "duplicate key '" + k + "' (first on line " +
                              std::to_string(table.key_lines[first]) + ")");
    }
    table.keys.push_back(std::move(k));
    table.key_lines.push_back(line);
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) {
    // nlohmann's text is "[json.exception.parse_error.101] parse error at line L, column C:
    // what" (or "[json.exception.out_of_range.406] what"); keep the what, the line is ours.
    std::string what = e.what();
    if (!what.empty() && what.front() == '[') {
      const std::size_t end = what.find("] ");
      if (end != std::string::npos) what.erase(0, end + 2);
    }
    if (what.rfind("parse error", 0) == 0) {
      const std::size_t column = what.find(", column ");
      const std::size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
      if (colon != std::string::npos) what.erase(0, colon + 2);
    }
    const std::size_t index = position == 0 ? 0 : std::min(position - 1, text_.size());
    throw ScenarioError(file_, line_at(index), "JSON syntax error: " + what);
  }

 private:
  Node scalar(Node::Kind kind) const {
    Node n;
    n.kind = kind;
    n.line = token_line();
    return n;
  }

  bool add(Node n) {
    if (stack_.empty()) {
      root_ = std::move(n);
      return true;
    }
    stack_.back()->children.push_back(std::move(n));
    return true;
  }

  // Pointers on the stack stay valid: only the innermost open node gains children.
  bool open(Node::Kind kind) {
    Node n = scalar(kind);
    if (stack_.size() >= kMaxDepth) throw ScenarioError(file_, n.line, "values nested too deeply");
    add(std::move(n));
    stack_.push_back(stack_.empty() ? &root_ : &stack_.back()->children.back());
    return true;
  }

  bool close() {
    stack_.pop_back();
    return true;
  }

  const std::string& text_;
  const std::string& file_;
  const char** cursor_;
  std::vector<std::size_t> newlines_;
  std::vector<Node*> stack_;
  Node root_;
};

}  // namespace

Node json_tree(const std::string& text, const std::string& file) {
  const char* cursor = text.data();
  TreeBuilder builder(text, file, &cursor);
  const TrackingIterator first(text.data(), &cursor);
  const TrackingIterator last(text.data() + text.size(), nullptr);
  nlohmann::json::sax_parse(first, last, &builder);
  return builder.take_root();
}

}  // namespace detail

TimelineEntry parse_control_line(const std::string& text, std::size_t line, const Scenario& running,
                                 const std::string& source) {
  const std::string& file = source;
  try {
    const detail::Node root = detail::json_tree(text, file);
    detail::EntryLines entry_lines;
    TimelineEntry e = detail::read_control_entry(root, file, entry_lines);
    // Checked as an entry of the running scenario at its start: the same validator as the files'.
    Scenario probe;
    probe.name = running.name;
    probe.duration = running.duration;
    probe.bus = running.bus;
    probe.devices = running.devices;
    // The bench's lines and controllers too: a device's lustbus address needs its line, and an
    // entry may name a DFS-1 controller.
    probe.lustbus = running.lustbus;
    probe.controller_line = running.controller_line;
    probe.controllers = running.controllers;
    probe.timeline = {e};
    detail::SourceMap lines;
    lines.entries = {entry_lines};
    detail::validate(probe, lines, file);
    e.source_line = line;
    return e;
  } catch (const ScenarioError& err) {
    // The text is one line: its own line 1 is the channel's line `line`.
    std::string what = err.what();
    const std::string prefix = file + ":" + std::to_string(err.line()) + ": ";
    if (what.starts_with(prefix)) what.erase(0, prefix.size());
    throw ScenarioError(file, line, what);
  }
}

Scenario parse_scenario_json(const std::string& text, const std::string& file) {
  const detail::Node root = detail::json_tree(text, file);
  detail::SourceMap lines;
  Scenario s = detail::read_tree(root, detail::Format::json, file, lines);
  detail::validate(s, lines, file);
  return s;
}

}  // namespace ibs::sim
