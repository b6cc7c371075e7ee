#pragma once
// Stamped camera trajectories in the TUM RGB-D text format: one pose per line,
//   timestamp tx ty tz qx qy qz qw
// where (t, q) is the camera pose in the world, T_wc (see core/pose.h), timestamps in seconds.
#include <string>
#include <vector>

#include "amos/core/pose.h"

namespace amos::io {

struct StampedPose {
  double timestamp = 0;                   // seconds
  core::SE3 T_wc = core::SE3::Identity(); // camera-to-world
};

// Reads a TUM trajectory file, accepting what the TUM benchmark scripts accept: lines starting with '#' (after
// leading blanks) and blank lines are skipped, ',' and tab count as separators, quaternions need not be unit
// length (they are normalised). Like the benchmark's evaluate_rpe.py, a line with an all-zero quaternion or a
// NaN/inf value is skipped with a warning. Poses are returned in file order (duplicates and unsorted stamps
// are kept; the evaluator sorts them).
// Throws core::Error for a missing/unreadable file, and for a malformed line (not exactly 8 numbers), naming
// the file and the 1-based line number.
std::vector<StampedPose> readTumTrajectory(const std::string& path);
// readTumTrajectory of a file's text; `path` names it in errors and warnings (tests, the fuzz target).
std::vector<StampedPose> parseTumTrajectory(const std::string& text, const std::string& path);

// readTumTrajectory for a file that must hold poses, such as the ground truth or the estimate an evaluation
// compares: errors call the file by its `role` ("ground-truth file"), one that cannot be opened is named
// unreadable (with the system's reason), and one without a usable pose (empty, only comments, or every line
// skipped) is an error saying so instead of an empty trajectory.
std::vector<StampedPose> readTumTrajectoryWithPoses(const std::string& path, const std::string& role);

// Writes poses in the TUM format with a header comment: timestamps with %.6f, translations and quaternions with
// %.9f, enough for a lossless round trip of the TUM data (microsecond stamps). The file is written under a
// temporary name and renamed (atomic_file.h). Throws core::Error when the file cannot be written.
void writeTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses);

// The header comment and one pose's line as writeTumTrajectory writes them (for files written a line at a time).
inline constexpr const char* kTumTrajectoryHeader = "# timestamp tx ty tz qx qy qz qw (camera-to-world)\n";
std::string formatTumPose(const StampedPose& pose);

}  // namespace amos::io
