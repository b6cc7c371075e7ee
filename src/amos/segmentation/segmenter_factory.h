#pragma once
// Segmenter backends by name (Segmentation.backend), so another ONNX instance segmenter (a YOLACT or YOLO-seg
// export, say) can be added next to the built-in one without touching the SLAM code: register it in a factory
// and pass that factory where the segmenter is created.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "amos/segmentation/model_locator.h"
#include "amos/segmentation/segmenter.h"
#include "amos/segmentation/segmenter_options.h"

namespace amos::segmentation {

struct SegmenterBackend {
  std::string description;
  // Files the backend needs in the model folder for these options (used to find that folder).
  std::function<std::vector<std::string>(const SegmenterOptions&)> model_files;
  // Builds the backend; options.models_dir is resolved. Must load and check every model here, so a missing or
  // corrupt model is an error at start-up, not at the first frame.
  std::function<std::unique_ptr<Segmenter>(const SegmenterOptions&)> create;
};

class SegmenterFactory {
 public:
  // Throws core::Error when the name is taken or the backend is incomplete.
  void add(const std::string& name, SegmenterBackend backend);
  bool has(const std::string& name) const { return backends_.count(name) > 0; }
  std::vector<std::string> names() const;
  // Throws core::Error naming Segmentation.backend and the available backends (or, when there are none, how to run
  // without segmentation, in source_names' words).
  const SegmenterBackend& backend(const std::string& name, const SourceNames& source_names = {}) const;

  // options.check(), then the backend's create(). options.models_dir must already be set.
  std::unique_ptr<Segmenter> create(const SegmenterOptions& options) const;

 private:
  std::map<std::string, SegmenterBackend> backends_;
};

// The backends compiled into this build: "nanodet_selfie" when built with AMOS_WITH_DNN, none otherwise.
SegmenterFactory builtinSegmenterFactory();

// Resolves the model folder (options.models_dir if set counts as the settings-file source, see model_locator.h)
// and creates the backend. Throws core::Error with what to do when models are missing or unreadable.
std::unique_ptr<Segmenter> createSegmenter(SegmenterOptions options, const ModelSources& sources,
                                           const SegmenterFactory& factory);

}  // namespace amos::segmentation
