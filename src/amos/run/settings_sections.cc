#include "amos/run/settings_sections.h"

#include "amos/api/settings_sections.h"

namespace amos::run {

config::SectionRegistry settingsSections() { return api::settingsSections(); }

config::Settings loadSettings(const std::string& path) { return config::loadSettings(path, settingsSections()); }

}  // namespace amos::run
