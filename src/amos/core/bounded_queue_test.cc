#include "amos/core/bounded_queue.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

namespace amos::core {
namespace {

TEST(BoundedQueue, DeliversInOrderAcrossThreadsAndDrainsAfterClose) {
  BoundedQueue<int> q(2);
  std::thread producer([&] {
    for (int i = 0; i < 100; ++i) ASSERT_TRUE(q.push(i));
    q.close();
  });
  std::vector<int> got;
  while (auto v = q.pop()) got.push_back(*v);
  producer.join();
  ASSERT_EQ(got.size(), 100u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(got[i], i);
}

TEST(BoundedQueue, PushFailsAfterClose) {
  BoundedQueue<int> q(1);
  q.close();
  EXPECT_FALSE(q.push(1));
  EXPECT_FALSE(q.pop().has_value());
}

}  // namespace
}  // namespace amos::core
