#include "amos/core/option_error.h"

#include <gtest/gtest.h>

namespace amos::core {
namespace {

struct Limits {
  double share = 0.5;
  float widen = 0.25f;
};

TEST(RequireInRange, AcceptsBothEndsAndNamesTheMemberOutside) {
  Limits limits;
  EXPECT_NO_THROW(requireInRange(limits.share, "share", 0.0, 1.0));
  limits.share = 0.0;
  EXPECT_NO_THROW(requireInRange(limits.share, "share", 0.0, 1.0));
  limits.share = 1.0;
  EXPECT_NO_THROW(requireInRange(limits.share, "share", 0.0, 1.0));
  limits.widen = 2.5f;
  try {
    requireInRange(limits.widen, "widen", 0.f, 2.f);
    FAIL() << "2.5 accepted in [0, 2]";
  } catch (const InvalidOption& e) {
    EXPECT_EQ(e.field().address, &limits.widen);
    EXPECT_EQ(e.rule(), "must be in [0, 2], got 2.5");
  }
  limits.share = -0.1;
  EXPECT_THROW(requireInRange(limits.share, "share", 0.0, 1.0), InvalidOption);
}

}  // namespace
}  // namespace amos::core
