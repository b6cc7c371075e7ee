#pragma once
// The settings sections the program reads beyond config's own (config/section_registry.h): the dense map's
// Dense.* keys (dense/dense_keys.h). Header-only option structs, so the keys are read and checked whether or not
// the dense module is built.
#include <string>

#include "amos/config/settings.h"

namespace amos::run {

config::SectionRegistry settingsSections();

// config::loadSettings with settingsSections().
config::Settings loadSettings(const std::string& path);

}  // namespace amos::run
