#include "amos/config/section_registry.h"

#include <gtest/gtest.h>

#include "amos/config/settings.h"
#include "amos/config/settings_writer.h"
#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::config {
namespace {

// A section config knows nothing of, as a module above it would add one.
struct LampOptions {
  double brightness = 0.5;
  int bulbs = 2;
  void check() const {
    core::requireOption(brightness > 0 && brightness <= 1, core::option(brightness, "brightness"),
                        "must be in (0, 1]");
    core::requireAtLeast(bulbs, "bulbs", 1);
  }
};

void listLampKeys(LampOptions& o, KeySection& s) {
  s.add("Lamp.brightness", &o.brightness, "share of the full light");
  s.add("Lamp.bulbs", &o.bulbs, "bulbs lit");
}

SectionRegistry lamp() {
  SectionRegistry sections;
  sections.add<LampOptions>("Lamp", &listLampKeys);
  return sections;
}

const char* kCameraSection = "Camera.fx: 500\nCamera.fy: 500\nCamera.cx: 320\nCamera.cy: 240\n";

TEST(SectionRegistry, AnAddedSectionIsReadCheckedByKeyAndWritten) {
  const Settings s = parseSettings(std::string(kCameraSection) + "Lamp.bulbs: 3\n", "lamp.yaml", lamp());
  EXPECT_EQ(s.section<LampOptions>().bulbs, 3);
  EXPECT_DOUBLE_EQ(s.section<LampOptions>().brightness, 0.5);
  EXPECT_NE(settingsFileText(s, {}).find("Lamp.bulbs: 3\n"), std::string::npos);
  EXPECT_NE(keysMarkdown(lamp()).find("| `Lamp.brightness` | `0.5` |"), std::string::npos);
  try {
    parseSettings(std::string(kCameraSection) + "Lamp.brightness: 2\n", "lamp.yaml", lamp());
    ADD_FAILURE() << "accepted a brightness of 2";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("lamp.yaml:5: Lamp.brightness must be in (0, 1]"), std::string::npos)
        << e.what();
  }
}

TEST(SectionRegistry, ACopyOfTheSettingsHoldsItsOwnOptions) {
  Settings a = parseSettings(kCameraSection, "lamp.yaml", lamp());
  Settings b = a;
  b.section<LampOptions>().bulbs = 7;
  EXPECT_EQ(a.section<LampOptions>().bulbs, 2);
  EXPECT_EQ(b.section<LampOptions>().bulbs, 7);
}

TEST(SectionRegistry, WithoutTheRegistryItsKeysAreUnknownAndItsSectionAbsent) {
  const Settings s = parseSettings(std::string(kCameraSection) + "Lamp.bulbs: 3\n", "plain.yaml");
  EXPECT_THROW(s.section<LampOptions>(), core::Error);
}

TEST(SectionRegistry, ASectionAddedTwiceIsRefused) {
  SectionRegistry sections = lamp();
  EXPECT_THROW(sections.add<LampOptions>("Lamp again", &listLampKeys), core::Error);
}

}  // namespace
}  // namespace amos::config
