// Colour and depth paired by stamp as they arrive: the nearest waiting partner within the window, older ones let go.
#include "stamp_pairer.h"

#include <boost/make_shared.hpp>
#include <gtest/gtest.h>

namespace amos::node {
namespace {

sensor_msgs::ImageConstPtr image(double t) {
  auto m = boost::make_shared<sensor_msgs::Image>();
  m->header.stamp.fromSec(t);
  return m;
}

TEST(StampPairer, PairsTheNearestWaitingMessageAtOnce) {
  StampPairer pairer(10, 0.02);
  EXPECT_FALSE(pairer.addDepth(image(10.000)));
  EXPECT_FALSE(pairer.addDepth(image(10.030)));
  const auto pair = pairer.addColour(image(10.025));
  ASSERT_TRUE(pair);
  EXPECT_DOUBLE_EQ(pair->second->header.stamp.toSec(), 10.030);
  // 10.000 was older than the pair: let go, so a late colour image cannot take it.
  EXPECT_FALSE(pairer.addColour(image(10.001)));
}

TEST(StampPairer, NothingBeyondTheWindow) {
  StampPairer pairer(10, 0.02);
  EXPECT_FALSE(pairer.addColour(image(5.0)));
  EXPECT_FALSE(pairer.addDepth(image(5.05)));
  const auto pair = pairer.addColour(image(5.06));
  ASSERT_TRUE(pair);
  EXPECT_DOUBLE_EQ(pair->first->header.stamp.toSec(), 5.06);
}

TEST(StampPairer, QueueIsBounded) {
  StampPairer pairer(2, 0.02);
  for (double t : {1.0, 2.0, 3.0}) EXPECT_FALSE(pairer.addColour(image(t)));
  EXPECT_FALSE(pairer.addDepth(image(1.0)));  // the oldest colour image was let go
  EXPECT_TRUE(pairer.addDepth(image(2.0)));
}

}  // namespace
}  // namespace amos::node
