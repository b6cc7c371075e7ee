#include "amos/report/mover_diagnosis.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <ostream>

#include "amos/core/camera.h"
#include "amos/core/error.h"
#include "amos/dynamic/baseline_history.h"
#include "amos/dynamic/dynamic_front_end.h"
#include "amos/dynamic/mask_building.h"
#include "amos/dynamic/mover_diagnostics.h"
#include "amos/eval/ground_truth_masks.h"
#include "amos/evidence/evidence_sources.h"
#include "amos/io/dataset.h"
#include "amos/io/image_codecs.h"
#include "amos/io/trajectory.h"

namespace amos::report {

namespace {
// The true pose nearest t (the synthetic truth has a pose at every frame's time stamp).
core::SE3 truthAt(const std::vector<io::StampedPose>& truth, double t) {
  const auto it = std::lower_bound(truth.begin(), truth.end(), t,
                                   [](const io::StampedPose& p, double s) { return p.timestamp < s; });
  const io::StampedPose* best = nullptr;
  if (it != truth.end()) best = &*it;
  if (it != truth.begin() && (!best || std::fabs((it - 1)->timestamp - t) < std::fabs(best->timestamp - t)))
    best = &*(it - 1);
  core::require(best && std::fabs(best->timestamp - t) < 0.005,
                fmt::format("diagnose-movers: no ground-truth pose within 5 ms of frame time {:.6f}", t));
  return best->T_wc;
}

}  // namespace

cv::Mat decisionPicture(const cv::Mat& bgr, const cv::Mat& truth_ids, const dynamic::FrontEndResult& result) {
  core::require(bgr.type() == CV_8UC3, "decisionPicture: the frame must be CV_8UC3");
  core::require(truth_ids.type() == CV_16U && truth_ids.size() == bgr.size(),
                "decisionPicture: the truth must be CV_16U of the frame's size");
  core::require(result.mask.type() == CV_8U && result.mask.size() == bgr.size(),
                "decisionPicture: the mask must be CV_8U of the frame's size");
  cv::Mat pic = bgr * 0.6;
  for (int y = 0; y < pic.rows; ++y) {
    const std::uint8_t* m = result.mask.ptr<std::uint8_t>(y);
    const std::uint16_t* t = truth_ids.ptr<std::uint16_t>(y);
    auto* p = pic.ptr<cv::Vec3b>(y);
    for (int x = 0; x < pic.cols; ++x) {
      const bool marked = m[x] != 0, mover = t[x] != 0;
      if (!marked && !mover) continue;
      const cv::Vec3b tint = marked && mover ? cv::Vec3b(0, 160, 0) : marked ? cv::Vec3b(0, 0, 200) : cv::Vec3b(200, 0, 0);
      p[x] = p[x] * 0.5 + tint;
    }
  }
  if (!result.cluster_map.empty() && !result.dynamic_cluster.empty()) {
    cv::Mat dynamic_clusters(result.cluster_map.size(), CV_8U, cv::Scalar(0));
    dynamic::markLabelledPixels(result.cluster_map, result.dynamic_cluster, dynamic_clusters);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(dynamic_clusters, contours, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(pic, contours, -1, cv::Scalar(255, 255, 255), 1);
  }
  const double bar = std::max(result.diagnostics.confirm_threshold_px, 0.5);
  for (std::size_t i = 0; i < result.tracks.size(); ++i) {
    const auto& e = i < result.judged_error_px.size() ? result.judged_error_px[i] : std::nullopt;
    const cv::Scalar colour = !e                ? cv::Scalar(160, 160, 160)
                              : *e < bar        ? cv::Scalar(0, 255, 0)
                              : *e < 3 * bar    ? cv::Scalar(0, 255, 255)
                                                : cv::Scalar(0, 0, 255);
    cv::circle(pic, result.tracks[i].current, 2, colour, cv::FILLED);
  }
  return pic;
}

MoverDiagnosisSummary diagnoseSequenceMovers(const config::Settings& settings, const MoverDiagnosisOptions& options,
                                             std::ostream& out) {
  io::SequenceIndex index = io::indexSequence(options.sequence_dir);
  core::require(!index.groundtruth_file.empty(), "diagnose-movers: " + options.sequence_dir + " has no groundtruth.txt");
  const std::vector<io::StampedPose> truth = io::readTumTrajectoryWithPoses(index.groundtruth_file, "ground-truth file");
  const auto masks = eval::GroundTruthMasks::find(options.sequence_dir);
  core::require(masks.has_value(), "diagnose-movers: " + options.sequence_dir + " has no masks.txt / instances.json");
  MoverDiagnosisSummary summary;
  for (const eval::GroundTruthInstance& inst : masks->instances()) summary.instances[inst.id].name = inst.name;

  dynamic::DynamicOptions dyn = settings.dynamic;
  dyn.mode = dynamic::DynamicMode::kGeometry;
  const core::PinholeCamera camera(settings.camera);
  const dynamic::DynamicFrontEnd front_end(camera, dyn, evidence::makeEvidenceSources(camera, dyn));
  io::SequenceReader reader(std::move(index), settings.readerOptions());
  if (options.per_frame)
    out << "frame id name pixels marked tracks scored init_px judged_px epi_viol base_moving/base_points base_px "
           "cause | clusters: "
           "c<id>:<mover share of cluster>/<share of mover> n<tracks> i<initial px>[C] r<refit px>[K] [D]\n";
  cv::Mat last_gray, last_depth, last_mask;
  core::SE3 T_cw_last, T_cw_before;
  // As the pipeline keeps it.
  dynamic::BaselineHistory baseline_history(dyn.depth.baseline_frames);
  bool have_before = false;
  if (!options.images_dir.empty()) std::filesystem::create_directories(options.images_dir);
  while (auto frame = reader.next()) {
    const int k = static_cast<int>(frame->index);
    if (options.last_frame >= 0 && k > options.last_frame) break;
    cv::Mat gray;
    cv::cvtColor(frame->bgr, gray, cv::COLOR_BGR2GRAY);
    const core::SE3 T_cw = truthAt(truth, frame->timestamp).inverse();
    if (k >= options.first_frame && !last_gray.empty()) {
      dynamic::FrontEndInput in;
      in.gray = gray, in.bgr = frame->bgr, in.depth = frame->depth;
      in.last_gray = last_gray, in.last_depth = last_depth, in.last_mask = last_mask;
      in.T_cw_last = T_cw_last;
      if (const auto* baseline = baseline_history.baseline()) {
        in.baseline_depth = baseline->depth;
        in.baseline_gray = baseline->gray;
        in.T_cw_baseline = baseline->T_cw;
      }
      in.T_cw_initial = options.exact_initial ? T_cw
                        : have_before        ? T_cw_last * T_cw_before.inverse() * T_cw_last
                                             : T_cw_last;
      const dynamic::FrontEndResult result = front_end.process(in);
      last_mask = result.mask;
      const auto mk = masks->frameAt(frame->timestamp);
      if (mk) {
        const cv::Mat ids = masks->instanceMask(*mk);
        if (!options.images_dir.empty()) {
          const std::string file = fmt::format("{}/{:04d}.png", options.images_dir, k);
          io::writeImage(file, decisionPicture(frame->bgr, ids, result));
        }
        for (const dynamic::MoverFrameDiagnosis& d :
             dynamic::diagnoseMovers(result, ids, masks->movingIds(*mk), dyn)) {
          auto& s = summary.instances[d.id];
          ++s.frames;
          s.pixels += d.pixels;
          s.marked += d.marked;
          ++s.causes[d.cause];
          if (!options.per_frame) continue;
          out << fmt::format("{} {} {} {} {} {} {} {:.2f} {:.2f} {} {}/{} {:.2f} {} |", k, d.id, s.name, d.pixels,
                             d.marked, d.tracks, d.tracks_scored, d.median_initial_px, d.median_judged_px,
                             d.epipolar_violators, d.baseline_moving, d.baseline_points, d.median_baseline_px,
                             d.cause);
          for (std::size_t i = 0; i < d.clusters.size() && i < 4; ++i) {
            const auto& c = d.clusters[i];
            out << fmt::format(" c{}:{:.2f}/{:.2f} n{} i{:.1f}{} r{:.1f}{}{}", c.cluster,
                               c.cluster_px ? double(c.overlap_px) / c.cluster_px : 0.0,
                               d.pixels ? double(c.overlap_px) / d.pixels : 0.0, c.tracks, c.initial_px,
                               c.candidate ? "C" : "", c.confirm_px, c.confirmed ? "K" : "", c.dynamic ? " D" : "");
          }
          out << fmt::format("  [refit {} sigma {:.2f} thr {:.2f} baseline bar {:.2f} rigid {}/{}]\n",
                             result.diagnostics.pose_refit_ok ? "ok" : "no", result.diagnostics.pose_refit_sigma_px,
                             result.diagnostics.confirm_threshold_px, result.baseline_bar_px,
                             result.diagnostics.rigid_movers, result.diagnostics.rigid_superpixels);
        }
      }
    } else {
      last_mask.release();
    }
    if (!last_gray.empty()) T_cw_before = T_cw_last, have_before = true;
    last_gray = gray, last_depth = frame->depth, T_cw_last = T_cw;
    baseline_history.add({frame->depth, gray, {}, T_cw});
    if ((k + 1) % 50 == 0) spdlog::info("diagnose-movers: frame {}", k + 1);
  }
  out << "\nid name frames recall causes\n";
  for (const auto& [id, s] : summary.instances) {
    out << fmt::format("{} {} {} {:.3f}", id, s.name, s.frames, s.pixels ? double(s.marked) / s.pixels : 0.0);
    for (const auto& [cause, n] : s.causes) out << fmt::format(" {}={}", cause, n);
    out << "\n";
  }
  return summary;
}

}  // namespace amos::report
