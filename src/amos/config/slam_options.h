#pragma once
// Settings -> the SLAM system's options: the mapping from a settings file to system::SlamOptions (camera, virtual
// baseline, ORB, tracking, mapping, loop closing, covisibility) and the place-recognition vocabulary it names.
// Here, not in system/, so that the system knows nothing of settings files (system/ does not depend on config/;
// config/ depends on system/ and place/ for these option types).
#include <memory>

#include "amos/config/settings.h"
#include "amos/place/vocabulary.h"
#include "amos/system/slam_system.h"

namespace amos::config {

// The SLAM options that follow from a settings file (camera, virtual baseline, ORB; defaults elsewhere).
system::SlamOptions slamOptionsFromSettings(const Settings& settings, bool deterministic);
// The vocabulary Place.vocabulary names (an existing path, else looked for in $AMOS_MODELS, ./models,
// ../shared/models), or null, with a warning, when it is not found or the setting is "" (thumbnails then). A
// file that is there but cannot be read is an error naming it.
std::shared_ptr<const place::Vocabulary> loadPlaceVocabulary(const Settings& settings);

}  // namespace amos::config
