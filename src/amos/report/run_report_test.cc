#include "amos/report/run_report.h"

#include <gtest/gtest.h>

namespace amos::report {
namespace {

TEST(RunReport, StatsJsonReportsTheAssociationFileRowsBeyondTheWindow) {
  const system::SlamStats stats;
  const core::StageTimes times;
  RunInfo info;
  EXPECT_FALSE(statsJson(stats, times, info).contains("association"));
  info.association = io::AssociationStats{"seq/associations.txt", 270, 3, 0.02, 2};
  const nlohmann::json j = statsJson(stats, times, info);
  ASSERT_TRUE(j.contains("association"));
  EXPECT_EQ(j["association"]["file"], "seq/associations.txt");
  EXPECT_EQ(j["association"]["rows"], 270);
  EXPECT_EQ(j["association"]["rows_beyond_window"], 3);
  EXPECT_EQ(j["association"]["duplicate_rows"], 2);
  EXPECT_DOUBLE_EQ(j["association"]["window_s"].get<double>(), 0.02);
}

}  // namespace
}  // namespace amos::report
