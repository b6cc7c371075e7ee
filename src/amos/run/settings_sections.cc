#include "amos/run/settings_sections.h"

#include "amos/dense/dense_keys.h"

namespace amos::run {

config::SectionRegistry settingsSections() {
  config::SectionRegistry sections;
  sections.add<dense::DenseOptions>("Dense static map (run --dense)", &dense::listDenseKeys<config::KeySection>);
  return sections;
}

config::Settings loadSettings(const std::string& path) { return config::loadSettings(path, settingsSections()); }

}  // namespace amos::run
