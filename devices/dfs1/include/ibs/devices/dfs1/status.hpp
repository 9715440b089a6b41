// The names of the DFS-1's status bits (command 81's ST2 and ST1, bit 7 down; docs/dfs1.md,
// "Status"), as the command line and its JSON print them: a fact of this controller, so here
// beside the bits (controller.hpp) and not in each program that shows them.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace ibs::devices::dfs1 {

// The names of the bits set in ST2 / ST1, the highest bit first; empty when none is set.
std::vector<std::string_view> st2_flags(std::uint8_t st2);
std::vector<std::string_view> st1_flags(std::uint8_t st1);

}  // namespace ibs::devices::dfs1
