// The dense plugin (dense_plugin.h): the module libamos_dense_plugin.so, which holds the code that needs Open3D
// (dense/, run/dense_observer.h, eval/mesh_eval.h) behind thin adapters. Not part of amos_run: built alone as a
// MODULE (run/CMakeLists.txt) and loaded by dense_plugin_loader.h.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "amos/eval/mesh_eval.h"
#include "amos/eval/see_through_share.h"
#include "amos/run/dense_observer.h"
#include "amos/run/dense_plugin.h"

namespace amos::run {
namespace {

// A DenseObserver seen through DenseRunMap: every call forwarded.
class DenseObserverRunMap : public DenseRunMap {
 public:
  DenseObserverRunMap(const dense::DenseOptions& options, std::string output_dir,
                      dense::LiveCloudCallback on_live_cloud)
      : observer_(options, std::move(output_dir), std::move(on_live_cloud)) {}

  void onStart(const RunStart& start) override { observer_.onStart(start); }
  void onFrame(const FrameSnapshot& frame) override { observer_.onFrame(frame); }
  void onStreamEnd() override { observer_.onStreamEnd(); }
  void addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) override {
    observer_.addToInfo(trajectory, info);
  }
  void onEnd(const std::vector<io::StampedPose>& trajectory, const report::RunInfo& info) override {
    observer_.onEnd(trajectory, info);
  }
  report::OptionalStage finishMap(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info,
                                  const std::atomic<bool>* stop) override {
    return observer_.finishMap(trajectory, info, stop);
  }

 private:
  DenseObserver observer_;
};

class OpenThreeDPlugin : public DensePlugin {
 public:
  std::vector<std::string> denseOutputNames() const override { return DenseObserver::outputNames(); }
  std::unique_ptr<DenseRunMap> makeDenseRunMap(const dense::DenseOptions& options, std::string output_dir,
                                               dense::LiveCloudCallback on_live_cloud) const override {
    return std::make_unique<DenseObserverRunMap>(options, std::move(output_dir), std::move(on_live_cloud));
  }
  eval::MeshScore evaluateMesh(const eval::MeshEvalRequest& request) const override {
    return eval::evaluateMesh(request);
  }
  nlohmann::json meshScoreJson(const eval::MeshScore& score) const override { return eval::toJson(score); }
  void writePointsPly(const std::string& path, const std::vector<Eigen::Vector3d>& points) const override {
    eval::writePointsPly(path, points);
  }
  eval::SeeThroughScore evaluateSeeThrough(const eval::SeeThroughRequest& request) const override {
    return eval::evaluateSeeThrough(request);
  }
  nlohmann::json seeThroughJson(const eval::SeeThroughScore& score) const override { return eval::toJson(score); }
};

}  // namespace
}  // namespace amos::run

// The one symbol the module exports (the others are hidden: run/CMakeLists.txt).
extern "C" __attribute__((visibility("default"))) const amos::run::DensePlugin* amos_dense_plugin(
    amos::run::DensePluginAbi* built_with) {
  static const amos::run::OpenThreeDPlugin plugin;
  if (built_with != nullptr) *built_with = amos::run::DensePluginAbi{};
  return &plugin;
}
