#pragma once
// The settings a run used, written as a settings file (`settings_used.yaml` beside a run's stats.json; after
// COLMAP's project.ini): every key of settingsKeys at its value, section by section, so that the file read back by
// loadSettings gives the same value for every key, and `amos-slam run --config <that file>` with the same other
// flags runs with the same settings.
#include <string>
#include <vector>

#include "amos/config/settings.h"

namespace amos::config {

// The settings file's text: `%YAML:1.0` (as the shipped configs, which OpenCV's reader needs), then
// `comment_lines` as comments (each prefixed "# "), then one "# title" line per section and one `Key: value` line
// per key. Text values that YAML would read otherwise (a ':' or '#', quotes, leading or trailing blanks, ...) are
// double-quoted.
std::string settingsFileText(const Settings& settings, const std::vector<std::string>& comment_lines);

// Writes settingsFileText to `path` atomically (io/atomic_file.h); throws core::Error naming the file.
void writeSettingsFile(const std::string& path, const Settings& settings,
                       const std::vector<std::string>& comment_lines);

}  // namespace amos::config
