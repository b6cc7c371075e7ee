#pragma once
// Settings -> the SLAM system's options: the mapping from a settings file to system::SlamOptions (camera, virtual
// baseline, ORB, tracking, mapping, loop closing, covisibility) and the place-recognition vocabulary it names.
// Here, not in system/, so that the system knows nothing of settings files (system/ does not depend on config/;
// config/ depends on system/ and place/ for these option types).
#include <memory>
#include <string>

#include "amos/config/settings.h"
#include "amos/place/vocabulary.h"
#include "amos/system/slam_system.h"

namespace amos::config {

// The SLAM options that follow from a settings file (camera, virtual baseline, ORB; defaults elsewhere);
// models_dir is the command line's --models ("" = not given), where the vocabulary is looked for first.
system::SlamOptions slamOptionsFromSettings(const Settings& settings, bool deterministic,
                                            const std::string& models_dir = "");
// The vocabulary Place.vocabulary names: an existing path, else the name looked for in the models folders in the
// order the segmentation models are (--models, Segmentation.modelsDir, $AMOS_MODELS, ./models, ../shared/models),
// so that the folder that holds the networks also gives the vocabulary. Null, with a warning, when it is not found
// or the setting is "" (thumbnails then). A file that is there but cannot be read is an error naming it.
std::shared_ptr<const place::Vocabulary> loadPlaceVocabulary(const Settings& settings,
                                                             const std::string& models_dir = "");

}  // namespace amos::config
