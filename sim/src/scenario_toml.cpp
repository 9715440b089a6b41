// TOML scenarios: toml++ parses, this file turns its nodes into the line-carrying document tree.
#include <toml++/toml.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "ibs/sim/scenario.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim {

namespace detail {

namespace {

constexpr int kMaxDepth = 32;

std::size_t line_of(const toml::source_region& r) {
  return static_cast<std::size_t>(r.begin.line);
}

Node convert(const toml::node& n, std::size_t fallback_line, const std::string& file, int depth) {
  Node out;
  out.line = line_of(n.source());
  if (out.line == 0) out.line = fallback_line;
  if (depth > kMaxDepth) throw ScenarioError(file, out.line, "values nested too deeply");
  switch (n.type()) {
    case toml::node_type::table: {
      out.kind = Node::Kind::table;
      const toml::table& t = *n.as_table();
      // toml++ keeps keys sorted; put them back in source order so that the first problem in
      // the file is the one reported.
      std::vector<std::pair<const toml::key*, const toml::node*>> members;
      for (const auto& [key, value] : t) members.emplace_back(&key, &value);
      std::stable_sort(members.begin(), members.end(), [](const auto& a, const auto& b) {
        const toml::source_position& pa = a.first->source().begin;
        const toml::source_position& pb = b.first->source().begin;
        return pa.line != pb.line ? pa.line < pb.line : pa.column < pb.column;
      });
      for (const auto& [key, value] : members) {
        std::size_t key_line = line_of(key->source());
        if (key_line == 0) key_line = out.line;
        out.keys.emplace_back(key->str());
        out.key_lines.push_back(key_line);
        out.children.push_back(convert(*value, key_line, file, depth + 1));
      }
      break;
    }
    case toml::node_type::array:
      out.kind = Node::Kind::array;
      for (const toml::node& item : *n.as_array()) {
        out.children.push_back(convert(item, out.line, file, depth + 1));
      }
      break;
    case toml::node_type::string:
      out.kind = Node::Kind::string;
      out.text = n.as_string()->get();
      break;
    case toml::node_type::integer:
      out.kind = Node::Kind::integer;
      out.integer = n.as_integer()->get();
      break;
    case toml::node_type::floating_point:
      out.kind = Node::Kind::floating;
      out.floating = n.as_floating_point()->get();
      break;
    case toml::node_type::boolean:
      out.kind = Node::Kind::boolean;
      out.boolean = n.as_boolean()->get();
      break;
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
    case toml::node_type::none:
      out.kind = Node::Kind::datetime;
      break;
  }
  return out;
}

}  // namespace

Node toml_tree(const std::string& text, const std::string& file) {
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw ScenarioError(file, line_of(e.source()),
                        "TOML syntax error: " + std::string(e.description()));
  }
  return convert(root, 1, file, 0);
}

}  // namespace detail

Scenario parse_scenario_toml(const std::string& text, const std::string& file) {
  const detail::Node root = detail::toml_tree(text, file);
  detail::SourceMap lines;
  Scenario s = detail::read_tree(root, detail::Format::toml, file, lines);
  detail::validate(s, lines, file);
  return s;
}

}  // namespace ibs::sim
