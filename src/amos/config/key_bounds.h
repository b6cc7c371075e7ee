#pragma once
// The bounds each key's meaning gives its value, in one table (key_bounds.cc) applied to the key lists: counts that
// size allocations or loops, shares in [0, 1], distances in pixels against the image, times and thresholds >= 0.
// A key read from a file is checked against them at once (SettingsKey::within), naming file, line, key, value,
// bound and reason. Keys of sections added through the SectionRegistry bound themselves in their own check().
#include <vector>

#include "amos/config/key_list.h"
#include "amos/core/camera.h"

namespace amos::config {

// Gives every key of `sections` that the table names its bounds; those relative to the image follow `camera`
// (read before the other sections), which must outlive the sections.
void applyKeyBounds(std::vector<KeySection>& sections, const core::CameraIntrinsics& camera);

}  // namespace amos::config
