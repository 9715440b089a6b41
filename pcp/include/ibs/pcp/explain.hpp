// Human-readable readings of PCP channel frames, for trace remarks, `decode` and mismatch
// reports (allocates: never on the cycle path).
#pragma once

#include <span>
#include <string>

#include "ibs/base/words.hpp"
#include "ibs/pcp/link.hpp"

namespace ibs::pcp {

// One frame: `FIRST s0 a3: 00 81 00 (Read.req)`, `IDLE a2`, `ABORT`, or what is wrong with it.
// `expected` is the direction the frame should carry.
std::string explain_frame(std::span<const Word> words, Direction expected);

}  // namespace ibs::pcp
