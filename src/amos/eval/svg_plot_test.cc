#include "amos/eval/svg_plot.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

namespace amos::eval {
namespace {

std::size_t countOf(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + 1)) ++n;
  return n;
}

TEST(SvgPlot, DrawsBothPanelsWithLabelsLegendAndTitle) {
  // A trajectory in the x-z plane (y nearly constant): the top view must use x and z.
  std::vector<io::StampedPose> gt, est;
  for (int k = 0; k < 300; ++k) {
    const double t = k / 30.0;
    io::StampedPose p;
    p.timestamp = 100 + t;
    p.T_wc.translation() = Eigen::Vector3d(std::cos(t), 0.01 * std::sin(3 * t), 2 * std::sin(t));
    gt.push_back(p);
    p.T_wc.translation() += Eigen::Vector3d(0.02 * std::sin(5 * t), 0, 0.01);
    est.push_back(p);
  }
  const EvaluationResult r = evaluate(gt, est);
  const std::string svg = renderEvaluationSvg(gt, est, r, "demo <run> & test");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(countOf(svg, "<svg"), countOf(svg, "</svg>"));
  EXPECT_NE(svg.find("x [m]"), std::string::npos);
  EXPECT_NE(svg.find("z [m]"), std::string::npos);
  EXPECT_EQ(svg.find("y [m]"), std::string::npos);
  EXPECT_NE(svg.find("ATE error [m]"), std::string::npos);
  EXPECT_NE(svg.find("ground truth"), std::string::npos);
  EXPECT_NE(svg.find("estimate (aligned)"), std::string::npos);
  EXPECT_NE(svg.find(fmt::format("ATE RMSE {:.6f} m", r.ate_rmse_m)), std::string::npos);
  EXPECT_NE(svg.find("demo &lt;run&gt; &amp; test"), std::string::npos);  // escaped title
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

}  // namespace
}  // namespace amos::eval
