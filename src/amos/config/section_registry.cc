#include "amos/config/section_registry.h"

#include <fmt/format.h>

#include "amos/core/error.h"

namespace amos::config {

KeySection AddedSection::keys() {
  KeySection section{title};
  list_keys(options, section);
  return section;
}

void SectionRegistry::requireNew(const char* type_name) const {
  for (const AddedSection& s : sections_) {
    core::require(std::string(s.options.type().name()) != type_name,
                  fmt::format("settings section '{}' is registered twice", s.title));
  }
}

}  // namespace amos::config
