#pragma once
// The keys of one section of the settings file, each named once, beside the member of an option struct it sets and
// a one-line description; its default is that member's value when the list is made (as COLMAP's option manager
// does: AddDefaultOption("Mapper.init_min_num_inliers", &options->init_min_num_inliers)). From these lists the
// settings are read, the option structs' check() errors are reported by key, file and line, and the key tables of
// configs/README.md are written (settings.h). The lists themselves are in *_section.cc.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "amos/config/yaml_reader.h"

namespace amos::config {

class SettingsKey {
 public:
  enum class Kind { kNumber, kWholeNumber, kFlag, kText, kList, kChoice };

  // T: double, float, int, unsigned, bool, std::string or std::vector<std::string> (what YamlReader reads).
  template <typename T>
  SettingsKey(std::string name, T* member, std::string description);
  // An enumeration, written as one of the names of `choices`.
  template <typename E>
  SettingsKey(std::string name, E* member, std::vector<std::pair<std::string, E>> choices, std::string description);

  // An older name of the key: still read, with a warning that gives the new name.
  SettingsKey& formerly(std::string old_name);
  // The file must set the key.
  SettingsKey& required();
  // The default as documented, when it is not the member's value when the list is made (it follows another key).
  SettingsKey& defaultIs(std::string text);
  // The key switches on an experiment (e.g. an evidence source added after the paper): off by default, on in at
  // least one shipped config (a test checks that), marked as such in the key tables. An experiment that no shipped
  // config turns on is deleted, with a record in docs/experiments/.
  SettingsKey& experimental();
  // The bounds the key's meaning gives its value (numeric keys): [low, high], with the reason, checked as the key is
  // read ("file:line: K must be in [low, high] (reason), got v"). `high` may follow keys read before (the
  // image size): then it is a function, called at reading.
  SettingsKey& within(double low, double high, std::string reason);
  SettingsKey& within(double low, std::function<double()> high, std::string reason);

  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  const std::string& defaultValue() const { return default_; }
  const std::vector<std::string>& formerNames() const { return former_; }
  bool isRequired() const { return required_; }
  bool isExperimental() const { return experimental_; }
  Kind kind() const { return kind_; }
  const std::vector<std::string>& choices() const { return choices_; }
  const void* member() const { return member_; }
  bool isBounded() const { return static_cast<bool>(high_); }
  // The bounds (when isBounded()), the upper one as it stands now.
  double lowBound() const { return low_; }
  double highBound() const { return high_(); }
  // The member's value, written as a settings file writes it (flags 1 / 0, lists [a, b], empty text "").
  std::string value() const { return value_(); }

  // The name under which `in` sets the key, its own or a former one; "" when it does not. Both set is an error
  // naming both lines.
  std::string nameIn(const YamlReader& in) const;
  // Sets the member from `in` when `in` sets the key (a former name with a warning). A value of the wrong type
  // throws core::Error naming file, line and key; a required key that is missing throws naming file and key.
  void read(YamlReader& in) const;

 private:
  using Reader = std::function<void(YamlReader&, const std::string& name)>;
  SettingsKey(std::string name, const void* member, Kind kind, std::string description, Reader read,
              std::function<std::string()> value, std::function<double()> number = {});
  void checkBounds(const YamlReader& in, const std::string& found) const;

  std::string name_, description_, default_;
  std::vector<std::string> former_, choices_;
  bool required_ = false;
  bool experimental_ = false;
  Kind kind_;
  const void* member_;
  Reader read_;
  std::function<std::string()> value_;
  std::function<double()> number_;  // the member as a number (numeric keys)
  double low_ = 0;
  std::function<double()> high_;
  std::string bound_reason_;
};

// One section of the settings file: a table of configs/README.md.
struct KeySection {
  explicit KeySection(std::string section_title) : title(std::move(section_title)) {}

  std::string title;
  std::vector<SettingsKey> keys;
  // Run before the section's keys are read: defaults that follow keys read before (Tracking.maxFrames follows
  // Camera.fps).
  std::function<void()> prepare;

  template <typename... Args>
  SettingsKey& add(Args&&... args) {
    return keys.emplace_back(std::forward<Args>(args)...);
  }
  template <typename E>
  SettingsKey& add(std::string name, E* member, std::vector<std::pair<std::string, E>> choices,
                   std::string description) {
    return keys.emplace_back(std::move(name), member, std::move(choices), std::move(description));
  }
};

// The key of `member` in `sections`, or nullptr when no key sets it.
const SettingsKey* keyOf(const std::vector<KeySection>& sections, const void* member);
// One markdown table (key, default, meaning) per section, each under a "### title" heading; an experimental key's
// meaning starts with "*experimental:*".
std::string keyTablesMarkdown(const std::vector<KeySection>& sections);

// Throws core::Error "file:line: key 'K' must be one of a, b, got 'text'".
[[noreturn]] void throwNotAChoice(const YamlReader& in, const std::string& key, const std::vector<std::string>& choices,
                                  const std::string& text);

template <typename E>
SettingsKey::SettingsKey(std::string name, E* member, std::vector<std::pair<std::string, E>> choices,
                         std::string description)
    : SettingsKey(
          std::move(name), member, Kind::kChoice, std::move(description),
          [member, choices](YamlReader& in, const std::string& key) {
            std::string text;
            in.read(key, text);
            for (const auto& [spelling, value] : choices) {
              if (spelling == text) {
                *member = value;
                return;
              }
            }
            std::vector<std::string> names;
            for (const auto& choice : choices) names.push_back(choice.first);
            throwNotAChoice(in, key, names, text);
          },
          [member, choices] {
            for (const auto& [spelling, value] : choices) {
              if (value == *member) return spelling;
            }
            return std::string("?");
          }) {
  for (const auto& choice : choices) choices_.push_back(choice.first);
}

}  // namespace amos::config
