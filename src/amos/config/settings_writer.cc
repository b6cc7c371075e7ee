#include "amos/config/settings_writer.h"

#include <fmt/format.h>

#include <string_view>

#include "amos/io/atomic_file.h"

namespace amos::config {

namespace {

// Whether YAML would read `text` as something other than that plain string.
bool needsQuotes(std::string_view text) {
  if (text.empty() || text == "\"\"") return false;  // value() writes the empty text as ""
  if (text.front() == ' ' || text.back() == ' ') return true;
  if (std::string_view("-?:,[]{}#&*!|>'\"%@`").find(text.front()) != std::string_view::npos) return true;
  return text.find(": ") != std::string_view::npos || text.find(" #") != std::string_view::npos ||
         text.back() == ':' || text.find_first_of("\"\\\t\n") != std::string_view::npos;
}

std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\t': out += "\\t"; break;
      case '\n': out += "\\n"; break;
      default: out += c;
    }
  }
  return out + "\"";
}

std::string valueText(const SettingsKey& key) {
  const std::string value = key.value();
  return key.kind() == SettingsKey::Kind::kText && needsQuotes(value) ? quoted(value) : value;
}

}  // namespace

std::string settingsFileText(const Settings& settings, const std::vector<std::string>& comment_lines) {
  Settings copy = settings;  // settingsKeys binds the keys to a Settings it may write to; this one is only read
  std::string out = "%YAML:1.0\n";
  for (const std::string& line : comment_lines) out += line.empty() ? "#\n" : fmt::format("# {}\n", line);
  for (const KeySection& section : settingsKeys(copy)) {
    out += fmt::format("\n# {}\n", section.title);
    for (const SettingsKey& key : section.keys) out += fmt::format("{}: {}\n", key.name(), valueText(key));
  }
  return out;
}

void writeSettingsFile(const std::string& path, const Settings& settings,
                       const std::vector<std::string>& comment_lines) {
  io::writeFileAtomically(path, settingsFileText(settings, comment_lines));
}

}  // namespace amos::config
