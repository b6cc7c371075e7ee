// Every numeric key has the bounds its meaning gives it, checked when a settings file is read (config --check and
// the start of a run): a value outside them is an error naming the file, line, key, value and bound.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "amos/config/settings.h"
#include "amos/config/test_settings.h"
#include "amos/core/error.h"

namespace amos::config {
namespace {

using namespace test_settings;

// The error parsing the required keys with `key` set to `value`, or nothing when the file is accepted.
std::optional<std::string> errorWith(const std::string& key, const std::string& value) {
  std::map<std::string, std::string> file = kRequired;
  file[key] = value;
  try {
    parseSettings(yamlOf(file), "t.yaml", addedSections());
  } catch (const core::Error& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

struct NumericKey {
  std::string name;
  bool whole;
  bool bounded;
  double low, high;
};

// Every number key of the registry, with its declared bounds (at the default image, 640 x 480).
std::vector<NumericKey> numericKeys() {
  Settings s = defaultSettings(addedSections());
  std::vector<NumericKey> out;
  for (const auto& section : settingsKeys(s)) {
    for (const auto& key : section.keys) {
      const bool whole = key.kind() == SettingsKey::Kind::kWholeNumber;
      if (!whole && key.kind() != SettingsKey::Kind::kNumber) continue;
      out.push_back({key.name(), whole, key.isBounded(), key.isBounded() ? key.lowBound() : 0,
                     key.isBounded() ? key.highBound() : 0});
    }
  }
  return out;
}

// A key added without bounds fails here: it must declare bounds (key_bounds.cc), or (a section added through the
// registry) its check() must refuse both a huge and a hugely negative value by name.
TEST(KeyBounds, EveryNumericKeyOfTheRegistryIsBounded) {
  const std::vector<NumericKey> keys = numericKeys();
  ASSERT_GT(keys.size(), 150u);
  for (const NumericKey& key : keys) {
    if (key.bounded) continue;
    EXPECT_EQ(key.name.rfind("Dense.", 0), 0u) << key.name << " has no bounds in key_bounds.cc";
    for (const std::string& value : key.whole ? std::vector<std::string>{"2147483647", "-2147483647"}
                                              : std::vector<std::string>{"1e12", "-1e12"}) {
      const std::optional<std::string> error = errorWith(key.name, value);
      if (!error) {
        ADD_FAILURE() << key.name << ": " << value << " is accepted";
        continue;
      }
      EXPECT_NE(error->find(key.name), std::string::npos) << key.name << " = " << value << ": " << *error;
      EXPECT_NE(error->find("t.yaml:"), std::string::npos) << *error;
    }
  }
}

// The value `step` beyond `bound` (step < 0: below it), as a settings file writes it.
std::string beside(const NumericKey& key, double bound, double step) {
  if (key.whole) return fmt::format("{}", static_cast<long long>(bound) + (step > 0 ? 1 : -1));
  const double delta = std::max(std::abs(bound) * 1e-4, 1e-4);
  return fmt::format("{}", bound + (step > 0 ? delta : -delta));
}

std::string boundText(const NumericKey& key) { return fmt::format("must be in [{}, {}]", key.low, key.high); }

// Table-driven from the declared bounds: just outside each bound the file is refused, naming file, line, key and
// the bound; just inside (at the bound) the bound does not refuse it (another key's rule may).
TEST(KeyBounds, JustOutsideABoundIsRefusedByNameAndJustInsideIsNot) {
  int checked = 0;
  for (const NumericKey& key : numericKeys()) {
    if (!key.bounded) continue;
    for (const auto& [bound, step] : {std::pair{key.low, -1.0}, std::pair{key.high, 1.0}}) {
      const std::string outside = beside(key, bound, step);
      const std::optional<std::string> refused = errorWith(key.name, outside);
      if (!refused) {
        ADD_FAILURE() << key.name << ": " << outside << " is accepted";
        continue;
      }
      EXPECT_NE(refused->find("t.yaml:"), std::string::npos) << *refused;
      EXPECT_NE(refused->find(key.name), std::string::npos) << *refused;
      const bool beyond_the_type = refused->find("must be a whole number") != std::string::npos;
      EXPECT_TRUE(beyond_the_type || refused->find(boundText(key)) != std::string::npos) << *refused;
      const std::string inside =
          key.whole ? fmt::format("{}", static_cast<long long>(bound)) : fmt::format("{}", bound);
      const std::optional<std::string> accepted = errorWith(key.name, inside);
      EXPECT_TRUE(!accepted || accepted->find(boundText(key)) == std::string::npos) << *accepted;
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

TEST(KeyBounds, AnErrorGivesTheValueTheBoundAndItsReason) {
  const std::optional<std::string> error = errorWith("ORBextractor.iniThFAST", "300");
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("t.yaml:"), std::string::npos) << *error;
  EXPECT_NE(error->find("ORBextractor.iniThFAST must be in [1, 255] (a FAST threshold is a difference of 8-bit "
                        "grey levels), got 300"),
            std::string::npos)
      << *error;
}

TEST(KeyBounds, PixelBoundsFollowTheImage) {
  EXPECT_FALSE(errorWith("Dynamic.Boundary.borderMargin", "200"));
  const std::optional<std::string> error = errorWith("Dynamic.Boundary.borderMargin", "241");
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("must be in [0, 240]"), std::string::npos) << *error;
}

TEST(KeyBounds, TheOrbPyramidTopLevelMustHoldCorners) {
  const std::optional<std::string> error = errorWith("ORBextractor.nLevels", "20");
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("ORBextractor.nLevels leaves the top pyramid level"), std::string::npos) << *error;
  EXPECT_FALSE(errorWith("ORBextractor.nLevels", "12"));
}

}  // namespace
}  // namespace amos::config
