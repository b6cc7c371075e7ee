#pragma once
// For the config tests: the sections the library and the program add (api/settings_sections.cc, which config cannot
// include), the camera keys a settings file must have, and a settings text made from key -> value pairs.
#include <map>
#include <string>

#include "amos/config/section_registry.h"
#include "amos/dense/dense_keys.h"

namespace amos::config::test_settings {

inline SectionRegistry addedSections() {
  SectionRegistry sections;
  sections.add<dense::DenseOptions>("Dense static map (run --dense)", &dense::listDenseKeys<KeySection>);
  return sections;
}

inline const std::map<std::string, std::string> kRequired = {
    {"Camera.fx", "500"}, {"Camera.fy", "500"}, {"Camera.cx", "320"}, {"Camera.cy", "240"}};

inline std::string yamlOf(const std::map<std::string, std::string>& keys) {
  std::string text;
  for (const auto& [key, value] : keys) text += key + ": " + value + "\n";
  return text;
}

}  // namespace amos::config::test_settings
