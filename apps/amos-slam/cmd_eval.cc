// amos-slam eval: ATE / RPE of an estimated TUM trajectory against ground truth, with the TUM benchmark's
// conventions (evaluate_ate.py; evaluate_rpe.py --fixed_delta --delta 1 --delta_unit s), and the frame-to-frame
// jitter (RPE over one frame, step and path lengths). All work is in amos::eval.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "amos/eval/bonn_ground_truth.h"
#include "amos/eval/evaluate.h"
#include "amos/eval/svg_plot.h"
#include "amos/io/trajectory.h"
#include "commands.h"

namespace amos::app {
namespace {

namespace fs = std::filesystem;

struct EvalArgs {
  std::string gt_file, est_file, plot_file;
  bool json = false;
  bool bonn_gt = false;
  eval::EvaluationOptions options;
};

std::string statsRow(const char* name, const eval::ErrorStats& s, int decimals) {
  auto cell = [decimals](double v) { return fmt::format("{:>10.{}f}", v, decimals); };
  if (s.count == 0) return fmt::format("{:<15}{:>10}\n", name, "n/a (0 pairs)");
  return fmt::format("{:<15}{}{}{}{}{}{}{:>8}\n", name, cell(s.rmse), cell(s.mean), cell(s.median), cell(s.std_dev),
                     cell(s.min), cell(s.max), s.count);
}


std::string table(const EvalArgs& args, const eval::EvaluationResult& r) {
  std::string out;
  out += fmt::format("ground truth : {} ({} poses{})\n", args.gt_file, r.gt_poses,
                     args.bonn_gt ? ", Bonn marker poses converted to camera poses" : "");
  out += fmt::format("estimate     : {} ({} poses)\n", args.est_file, r.est_poses);
  out += fmt::format("alignment    : {} of the estimate onto the ground truth (Horn){}\n", r.sim3 ? "Sim(3)" : "SE(3)",
                     r.sim3 ? fmt::format(", scale {:.6f}", r.alignment.scale) : "");
  out += fmt::format("association  : max difference {} s; RPE over {} s, {}\n\n", args.options.max_time_difference_s,
                     r.rpe_delta_s, r.sim3 ? "estimate motions scaled by the Sim(3) scale" : "no alignment");
  out += fmt::format("{:<15}{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}{:>8}\n", "", "rmse", "mean", "median", "std", "min",
                     "max", "pairs");
  out += statsRow("ATE [m]", r.ate.error_m, 6);
  out += statsRow("RPE trans [m]", r.rpe.trans_m, 6);
  out += statsRow("RPE rot [deg]", r.rpe.rot_deg, 6);
  out += "\n" + eval::jitterLine(r.jitter);
  return out;
}

void runEval(const EvalArgs& args, int& exit_code) {
  std::vector<io::StampedPose> gt = io::readTumTrajectoryWithPoses(args.gt_file, "ground-truth file");
  if (args.bonn_gt) gt = eval::bonnMarkerToCamera(gt);
  const std::vector<io::StampedPose> est = io::readTumTrajectoryWithPoses(args.est_file, "estimate file");
  const eval::EvaluationResult result = eval::evaluate(gt, est, args.options);
  if (!args.plot_file.empty()) {
    const std::string title = fmt::format("{} vs {}{}", fs::path(args.est_file).filename().string(),
                                          fs::path(args.gt_file).filename().string(),
                                          args.bonn_gt ? " (Bonn marker poses converted to camera)" : "");
    eval::writeEvaluationSvg(args.plot_file, gt, est, result, title);
  }
  if (args.json) {
    nlohmann::json j = eval::toJson(result);
    j["gt_file"] = args.gt_file;
    j["est_file"] = args.est_file;
    j["bonn_gt"] = args.bonn_gt;
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << table(args, result);
    if (!args.plot_file.empty()) std::cout << "\nplot written to " << args.plot_file << "\n";
  }
  exit_code = 0;
}

}  // namespace

void addEvalCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<EvalArgs>();
  auto* cmd = app.add_subcommand(
      "eval",
      "Evaluate an estimated trajectory against ground truth (TUM format 'timestamp tx ty tz qx qy qz qw', "
      "camera-to-world): ATE after aligning the estimate onto the ground truth (Horn, rigid unless --sim3) and "
      "RPE over 1 s, reproducing the TUM benchmark's evaluate_ate.py and evaluate_rpe.py --fixed_delta");
  cmd->add_option("--gt", args->gt_file, "Ground-truth trajectory file (TUM format)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--est", args->est_file, "Estimated trajectory file (TUM format)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_flag("--json", args->json, "Print one JSON object instead of the table");
  cmd->add_option("--plot", args->plot_file,
                  "Write an SVG plot: top view of ground truth and aligned estimate, and ATE over time");
  cmd->add_flag("--sim3", args->options.sim3,
                "Align with a similarity (rotation, translation, scale), e.g. for monocular estimates; the scale "
                "also multiplies the estimate's motions for RPE");
  cmd->add_flag("--bonn-gt", args->bonn_gt,
                "The ground truth is a Bonn RGB-D Dynamic groundtruth.txt (marker poses): convert it to camera "
                "poses first (T_ROS^T * T_gt * T_ROS * T_m)");
  cmd->add_option("--max-difference", args->options.max_time_difference_s,
                  "Maximum time difference for associating stamps, seconds")
      ->capture_default_str();
  cmd->add_option("--rpe-delta", args->options.rpe_delta_s, "Time between the two poses of an RPE pair, seconds")
      ->capture_default_str();
  cmd->add_option("--time-offset", args->options.time_offset_s, "Seconds added to the estimate's stamps")
      ->capture_default_str();
  cmd->callback([args, &exit_code] { runEval(*args, exit_code); });
}

}  // namespace amos::app
