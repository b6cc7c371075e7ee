#include "amos/io/trajectory.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"
#include "amos/io/text_lines.h"

namespace amos::io {
namespace {

// Locale-independent parse of one whole token; accepts a leading '+' like Python's float().
bool parseDouble(const std::string& token, double& value) {
  const char* begin = token.data();
  const char* end = token.data() + token.size();
  if (begin != end && *begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end;
}

struct PoseLines {
  std::vector<StampedPose> poses;
  int lines = 0;  // pose lines read, skipped ones included
};

// The poses of `lines`, read from `path`.
PoseLines parsePoseLines(const std::vector<TextLine>& lines, const std::string& path) {
  PoseLines out;
  std::vector<StampedPose>& poses = out.poses;
  int skipped = 0;
  // readTextLines splits on blanks, tabs and commas and drops '#' comments and blank lines, like the TUM scripts.
  for (const TextLine& line : lines) {
    ++out.lines;
    const std::vector<std::string>& fields = line.fields;
    if (fields.size() != 8) {
      throw core::Error(fmt::format("{}:{}: expected 8 numbers 'timestamp tx ty tz qx qy qz qw', found {} fields",
                                    path, line.number, fields.size()));
    }
    std::array<double, 8> v{};
    for (std::size_t k = 0; k < fields.size(); ++k) {
      if (!parseDouble(fields[k], v[k])) {
        throw core::Error(fmt::format("{}:{}: field {} '{}' is not a number", path, line.number, k + 1, fields[k]));
      }
    }
    const bool finite = std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
    const bool zero_quaternion = v[4] == 0 && v[5] == 0 && v[6] == 0 && v[7] == 0;
    if (!finite || zero_quaternion) {
      // evaluate_rpe.py drops such lines too; they carry no usable pose.
      spdlog::warn("{}:{}: {}, line skipped", path, line.number, finite ? "all-zero quaternion" : "non-finite value");
      ++skipped;
      continue;
    }
    StampedPose pose;
    pose.timestamp = v[0];
    pose.T_wc = core::makeSE3(Eigen::Quaterniond(v[7], v[4], v[5], v[6]), Eigen::Vector3d(v[1], v[2], v[3]));
    poses.push_back(pose);
  }
  if (skipped > 0) spdlog::warn("{}: {} line(s) skipped", path, skipped);
  return out;
}

PoseLines readPoseLines(const std::string& path, const std::string& role) {
  core::require(std::filesystem::is_regular_file(path),
                fmt::format("{} '{}' does not exist (or is not a regular file)", role, path));
  if (!std::ifstream(path).good()) {
    throw core::Error(fmt::format("{} '{}' cannot be read: {}", role, path, std::strerror(errno)));
  }
  return parsePoseLines(readTextLines(path), path);
}

}  // namespace

std::vector<StampedPose> readTumTrajectory(const std::string& path) {
  return readPoseLines(path, "trajectory file").poses;
}

std::vector<StampedPose> parseTumTrajectory(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  return parsePoseLines(readTextLines(in), path).poses;
}

std::vector<StampedPose> readTumTrajectoryWithPoses(const std::string& path, const std::string& role) {
  PoseLines read = readPoseLines(path, role);
  core::require(read.lines > 0, fmt::format("{} '{}' is empty: it has no pose line", role, path));
  core::require(!read.poses.empty(),
                fmt::format("{} '{}' has no usable pose: all {} of its pose lines were skipped (non-finite values or "
                            "all-zero quaternions)",
                            role, path, read.lines));
  return std::move(read.poses);
}

std::string formatTumPose(const StampedPose& pose) {
  const Eigen::Vector3d t = pose.T_wc.translation();
  const Eigen::Quaterniond q(pose.T_wc.linear());
  char line[256];
  const int n = std::snprintf(line, sizeof(line), "%.6f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", pose.timestamp, t.x(),
                              t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  core::require(n > 0 && n < static_cast<int>(sizeof(line)),
                fmt::format("pose at {} does not fit a trajectory line", pose.timestamp));
  return std::string(line, static_cast<std::size_t>(n));
}

void writeTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses) {
  std::string text = kTumTrajectoryHeader;
  for (const StampedPose& pose : poses) {
    try {
      text += formatTumPose(pose);
    } catch (const core::Error& e) {
      throw core::Error(fmt::format("trajectory file '{}': {}", path, e.what()));
    }
  }
  writeFileAtomically(path, text);
}

}  // namespace amos::io
