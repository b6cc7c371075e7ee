#include "amos/run/recording.h"

namespace amos::run {

Recording::Recording(const std::string& dir, double depth_factor) : recorder_(dir, depth_factor) {}

}  // namespace amos::run
