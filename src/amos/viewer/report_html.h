#pragma once
// report.html: one self-contained file in a run's output folder (data and script inside, no server, no network)
// with the trajectory against the ground truth (top and side views), ATE over time, RPE, the time per frame of
// each SLAM stage, the fraction of keypoints the dynamic mask removed per frame, a strip of mask overlays, the
// settings used and, after `run --dense`, a top view of the occupancy grid. The page (web/report_template.html)
// draws its plots as inline SVG from the JSON block
//   <script id="amos-report-data" type="application/json">{...}</script>
// that reportData() builds (its keys: see report_html.cc).
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "amos/viewer/report_recorder.h"

namespace amos::viewer {

struct ReportInputs {
  nlohmann::json stats;         // the run's stats.json
  std::string settings_file;    // --config
  std::string settings_text;    // its contents
  nlohmann::json run_options;   // the command line's choices (mode, source, ...)
};

nlohmann::json reportData(const ReportRecorder& recorder, const ReportInputs& inputs);
// Adds what `run --dense` left in `dir` (those present of mesh.ply, cloud.ply, removed_points.ply, occupancy.*):
// "dense_files" [{name, bytes}] and "occupancy" (occupancy_grid.h: occupancyReportJson; {error} when the grid
// cannot be read: a warning, report.html is written without it).
void addDenseProducts(const std::filesystem::path& dir, nlohmann::json& data);
// The page with `data` inside ("</" escaped so the JSON cannot end its script element).
std::string reportHtml(const nlohmann::json& data);
// Writes <dir>/report.html (under a temporary name, then renamed) with the dense products found in `dir`
// (addDenseProducts: call it after they are written); throws core::Error naming the file.
void writeReportHtml(const std::filesystem::path& dir, const ReportRecorder& recorder, const ReportInputs& inputs);

}  // namespace amos::viewer
