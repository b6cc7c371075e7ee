#include "amos/config/key_list.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <type_traits>

#include "amos/core/error.h"

namespace amos::config {

namespace {

SettingsKey::Kind kindOf(const double*) { return SettingsKey::Kind::kNumber; }
SettingsKey::Kind kindOf(const float*) { return SettingsKey::Kind::kNumber; }
SettingsKey::Kind kindOf(const int*) { return SettingsKey::Kind::kWholeNumber; }
SettingsKey::Kind kindOf(const unsigned*) { return SettingsKey::Kind::kWholeNumber; }
SettingsKey::Kind kindOf(const bool*) { return SettingsKey::Kind::kFlag; }
SettingsKey::Kind kindOf(const std::string*) { return SettingsKey::Kind::kText; }
SettingsKey::Kind kindOf(const std::vector<std::string>*) { return SettingsKey::Kind::kList; }

// A value as a settings file writes it.
template <typename T>
std::string textOf(const T& number) {
  return fmt::format("{}", number);
}
std::string textOf(bool flag) { return flag ? "1" : "0"; }
std::string textOf(const std::string& text) { return text.empty() ? "\"\"" : text; }
std::string textOf(const std::vector<std::string>& list) { return fmt::format("[{}]", fmt::join(list, ", ")); }

std::string escapeCell(std::string text) {
  for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) text.insert(at, "\\");
  return text;
}

// The member as a number, for the bounds of numeric keys.
template <typename T>
std::function<double()> numberOf(const T* member) {
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    return [member] { return static_cast<double>(*member); };
  } else {
    return {};
  }
}

}  // namespace

SettingsKey::SettingsKey(std::string name, const void* member, Kind kind, std::string description, Reader read,
                         std::function<std::string()> value, std::function<double()> number)
    : name_(std::move(name)),
      description_(std::move(description)),
      kind_(kind),
      member_(member),
      read_(std::move(read)),
      value_(std::move(value)),
      number_(std::move(number)) {
  default_ = value_();
}

template <typename T>
SettingsKey::SettingsKey(std::string name, T* member, std::string description)
    : SettingsKey(
          std::move(name), member, kindOf(member), std::move(description),
          [member](YamlReader& in, const std::string& key) { in.read(key, *member); },
          [member] { return textOf(*member); }, numberOf(member)) {}

template SettingsKey::SettingsKey(std::string, double*, std::string);
template SettingsKey::SettingsKey(std::string, float*, std::string);
template SettingsKey::SettingsKey(std::string, int*, std::string);
template SettingsKey::SettingsKey(std::string, unsigned*, std::string);
template SettingsKey::SettingsKey(std::string, bool*, std::string);
template SettingsKey::SettingsKey(std::string, std::string*, std::string);
template SettingsKey::SettingsKey(std::string, std::vector<std::string>*, std::string);

SettingsKey& SettingsKey::formerly(std::string old_name) {
  former_.push_back(std::move(old_name));
  return *this;
}

SettingsKey& SettingsKey::required() {
  required_ = true;
  return *this;
}

SettingsKey& SettingsKey::defaultIs(std::string text) {
  default_ = std::move(text);
  return *this;
}

SettingsKey& SettingsKey::experimental() {
  experimental_ = true;
  return *this;
}

SettingsKey& SettingsKey::within(double low, double high, std::string reason) {
  return within(low, [high] { return high; }, std::move(reason));
}

SettingsKey& SettingsKey::within(double low, std::function<double()> high, std::string reason) {
  core::require(static_cast<bool>(number_), fmt::format("key '{}' is not a number and cannot have bounds", name_));
  low_ = low;
  high_ = std::move(high);
  bound_reason_ = std::move(reason);
  return *this;
}

void SettingsKey::checkBounds(const YamlReader& in, const std::string& found) const {
  if (!isBounded()) return;
  const double value = number_(), high = high_();
  if (value >= low_ && value <= high) return;
  throw core::Error(fmt::format("{}: {} must be in [{}, {}] ({}), got {}", in.where(found), found, low_, high,
                                bound_reason_, value_()));
}

std::string SettingsKey::nameIn(const YamlReader& in) const {
  std::string found = in.has(name_) ? name_ : std::string();
  for (const auto& old : former_) {
    if (!in.has(old)) continue;
    if (!found.empty()) {
      throw core::Error(fmt::format("{}: key '{}' is the old name of '{}', which is set too ({}); keep one of the two",
                                    in.where(old), old, name_, in.where(found)));
    }
    found = old;
  }
  return found;
}

void SettingsKey::read(YamlReader& in) const {
  const std::string found = nameIn(in);
  if (found.empty()) {
    core::require(!required_, fmt::format("{}: required key '{}' is missing", in.path(), name_));
    return;
  }
  if (found != name_) {
    spdlog::warn("{}: key '{}' is deprecated: it is now called '{}' (the old name still works)", in.where(found), found,
                 name_);
  }
  read_(in, found);
  checkBounds(in, found);
}

void throwNotAChoice(const YamlReader& in, const std::string& key, const std::vector<std::string>& choices,
                     const std::string& text) {
  throw core::Error(
      fmt::format("{}: key '{}' must be one of {}, got '{}'", in.where(key), key, fmt::join(choices, ", "), text));
}

const SettingsKey* keyOf(const std::vector<KeySection>& sections, const void* member) {
  for (const auto& section : sections) {
    for (const auto& key : section.keys) {
      if (key.member() == member) return &key;
    }
  }
  return nullptr;
}

std::string keyTablesMarkdown(const std::vector<KeySection>& sections) {
  std::string out;
  for (const auto& section : sections) {
    out += fmt::format("### {}\n\n| key | default | meaning |\n|---|---|---|\n", section.title);
    for (const auto& key : section.keys) {
      std::string meaning = key.isExperimental() ? "*experimental:* " + key.description() : key.description();
      if (key.kind() == SettingsKey::Kind::kChoice) {
        meaning += fmt::format(" (`{}`)", fmt::join(key.choices(), "`, `"));
      }
      for (const auto& old : key.formerNames()) meaning += fmt::format("; formerly `{}`", old);
      const std::string default_cell = key.isRequired() ? "required" : fmt::format("`{}`", key.defaultValue());
      out += fmt::format("| `{}` | {} | {} |\n", key.name(), escapeCell(default_cell), escapeCell(meaning));
    }
    out += "\n";
  }
  return out;
}

}  // namespace amos::config
