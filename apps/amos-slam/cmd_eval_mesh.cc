// amos-slam eval-mesh: scores a dense map (a run's mesh.ply, `run --dense`) against the true static surface of the
// synthetic sequence it was made from (static_surface.ply and swept_volume.ply, written by `amos-slam synth`):
// accuracy, completeness, ghosts (off the static surface inside the movers' swept volume) and vertices off the
// static surface anywhere (eval/mesh_eval.h); and, on any sequence (--no-truth: a real one), the share of the
// mesh's vertices that the run's own frames see through (eval/see_through_share.h), with the camera, depth factor
// and Dense.* band of the run's settings (--settings, default settings_used.yaml beside the mesh). Prints one line
// per measure and writes the figures as JSON (--output, default mesh_eval.json beside the mesh). The scoring is in
// the dense plugin (run/dense_plugin.h), loaded by this command only; without the dense module (AMOS_WITH_OPEN3D
// off) it is an error.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"
#ifdef AMOS_HAVE_DENSE_PLUGIN
#include "amos/dense/dense_options.h"
#include "amos/run/dense_plugin_loader.h"
#include "amos/run/settings_sections.h"
#endif
#include "commands.h"

namespace amos::app {

namespace {

struct EvalMeshArgs {
  std::string mesh, sequence, trajectory, swept, output, ghosts, settings, seen_through;
  double tolerance = 0.04, max_depth = 4.0, sweep_margin = -1;
  bool no_truth = false;
};

#ifdef AMOS_HAVE_DENSE_PLUGIN
std::string besideTheMesh(const EvalMeshArgs& a, const std::string& given, const char* name) {
  return given.empty() ? (std::filesystem::path(a.mesh).parent_path() / name).string() : given;
}

eval::SeeThroughScore seenThrough(const EvalMeshArgs& a, const run::DensePlugin& dense) {
  const std::string settings_file = besideTheMesh(a, a.settings, "settings_used.yaml");
  core::require(std::filesystem::exists(settings_file),
                fmt::format("{} is missing: give the run's settings (camera, DepthMapFactor, Dense.*) with --settings",
                            settings_file));
  const config::Settings settings = run::loadSettings(settings_file);
  eval::SeeThroughRequest request;
  request.mesh = a.mesh;
  request.sequence = a.sequence;
  request.trajectory = besideTheMesh(a, a.trajectory, "trajectory.txt");
  request.camera = settings.camera;
  request.depth_factor = settings.depth_factor;
  request.dense = settings.section<dense::DenseOptions>();
  const eval::SeeThroughScore s = dense.evaluateSeeThrough(request);
  std::cout << fmt::format("seen through by the run's frames: {} of {} vertices ({:.2f} %; {} voted on), {} frames, "
                           "band {:.3f} m at 2 m\n",
                           s.seen_through, s.vertices, 100.0 * s.share, s.voted, s.frames, s.band_at_2m);
  return s;
}
#endif

void evalMesh(const EvalMeshArgs& a) {
#ifdef AMOS_HAVE_DENSE_PLUGIN
  const run::DensePlugin& dense = run::densePlugin();  // the scoring is in the dense plugin (Open3D)
  const eval::SeeThroughScore through = seenThrough(a, dense);
  nlohmann::json json = {{"seen_through", dense.seeThroughJson(through)}};
  if (!a.seen_through.empty()) dense.writePointsPly(a.seen_through, through.points);
  const std::string output = besideTheMesh(a, a.output, "mesh_eval.json");
  if (a.no_truth) {
    io::writeFileAtomically(output, json.dump(2) + "\n");
    return;
  }
  eval::MeshEvalRequest request;
  request.mesh = a.mesh;
  request.sequence = a.sequence;
  request.trajectory = a.trajectory;
  request.tolerance = a.tolerance;
  request.max_depth = a.max_depth;
  request.swept = a.swept;
  request.sweep_margin = a.sweep_margin;
  const eval::MeshScore s = dense.evaluateMesh(request);
  std::cout << fmt::format(
      "accuracy median {:.4f} m  p90 {:.4f} m;  completeness {:.3f};  ghosts {} of {} vertices ({:.2f} %), "
      "off the static surface {} ({:.2f} %);  tolerance {:.3f} m, sweep {:.3f} m^3 grown by {:.3f} m, {} truth "
      "points, ATE of the alignment {:.4f} m\n",
      s.accuracy_median_m, s.accuracy_p90_m, s.completeness, s.ghosts, s.vertices, 100.0 * s.ghost_share,
      s.off_surface, 100.0 * s.off_surface_share, s.tolerance_m, s.swept_volume_m3, s.sweep_margin_m, s.truth_points,
      s.ate_rmse_m);
  json.update(dense.meshScoreJson(s));
  io::writeFileAtomically(output, json.dump(2) + "\n");
  if (!a.ghosts.empty()) dense.writePointsPly(a.ghosts, s.ghost_points);
#else
  (void)a;
  throw core::Error("eval-mesh: this build has no dense module (install libopen3d-dev and rebuild)");
#endif
}

}  // namespace

void addEvalMeshCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<EvalMeshArgs>();
  auto* cmd = app.add_subcommand(
      "eval-mesh",
      "Score a dense map (run --dense) against a synthetic sequence's true static surface and movers' swept volume, "
      "and by the share of it the run's own frames see through");
  cmd->add_option("--mesh", args->mesh, "The run's mesh.ply")->required()->check(CLI::ExistingFile);
  cmd->add_option("--sequence", args->sequence,
                  "The sequence the run read; synthetic (static_surface.ply, swept_volume.ply, groundtruth.txt) "
                  "unless --no-truth")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--trajectory", args->trajectory, "The run's trajectory (default: trajectory.txt beside the mesh)");
  cmd->add_option("--tolerance", args->tolerance,
                  "Distance (m) within which a vertex is on the true surface and a true point is covered (default "
                  "0.04 = 2 voxels)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-depth", args->max_depth,
                  "True points seen only from farther than this (m) are left out (default 4 = Dense.maxDepth)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--swept", args->swept,
                  "The movers' swept volume (default: swept_volume.ply of the sequence); a static twin is scored "
                  "against its moving sibling's")
      ->check(CLI::ExistingFile);
  cmd->add_option("--sweep-margin", args->sweep_margin,
                  "Distance (m) by which the swept volume is grown (default: the tolerance)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--ghosts", args->ghosts, "Also write the ghost vertices (ground truth frame) to this PLY file");
  cmd->add_option("--output", args->output, "JSON file of the figures (default: mesh_eval.json beside the mesh)");
  cmd->add_flag("--no-truth", args->no_truth,
                "Only the share seen through by the run's own frames (a real sequence: no ground truth needed)");
  cmd->add_option("--settings", args->settings,
                  "The run's settings: camera, DepthMapFactor and the Dense.* band of the see-through vote (default: "
                  "settings_used.yaml beside the mesh)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--seen-through", args->seen_through,
                  "Also write the vertices seen through (the run's world frame) to this PLY file");
  cmd->callback([args, &exit_code] {
    evalMesh(*args);
    exit_code = 0;
  });
}

}  // namespace amos::app
