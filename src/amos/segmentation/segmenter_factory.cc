#include "amos/segmentation/segmenter_factory.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "amos/core/error.h"
#ifdef AMOS_WITH_DNN
#include "amos/segmentation/segmenter_dnn.h"
#endif

namespace amos::segmentation {

void SegmenterFactory::add(const std::string& name, SegmenterBackend backend) {
  core::require(!name.empty(), "segmenter backend without a name");
  core::require(!has(name), fmt::format("segmenter backend '{}' registered twice", name));
  core::require(backend.model_files && backend.create, fmt::format("segmenter backend '{}' is incomplete", name));
  backends_.emplace(name, std::move(backend));
}

std::vector<std::string> SegmenterFactory::names() const {
  std::vector<std::string> out;
  for (const auto& entry : backends_) out.push_back(entry.first);
  return out;
}

const SegmenterBackend& SegmenterFactory::backend(const std::string& name, const SourceNames& source_names) const {
  const auto it = backends_.find(name);
  if (it != backends_.end()) return it->second;
  if (backends_.empty())
    throw core::Error(fmt::format(
        "Segmentation.backend '{}': this build has no segmentation backend (built with AMOS_WITH_DNN=OFF); rebuild "
        "with -DAMOS_WITH_DNN=ON or run with {}",
        name, source_names.modes_without_models));
  throw core::Error(fmt::format("Segmentation.backend '{}' is unknown; available: {}", name, fmt::join(names(), ", ")));
}

std::unique_ptr<Segmenter> SegmenterFactory::create(const SegmenterOptions& options) const {
  options.check();
  core::require(!options.models_dir.empty(), "Segmentation.modelsDir must be resolved before creating a segmenter");
  return backend(options.backend).create(options);
}

SegmenterFactory builtinSegmenterFactory() {
  SegmenterFactory factory;
#ifdef AMOS_WITH_DNN
  addDnnSegmenterBackends(factory);
#endif
  return factory;
}

std::unique_ptr<Segmenter> createSegmenter(SegmenterOptions options, const ModelSources& sources,
                                           const SegmenterFactory& factory) {
  options.check();
  const SegmenterBackend& backend = factory.backend(options.backend, sources.names);
  ModelSources resolved_sources = sources;
  if (resolved_sources.settings_dir.empty()) resolved_sources.settings_dir = options.models_dir;
  const ModelLocation location = locateModelDir(resolved_sources, backend.model_files(options));
  spdlog::info("segmentation: backend {} with models from {} ({})", options.backend, location.dir, location.source);
  options.models_dir = location.dir;
  return factory.create(options);
}

}  // namespace amos::segmentation
