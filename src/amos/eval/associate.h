#pragma once
// Timestamp association of trajectories exactly as the TUM RGB-D benchmark's associate.py (used by
// evaluate_ate.py); the rule itself is io::associateStamps (io/associate.h), shared with the dataset reader.
// Also the trajectory normalisation the scripts get from reading into a Python dict.
#include <cstddef>
#include <utility>
#include <vector>

#include "amos/io/trajectory.h"

namespace amos::eval {

struct AssociationOptions {
  double max_difference_s = 0.02;  // eval.max_time_difference: association radius in seconds
  double offset_s = 0.0;           // eval.time_offset: added to the second list's stamps
};

// Index pairs (i into first, j into second), see io::associateStamps.
std::vector<std::pair<std::size_t, std::size_t>> associate(const std::vector<double>& first,
                                                           const std::vector<double>& second,
                                                           const AssociationOptions& options = {});

// Poses sorted by timestamp with one pose per timestamp; of duplicates the LAST in file order is kept, which is
// what the benchmark scripts get from building a dict (the official fr2/desk ground truth has a duplicate stamp).
std::vector<io::StampedPose> sortedUniqueByTimestamp(const std::vector<io::StampedPose>& poses);

std::vector<double> timestampsOf(const std::vector<io::StampedPose>& poses);

}  // namespace amos::eval
