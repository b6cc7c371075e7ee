#pragma once
// The settings sections read beyond config's own (config/section_registry.h): the dense map's Dense.* keys
// (dense/dense_keys.h, header-only, so they are read and checked whether or not the dense module is built). Both
// amos::Slam and `amos-slam run` (run/settings_sections.h) read the settings with these.
#include "amos/config/section_registry.h"

namespace amos::api {

config::SectionRegistry settingsSections();

}  // namespace amos::api
