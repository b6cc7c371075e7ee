#include "amos/api/settings_sections.h"

#include "amos/dense/dense_keys.h"

namespace amos::api {

config::SectionRegistry settingsSections() {
  config::SectionRegistry sections;
  sections.add<dense::DenseOptions>("Dense static map (run --dense)", &dense::listDenseKeys<config::KeySection>);
  return sections;
}

}  // namespace amos::api
