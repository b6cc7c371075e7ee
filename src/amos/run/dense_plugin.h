#pragma once
// The dense map's code that needs Open3D (dense/, run/dense_observer.h, eval/mesh_eval.h,
// eval/see_through_share.h) is a module that the
// program loads at run time (dense_plugin_loader.h), only for the commands that use it (`run --dense`,
// `eval-mesh`): Open3D and the ~80 libraries it brings (VTK, filament...) cost every other process ~35 MB and
// ~0.3 s at start-up. This is what the program sees of that module: plain interfaces, no Open3D type. The module
// (dense_plugin_module.cc) exports one C function, kDensePluginEntry, that returns its DensePlugin and the layout
// it was built with (DensePluginAbi), which the loader checks before using anything else.
#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "amos/dense/dense_mapper.h"
#include "amos/dense/dense_options.h"
#include "amos/eval/mesh_eval.h"
#include "amos/eval/see_through_share.h"
#include "amos/io/trajectory.h"
#include "amos/report/run_report.h"
#include "amos/run/run_observer.h"

namespace amos::run {

// `run --dense`'s observer (dense_observer.h): the frames to the fusion thread, then the final map and its files.
class DenseRunMap : public RunObserver {
 public:
  // See DenseObserver::finishMap. Never throws.
  virtual report::OptionalStage finishMap(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info,
                                          const std::atomic<bool>* stop) = 0;
};

class DensePlugin {
 public:
  virtual ~DensePlugin() = default;
  // DenseObserver::outputNames: the files `run --dense` adds to the output folder.
  virtual std::vector<std::string> denseOutputNames() const = 0;
  // A DenseObserver. Throws core::Error on options it rejects.
  virtual std::unique_ptr<DenseRunMap> makeDenseRunMap(const dense::DenseOptions& options, std::string output_dir,
                                                       dense::LiveCloudCallback on_live_cloud) const = 0;
  // eval::evaluateMesh, eval::toJson and eval::writePointsPly (eval-mesh).
  virtual eval::MeshScore evaluateMesh(const eval::MeshEvalRequest& request) const = 0;
  virtual nlohmann::json meshScoreJson(const eval::MeshScore& score) const = 0;
  virtual void writePointsPly(const std::string& path, const std::vector<Eigen::Vector3d>& points) const = 0;
  // eval::evaluateSeeThrough and its eval::toJson (eval-mesh's seen-through share, with or without ground truth).
  virtual eval::SeeThroughScore evaluateSeeThrough(const eval::SeeThroughRequest& request) const = 0;
  virtual nlohmann::json seeThroughJson(const eval::SeeThroughScore& score) const = 0;
};

// What the module was built with. The version is raised whenever this file's interfaces change; the sizes catch a
// module built from sources whose option or score structs differ from the program's (a stale build tree), which
// would otherwise crash instead of failing with a message.
struct DensePluginAbi {
  int version = 2;
  std::size_t options_size = sizeof(dense::DenseOptions);
  std::size_t request_size = sizeof(eval::MeshEvalRequest);
  std::size_t score_size = sizeof(eval::MeshScore);
  std::size_t see_through_request_size = sizeof(eval::SeeThroughRequest);
  std::size_t see_through_score_size = sizeof(eval::SeeThroughScore);
  std::size_t stage_size = sizeof(report::OptionalStage);
  std::size_t info_size = sizeof(report::RunInfo);

  bool operator==(const DensePluginAbi& o) const {
    return version == o.version && options_size == o.options_size && request_size == o.request_size &&
           score_size == o.score_size && see_through_request_size == o.see_through_request_size &&
           see_through_score_size == o.see_through_score_size && stage_size == o.stage_size && info_size == o.info_size;
  }
};

// The module's entry point: `const DensePlugin* amos_dense_plugin(DensePluginAbi* built_with)`. Its C signature
// never changes, so that a program can always call it to learn the module's ABI.
inline constexpr const char* kDensePluginEntry = "amos_dense_plugin";
using DensePluginEntry = const DensePlugin* (*)(DensePluginAbi* built_with);

}  // namespace amos::run
