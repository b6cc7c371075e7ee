#include "amos/eval/svg_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>

#include "amos/core/error.h"
#include "amos/eval/associate.h"

namespace amos::eval {
namespace {

constexpr double kWidth = 1200, kHeight = 660;
constexpr const char* kGtColour = "#222222";
constexpr const char* kEstColour = "#1f6fd1";
constexpr const char* kErrColour = "#d62728";

std::string escapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Plot rectangle in pixels and the data window mapped onto it (y up in data, down in SVG).
struct Frame {
  double left, top, width, height;
  double x0, x1, y0, y1;
  double px(double x) const { return left + (x - x0) / (x1 - x0) * width; }
  double py(double y) const { return top + height - (y - y0) / (y1 - y0) * height; }
};

// About `target` round tick values (1, 2, 5 x 10^k) covering [lo, hi].
std::vector<double> niceTicks(double lo, double hi, int target) {
  const double raw = (hi - lo) / std::max(target, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * magnitude;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) {
    ticks.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  }
  return ticks;
}

void drawAxes(std::string& svg, const Frame& f, const std::string& x_label, const std::string& y_label) {
  svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="white" stroke="#444"/>)"
                     "\n",
                     f.left, f.top, f.width, f.height);
  for (double x : niceTicks(f.x0, f.x1, 6)) {
    const double px = f.px(x);
    svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}" stroke="#e3e3e3"/>)"
                       R"(<text x="{0:.1f}" y="{3:.1f}" text-anchor="middle" font-size="12">{4:g}</text>)"
                       "\n",
                       px, f.top, f.top + f.height, f.top + f.height + 16, x);
  }
  for (double y : niceTicks(f.y0, f.y1, 6)) {
    const double py = f.py(y);
    svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{2:.1f}" y2="{1:.1f}" stroke="#e3e3e3"/>)"
                       R"(<text x="{3:.1f}" y="{4:.1f}" text-anchor="end" font-size="12">{5:g}</text>)"
                       "\n",
                       f.left, py, f.left + f.width, f.left - 6, py + 4, y);
  }
  svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle" font-size="14">{}</text>)"
                     "\n",
                     f.left + f.width / 2, f.top + f.height + 38, escapeXml(x_label));
  svg += fmt::format(R"(<text x="{0:.1f}" y="{1:.1f}" text-anchor="middle" font-size="14" )"
                     R"svg(transform="rotate(-90 {0:.1f} {1:.1f})">{2}</text>)svg"
                     "\n",
                     f.left - 52, f.top + f.height / 2, escapeXml(y_label));
}

// Polyline(s) through the points, broken where consecutive stamps are further apart than twice the median
// interval (as evaluate_ate.py's plot does), dropping points closer than half a pixel to the previous one.
void drawTrack(std::string& svg, const Frame& f, const std::vector<double>& stamps,
               const std::vector<Eigen::Vector2d>& points, const std::string& style) {
  if (points.empty()) return;
  std::vector<double> gaps;
  for (std::size_t i = 1; i < stamps.size(); ++i) gaps.push_back(stamps[i] - stamps[i - 1]);
  double max_gap = std::numeric_limits<double>::infinity();
  if (!gaps.empty()) {
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    max_gap = 2.0 * gaps[gaps.size() / 2];
  }
  std::string path;
  Eigen::Vector2d last_px(-1e9, -1e9);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d p(f.px(points[i].x()), f.py(points[i].y()));
    const bool new_segment = i == 0 || stamps[i] - stamps[i - 1] > max_gap;
    if (!new_segment && (p - last_px).norm() < 0.5 && i + 1 != points.size()) continue;
    path += fmt::format("{}{:.1f},{:.1f} ", new_segment ? "M" : "L", p.x(), p.y());
    last_px = p;
  }
  svg += fmt::format(R"(<path d="{}" fill="none" {}/>)"
                     "\n",
                     path, style);
  // Sparse tracks (e.g. keyframes only) would show as broken fragments or nothing: mark every sample.
  if (points.size() <= 300) {
    std::string marks;
    for (const auto& p : points) {
      marks += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="2.2"/>)", f.px(p.x()), f.py(p.y()));
    }
    const auto colour_begin = style.find("stroke=\"");
    const std::string colour =
        colour_begin == std::string::npos
            ? std::string("black")
            : style.substr(colour_begin + 8, style.find('"', colour_begin + 8) - colour_begin - 8);
    svg += fmt::format(R"(<g fill="{}">{}</g>)"
                       "\n",
                       colour, marks);
  }
}

