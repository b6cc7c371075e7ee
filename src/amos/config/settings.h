#pragma once
// All settings of a run, parsed once from one YAML file into the typed option structs of each module.
// Keys: ORB-SLAM2's (Camera.*, ThDepth, DepthMapFactor, ORBextractor.*) plus this project's own sections, each
// named once in the key lists of this module (settingsKeys); configs/README.md lists them with default and meaning.
// Sections of modules config does not include (the dense map's Dense.*) are added by a SectionRegistry
// (section_registry.h) given to loadSettings.
#include <any>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "amos/config/key_list.h"
#include "amos/config/section_registry.h"
#include "amos/core/camera.h"
#include "amos/core/error.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/segmentation/segmenter_options.h"
#include "amos/feature/orb_extractor.h"
#include "amos/io/dataset.h"
#include "amos/loop/loop_closer.h"
#include "amos/map/map.h"
#include "amos/mapping/local_mapper.h"
#include "amos/tracking/tracker.h"

namespace amos::config {

enum class GroundTruthFormat { kTum, kBonn };

struct Settings {
  std::string source_file;  // where these settings came from (empty for defaults)

  core::CameraIntrinsics camera;  // Camera.fx fy cx cy k1 k2 p1 p2 k3 width height
  double fps = 30.0;              // Camera.fps
  bool rgb_order = true;          // Camera.RGB: 1 = images are RGB (TUM PNGs are decoded to BGR by OpenCV either way)
  double bf = 40.0;               // Camera.bf: baseline x fx of the virtual stereo pair (ORB-SLAM2 RGB-D convention)
  double th_depth = 40.0;         // ThDepth: close/far threshold in baselines (close if z < ThDepth * bf / fx)
  double depth_factor = 5000.0;   // DepthMapFactor: raw depth value / factor = metres

  feature::OrbOptions orb;        // ORBextractor.*

  GroundTruthFormat groundtruth_format = GroundTruthFormat::kTum;  // Dataset.groundtruth: tum | bonn

  // Tracking.*, Matching.*, Relocalization.* (Tracking.maxFrames defaults to Camera.fps, as in ORB-SLAM2).
  tracking::TrackerOptions tracking;
  mapping::LocalMappingOptions mapping;    // Mapping.*, LocalBA.*
  map::CovisibilityOptions covisibility;   // Mapping.covisibilityMinWeight
  loop::LoopClosingOptions loop;           // Loop.*
  // Place.vocabulary: the bag-of-words vocabulary file of place recognition (relocalisation, loop detection);
  // a name that is not an existing path is looked for in $AMOS_MODELS, ./models and ../shared/models. "" = rank
  // keyframes by thumbnails instead.
  std::string place_vocabulary = "orb_vocabulary.voc";

  dynamic::DynamicOptions dynamic;         // Dynamic.* (the paper's two-stage front end)
  segmentation::SegmenterOptions segmentation;  // Segmentation.* (prior dynamic objects)
  // The sections of the SectionRegistry the settings were read with, each with its options.
  std::vector<AddedSection> added;

  // The options of an added section; throws core::Error when these settings were read without it.
  template <typename Options>
  const Options& section() const;
  template <typename Options>
  Options& section();

  // Reader options that follow from these settings (image size, depth factor).
  io::ReaderOptions readerOptions() const;
  // Close/far depth threshold in metres.
  double closeDepthThreshold() const { return th_depth * bf / camera.fx; }
  // Throws core::Error naming the key at fault.
  void check() const;

 private:
  // The ORB pyramid's top level against the image.
  void checkPyramid() const;
};

// Default settings with the sections of `added` at their defaults.
Settings defaultSettings(const SectionRegistry& added = {});

// Every settings key, section by section (the added ones last), bound to the members of `s`; the defaults they
// document are the values of `s` when called.
std::vector<KeySection> settingsKeys(Settings& s);
// The key tables of configs/README.md (key, default, meaning), made from settingsKeys of default Settings with the
// sections of `added`.
std::string keysMarkdown(const SectionRegistry& added = {});
// `readme` (configs/README.md) with the key tables between its marker lines made anew; throws core::Error when the
// markers are missing.
std::string withKeyTables(const std::string& readme, const SectionRegistry& added = {});

// Parses `path`: every key of settingsKeys (with the sections of `added`) that the file sets is read, a deprecated
// name with a warning. Unknown keys are warned about (with their line); a key set twice, a wrong type or an invalid
// value throws core::Error naming file, line and key.
Settings loadSettings(const std::string& path, const SectionRegistry& added = {});
// Same, from text (tests).
Settings parseSettings(const std::string& yaml_text, const std::string& virtual_path,
                       const SectionRegistry& added = {});

template <typename Options>
const Options& Settings::section() const {
  for (const AddedSection& s : added) {
    if (const Options* options = std::any_cast<Options>(&s.options)) return *options;
  }
  throw core::Error(fmt::format("the settings were read without the section of {} (SectionRegistry)",
                                typeid(Options).name()));
}

template <typename Options>
Options& Settings::section() {
  return const_cast<Options&>(static_cast<const Settings&>(*this).section<Options>());
}

}  // namespace amos::config
