#pragma once
// For tests only: the configs of the checkout and the short real sequence that many end-to-end tests run on, named
// once (AMOS_SOURCE_DIR is the test programs' compile definition of the checkout).
#include <string>

#include "amos/testing/shared_data.h"

namespace amos::testing {

inline const std::string kTum2 = std::string(AMOS_SOURCE_DIR) + "/configs/tum2.yaml";
inline const std::string kTum3 = std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml";
// The first 50 frames of TUM fr2/desk (../shared/data), by name and as a path.
inline const std::string kFr2Data = "tum_fr2_desk_first50";
inline const std::string kFr2 = dataPath(kFr2Data);

}  // namespace amos::testing