// A one-row legend (line sample + label per entry) starting at (x, y), outside the plot so it hides no data.
void drawLegend(std::string& svg, double x, double y, const std::vector<std::pair<std::string, std::string>>& entries) {
  for (const auto& [label, style] : entries) {
    svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" {}/>)"
                       R"(<text x="{:.1f}" y="{:.1f}" font-size="13">{}</text>)"
                       "\n",
                       x, y - 4, x + 28, y - 4, style, x + 34, y, escapeXml(label));
    x += 34 + 7.5 * static_cast<double>(label.size()) + 24;  // rough text width at 13 px
  }
}

// Long titles (full paths) are shortened from the left so that the end, usually the file names, stays visible.
std::string shortened(const std::string& text, std::size_t max_chars) {
  if (text.size() <= max_chars) return text;
  return "..." + text.substr(text.size() - (max_chars - 3));
}

std::string formatMetric(double value, const char* unit, int decimals) {
  return std::isfinite(value) ? fmt::format("{:.{}f} {}", value, decimals, unit) : std::string("n/a");
}

}  // namespace

std::string renderEvaluationSvg(const std::vector<io::StampedPose>& gt_raw, const std::vector<io::StampedPose>& est_raw,
                                const EvaluationResult& result, const std::string& title) {
  const AteResult& ate = result.ate;
  core::require(!ate.gt_stamps.empty(), "plot: the evaluation has no associated pairs");
  const std::vector<io::StampedPose> gt = sortedUniqueByTimestamp(gt_raw);
  const std::vector<io::StampedPose> est = sortedUniqueByTimestamp(est_raw);

  // Ground truth within the associated span; the whole estimate, aligned.
  const double t_begin = ate.gt_stamps.front(), t_end = ate.gt_stamps.back();
  std::vector<double> gt_stamps, est_stamps;
  std::vector<Eigen::Vector3d> gt_xyz, est_xyz;
  for (const io::StampedPose& p : gt) {
    if (p.timestamp < t_begin || p.timestamp > t_end) continue;
    gt_stamps.push_back(p.timestamp);
    gt_xyz.push_back(p.T_wc.translation());
  }
  for (const io::StampedPose& p : est) {
    est_stamps.push_back(p.timestamp);
    est_xyz.push_back(result.alignment.apply(Eigen::Vector3d(p.T_wc.translation())));
  }

  // The two axes along which the ground truth extends most, in x, y, z order.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : ate.gt_positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d extent = hi - lo;
  int dropped = 0;
  extent.minCoeff(&dropped);
  std::array<int, 2> axes{};
  for (int k = 0, n = 0; k < 3; ++k) {
    if (k != dropped) axes[n++] = k;
  }
  const char* axis_names = "xyz";
  auto project = [&](const std::vector<Eigen::Vector3d>& xyz) {
    std::vector<Eigen::Vector2d> out;
    out.reserve(xyz.size());
    for (const auto& p : xyz) out.emplace_back(p[axes[0]], p[axes[1]]);
    return out;
  };
  const std::vector<Eigen::Vector2d> gt_2d = project(gt_xyz), est_2d = project(est_xyz);
  const std::vector<Eigen::Vector2d> pair_gt_2d = project(ate.gt_positions);
  const std::vector<Eigen::Vector2d> pair_est_2d = project(ate.est_positions_aligned);

  // Top view frame: equal scale, data window centred with a margin.
  Frame top{90, 90, 470, 470, 0, 1, 0, 1};
  {
    Eigen::Vector2d mn = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), mx = -mn;
    for (const auto* list : {&gt_2d, &est_2d, &pair_gt_2d}) {
      for (const auto& p : *list) {
        mn = mn.cwiseMin(p);
        mx = mx.cwiseMax(p);
      }
    }
    const double span = std::max({mx.x() - mn.x(), mx.y() - mn.y(), 1e-3}) * 1.08;
    const Eigen::Vector2d centre = 0.5 * (mn + mx);
    top.x0 = centre.x() - span / 2;
    top.x1 = centre.x() + span / 2;
    top.y0 = centre.y() - span / 2;
    top.y1 = centre.y() + span / 2;
  }
  // Error-over-time frame.
  Frame err{680, 90, 480, 470, 0, 1, 0, 1};
  {
    err.x1 = std::max(t_end - t_begin, 1e-3);
    const double max_error = *std::max_element(ate.errors_m.begin(), ate.errors_m.end());
    err.y1 = std::max(max_error, 1e-6) * 1.1;
  }

  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0:.0f}" height="{1:.0f}" viewBox="0 0 {0:.0f} {1:.0f}" )"
      R"(font-family="DejaVu Sans, Arial, sans-serif">)"
      "\n"
      R"(<rect width="100%" height="100%" fill="white"/>)"
      "\n",
      kWidth, kHeight);
  const std::string heading = title.empty() ? std::string("Trajectory evaluation") : title;
  svg += fmt::format(R"(<text x="{:.1f}" y="30" text-anchor="middle" font-size="18" font-weight="bold">{}</text>)"
                     "\n",
                     kWidth / 2, escapeXml(shortened(heading, 110)));
  const std::string summary = fmt::format(
      "ATE RMSE {} ({} pairs, {})   RPE ({:g} s) {} / {} ({} pairs)", formatMetric(result.ate_rmse_m, "m", 6),
      result.ate_pairs,
      result.sim3 ? fmt::format("Sim(3) alignment, scale {:.4f}", result.alignment.scale) : "SE(3) alignment",
      result.rpe_delta_s, formatMetric(result.rpe_trans_rmse_m, "m", 6),
      formatMetric(result.rpe_rot_rmse_deg, "deg", 4), result.rpe_pairs);
  svg += fmt::format(R"(<text x="{:.1f}" y="56" text-anchor="middle" font-size="15">{}</text>)"
                     "\n",
                     kWidth / 2, escapeXml(summary));

  // Left panel: top view.
  drawAxes(svg, top, fmt::format("{} [m]", axis_names[axes[0]]), fmt::format("{} [m]", axis_names[axes[1]]));
  svg +=
      fmt::format(R"(<svg x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" viewBox="{:.1f} {:.1f} {:.1f} {:.1f}">)"
                  "\n",
                  top.left, top.top, top.width, top.height, top.left, top.top, top.width, top.height);  // clip
  std::string differences;
  for (std::size_t i = 0; i < pair_gt_2d.size(); ++i) {
    differences += fmt::format("M{:.1f},{:.1f} L{:.1f},{:.1f} ", top.px(pair_gt_2d[i].x()), top.py(pair_gt_2d[i].y()),
                               top.px(pair_est_2d[i].x()), top.py(pair_est_2d[i].y()));
  }
  svg += fmt::format(R"(<path d="{}" stroke="{}" stroke-width="0.6" stroke-opacity="0.45" fill="none"/>)"
                     "\n",
                     differences, kErrColour);
  drawTrack(svg, top, gt_stamps, gt_2d, fmt::format(R"(stroke="{}" stroke-width="1.6")", kGtColour));
  drawTrack(svg, top, est_stamps, est_2d, fmt::format(R"(stroke="{}" stroke-width="1.3")", kEstColour));
  svg += "</svg>\n";
  drawLegend(svg, top.left, top.top + top.height + 70,
             {{"ground truth", fmt::format(R"(stroke="{}" stroke-width="2")", kGtColour)},
              {"estimate (aligned)", fmt::format(R"(stroke="{}" stroke-width="2")", kEstColour)},
              {"difference", fmt::format(R"(stroke="{}" stroke-width="1.5" stroke-opacity="0.6")", kErrColour)}});
  svg += fmt::format(R"(<text x="{:.1f}" y="82" text-anchor="middle" font-size="14">top view (equal scale)</text>)"
                     "\n",
                     top.left + top.width / 2);

  // Right panel: ATE error over time.
  drawAxes(svg, err, fmt::format("time since {:.2f} [s]", t_begin), "ATE error [m]");
  std::vector<Eigen::Vector2d> error_points;
  for (std::size_t i = 0; i < ate.errors_m.size(); ++i) {
    error_points.emplace_back(ate.gt_stamps[i] - t_begin, ate.errors_m[i]);
  }
  drawTrack(svg, err, ate.gt_stamps, error_points, fmt::format(R"(stroke="{}" stroke-width="1.2")", kErrColour));
  const double rmse_y = err.py(result.ate_rmse_m);
  svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#555" stroke-dasharray="6,4"/>)"
                     "\n",
                     err.left, rmse_y, err.left + err.width, rmse_y);
  drawLegend(svg, err.left, err.top + err.height + 70,
             {{"error per pair", fmt::format(R"(stroke="{}" stroke-width="2")", kErrColour)},
              {fmt::format("RMSE {:.4f} m", result.ate_rmse_m), R"(stroke="#555" stroke-dasharray="6,4")"}});
  svg += fmt::format(R"(<text x="{:.1f}" y="82" text-anchor="middle" font-size="14">ATE over time</text>)"
                     "\n",
                     err.left + err.width / 2);
  svg += "</svg>\n";
  return svg;
}

void writeEvaluationSvg(const std::string& path, const std::vector<io::StampedPose>& gt,
                        const std::vector<io::StampedPose>& est, const EvaluationResult& result,
                        const std::string& title) {
  const std::string svg = renderEvaluationSvg(gt, est, result, title);
  std::ofstream out(path);
  core::require(out.is_open(), fmt::format("cannot write plot '{}'", path));
  out << svg;
  out.close();
  core::require(!out.fail(), fmt::format("error while writing plot '{}'", path));
}

}  // namespace amos::eval
