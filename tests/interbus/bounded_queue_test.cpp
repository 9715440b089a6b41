// The request queue of the parameter channels' master sides (interbus/bounded_queue.hpp).
#include <gtest/gtest.h>

#include "ibs/base/bounded_queue.hpp"

namespace ibs {
namespace {

TEST(BoundedQueue, IsFirstInFirstOutAcrossTheWrap) {
  BoundedQueue<int> q(3);
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.capacity(), 3U);
  int next_in = 0;
  int next_out = 0;
  // Many rounds of two in, one or two out: the head walks round the storage several times.
  for (int round = 0; round < 20; ++round) {
    while (!q.full()) ASSERT_TRUE(q.push(next_in++));
    EXPECT_FALSE(q.push(999)) << "a full queue refuses and keeps what it has";
    ASSERT_EQ(q.size(), 3U);
    for (std::size_t i = 0; i < q.size(); ++i) EXPECT_EQ(q[i], next_out + static_cast<int>(i));
    const int take = 1 + round % 2;
    for (int k = 0; k < take; ++k) {
      EXPECT_EQ(q.front(), next_out++);
      q.pop();
    }
  }
  while (!q.empty()) {
    EXPECT_EQ(q.front(), next_out++);
    q.pop();
  }
  EXPECT_EQ(next_out, next_in);
  q.pop();  // popping an empty queue changes nothing
  EXPECT_TRUE(q.empty());
  EXPECT_TRUE(q.push(7));
  EXPECT_EQ(q.front(), 7);
}

// clear (a CANLust node's power-on, a client's abort_all): empty at once, the whole capacity
// free again, wherever the front stood.
TEST(BoundedQueue, ClearEmptiesItAndFreesTheWholeCapacity) {
  BoundedQueue<int> q(3);
  EXPECT_TRUE(q.push(1));
  EXPECT_TRUE(q.push(2));
  q.pop();
  EXPECT_TRUE(q.push(3));
  q.clear();
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.size(), 0U);
  for (int v = 10; v < 13; ++v) EXPECT_TRUE(q.push(v));
  EXPECT_FALSE(q.push(13));
  for (int v = 10; v < 13; ++v) {
    EXPECT_EQ(q.front(), v);
    q.pop();
  }
}

}  // namespace
}  // namespace ibs
