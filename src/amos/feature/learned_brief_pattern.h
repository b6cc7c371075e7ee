#pragma once
// The default descriptor test pattern: 256 point pairs learned with learnBriefPattern (brief_pattern_learning.h),
// our own table (not ORB's or OpenCV's).
#include <vector>

#include "amos/feature/steered_brief.h"

namespace amos::feature {

const std::vector<BriefPair>& learnedBriefPattern();

}  // namespace amos::feature
