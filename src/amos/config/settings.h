#pragma once
// All settings of a run, parsed once from one YAML file into the typed option structs of each module.
// Keys: ORB-SLAM2's (Camera.*, ThDepth, DepthMapFactor, ORBextractor.*) plus this project's own sections, each
// named once in the key lists of this module (settingsKeys); configs/README.md lists them with default and meaning.
#include <string>
#include <vector>

#include "amos/config/key_list.h"
#include "amos/core/camera.h"
#include "amos/dense/dense_options.h"
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
  dense::DenseOptions dense;               // Dense.* (the dense static map of run --dense)

  // Reader options that follow from these settings (image size, depth factor).
  io::ReaderOptions readerOptions() const;
  // Close/far depth threshold in metres.
  double closeDepthThreshold() const { return th_depth * bf / camera.fx; }
  // Throws core::Error naming the key at fault.
  void check() const;
};

// Every settings key, section by section, bound to the members of `s`; the defaults they document are the values
// of `s` when called.
std::vector<KeySection> settingsKeys(Settings& s);
// The key tables of configs/README.md (key, default, meaning), made from settingsKeys of default Settings.
std::string keysMarkdown();
// `readme` (configs/README.md) with the key tables between its marker lines made anew; throws core::Error when the
// markers are missing.
std::string withKeyTables(const std::string& readme);

// Parses `path`: every key of settingsKeys that the file sets is read, a deprecated name with a warning. Unknown keys
// are warned about (with their line); a key set twice, a wrong type or an invalid value throws core::Error naming
// file, line and key.
Settings loadSettings(const std::string& path);
// Same, from text (tests).
Settings parseSettings(const std::string& yaml_text, const std::string& virtual_path);

}  // namespace amos::config
