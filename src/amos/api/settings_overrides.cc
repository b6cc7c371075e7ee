#include "amos/api/settings_overrides.h"

#include <fmt/format.h>

#include <sstream>

#include "amos/api/settings_sections.h"
#include "amos/config/settings.h"
#include "amos/core/error.h"

namespace amos::api {

namespace {

// The key's own name and its former ones, or nothing when the registry does not know it.
std::vector<std::string> namesOf(const std::string& key) {
  config::Settings defaults = config::defaultSettings(settingsSections());  // the Dense.* keys too
  for (const config::KeySection& section : config::settingsKeys(defaults)) {
    for (const config::SettingsKey& k : section.keys) {
      std::vector<std::string> names{k.name()};
      names.insert(names.end(), k.formerNames().begin(), k.formerNames().end());
      for (const std::string& name : names)
        if (name == key) return names;
    }
  }
  return {};
}

// Whether `line` sets one of `names` ("Name: value", leading blanks allowed).
bool setsOneOf(const std::string& line, const std::vector<std::string>& names) {
  const std::size_t start = line.find_first_not_of(" \t");
  if (start == std::string::npos) return false;
  for (const std::string& name : names) {
    if (line.compare(start, name.size(), name) != 0) continue;
    const std::size_t after = line.find_first_not_of(" \t", start + name.size());
    if (after != std::string::npos && line[after] == ':') return true;
  }
  return false;
}

}  // namespace

std::string withOverrides(const std::string& yaml, const SettingsOverrides& overrides, const std::string& option) {
  std::string text = yaml;
  for (const auto& [key, value] : overrides) {
    const std::vector<std::string> names = namesOf(key);
    core::require(!names.empty(), fmt::format("{}: unknown settings key '{}' (configs/README.md lists the keys)",
                                              option, key));
    core::require(value.find('\n') == std::string::npos && !value.empty(),
                  fmt::format("{}: the value of '{}' must be one non-empty line, got '{}'", option, key, value));
    std::istringstream in(text);
    std::string kept;
    for (std::string line; std::getline(in, line);)
      if (!setsOneOf(line, names)) kept += line + "\n";
    text = kept + fmt::format("{}: {}\n", key, value);
  }
  return text;
}

}  // namespace amos::api
