#pragma once
// How the check() of an options struct rejects a value: it names the member at fault and the rule that member
// breaks, and carries the member's address. It does not name a settings key: config/ is the one place that knows
// which key sets which member, and reports the error as "file:line: Key rule" by looking the address up. Outside
// config (tests, tools, structs filled in code) the message names the member: "lag (3) must not exceed interval (2)".
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "amos/core/error.h"

namespace amos::core {

// A member of an options struct: where it is and what the code calls it.
struct OptionField {
  const void* address = nullptr;
  const char* name = "";
};

template <typename T>
OptionField option(const T& member, const char* name) {
  return {&member, name};
}

class InvalidOption : public Error {
 public:
  // `rule` completes "<name> <rule>" ("must be >= 1, got 0"); it may name the `related` members by their names.
  InvalidOption(OptionField field, std::string rule, std::vector<OptionField> related = {})
      : Error(std::string(field.name) + " " + rule),
        field_(field),
        rule_(std::move(rule)),
        related_(std::move(related)) {}
  const OptionField& field() const { return field_; }
  const std::string& rule() const { return rule_; }
  const std::vector<OptionField>& related() const { return related_; }

 private:
  OptionField field_;
  std::string rule_;
  std::vector<OptionField> related_;
};

// Throws InvalidOption(field, rule, related) when `condition` is false.
inline void requireOption(bool condition, OptionField field, const std::string& rule,
                          std::vector<OptionField> related = {}) {
  if (!condition) throw InvalidOption(field, rule, std::move(related));
}

// The common rules: "<name> must be >= minimum, got <value>", "<name> must be > 0, got <value>" (finite, too),
// "<name> must be in [low, high], got <value>".
template <typename T>
void requireAtLeast(const T& member, const char* name, const std::common_type_t<T>& minimum) {
  requireOption(member >= minimum, option(member, name), fmt::format("must be >= {}, got {}", minimum, member));
}
template <typename T>
void requireInRange(const T& member, const char* name, const std::common_type_t<T>& low,
                    const std::common_type_t<T>& high) {
  requireOption(member >= low && member <= high, option(member, name),
                fmt::format("must be in [{}, {}], got {}", low, high, member));
}
template <typename T>
void requirePositive(const T& member, const char* name) {
  bool finite = true;
  if constexpr (std::is_floating_point_v<T>) finite = std::isfinite(member);
  requireOption(finite && member > 0, option(member, name), fmt::format("must be > 0, got {}", member));
}

}  // namespace amos::core
