#pragma once
// amos::Options::overrides: settings keys set over a settings file's values, checked against the key registry
// (config::settingsKeys, with the sections of settings_sections.h) first, so that a misspelt key is an error naming it rather than a value silently unused.
#include <string>
#include <utility>
#include <vector>

namespace amos::api {

using SettingsOverrides = std::vector<std::pair<std::string, std::string>>;

// `yaml` (a settings file's text) with each override's key set to its value: the lines that set the key (or a
// former name of it) removed and "key: value" appended. Throws core::Error naming `option` and the key when the
// registry does not know it, or when a key or value would not be one YAML line.
std::string withOverrides(const std::string& yaml, const SettingsOverrides& overrides, const std::string& option);

}  // namespace amos::api
