#include "amos/eval/ground_truth_masks.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "amos/core/error.h"
#include "amos/io/image_codecs.h"
#include "amos/io/text_lines.h"

namespace amos::eval {

namespace fs = std::filesystem;

bool GroundTruthInstance::movingAt(int frame) const {
  for (const auto& [first, last] : moving_frames)
    if (frame >= first && frame <= last) return true;
  return false;
}

std::optional<GroundTruthMasks> GroundTruthMasks::find(const std::string& sequence_dir) {
  const fs::path dir(sequence_dir);
  const fs::path index = dir / "masks.txt", instances = dir / "instances.json";
  if (!fs::is_regular_file(index) || !fs::is_regular_file(instances)) return std::nullopt;
  return GroundTruthMasks(index.string(), instances.string());
}

GroundTruthMasks::GroundTruthMasks(const std::string& masks_index, const std::string& instances_json) {
  const fs::path base = fs::path(masks_index).parent_path();
  for (const io::TextLine& line : io::readTextLines(masks_index)) {
    core::require(line.fields.size() >= 2,
                  masks_index + ":" + std::to_string(line.number) + ": expected `timestamp file`");
    const double t = io::parseNumber(line.fields[0], masks_index, line.number, "timestamp");
    core::require(stamps_.empty() || t > stamps_.back(),
                  masks_index + ":" + std::to_string(line.number) + ": time stamps must increase");
    stamps_.push_back(t);
    files_.push_back((base / line.fields[1]).string());
  }
  std::ifstream in(instances_json);
  core::require(in.good(), "cannot read " + instances_json);
  nlohmann::json j;
  try {
    in >> j;
    for (const auto& [key, value] : j.at("instances").items()) {
      GroundTruthInstance inst;
      inst.id = static_cast<std::uint16_t>(std::stoi(key));
      inst.category = value.value("class", "");
      inst.name = value.value("name", "");
      for (const auto& range : value.at("moving_frames")) inst.moving_frames.emplace_back(range.at(0), range.at(1));
      instances_.push_back(std::move(inst));
    }
  } catch (const std::exception& e) {
    throw core::Error(instances_json + ": malformed instances file: " + e.what());
  }
}

std::optional<int> GroundTruthMasks::frameAt(double t, double max_dt) const {
  const auto it = std::lower_bound(stamps_.begin(), stamps_.end(), t);
  std::optional<int> best;
  double best_dt = max_dt;
  for (auto c : {it, it == stamps_.begin() ? it : it - 1}) {
    if (c == stamps_.end()) continue;
    const double dt = std::fabs(*c - t);
    if (dt <= best_dt) best_dt = dt, best = static_cast<int>(c - stamps_.begin());
  }
  return best;
}

cv::Mat GroundTruthMasks::instanceMask(int frame) const {
  core::require(frame >= 0 && frame < static_cast<int>(files_.size()), "GroundTruthMasks: frame out of range");
  cv::Mat m = io::readImage(files_[frame], io::kReadUnchanged);
  core::require(!m.empty(), "cannot read ground-truth mask " + files_[frame]);
  core::require(m.channels() == 1 && (m.depth() == CV_16U || m.depth() == CV_8U),
                "ground-truth mask " + files_[frame] + " must be a single-channel 8- or 16-bit image");
  if (m.depth() == CV_8U) m.convertTo(m, CV_16U);
  return m;
}

cv::Mat GroundTruthMasks::moverMask(int frame) const { return moverMask(instanceMask(frame), movingIds(frame)); }

std::vector<bool> GroundTruthMasks::movingIds(int frame) const {
  std::vector<bool> moving(65536, false);
  for (const GroundTruthInstance& inst : instances_) moving[inst.id] = inst.movingAt(frame);
  return moving;
}

cv::Mat GroundTruthMasks::moverMask(const cv::Mat& ids, const std::vector<bool>& moving) {
  core::require(ids.type() == CV_16UC1, "GroundTruthMasks::moverMask: instance ids must be CV_16U");
  cv::Mat out(ids.size(), CV_8U);
  for (int y = 0; y < ids.rows; ++y) {
    const std::uint16_t* id = ids.ptr<std::uint16_t>(y);
    uchar* o = out.ptr<uchar>(y);
    for (int x = 0; x < ids.cols; ++x) o[x] = id[x] < moving.size() && moving[id[x]] ? 255 : 0;
  }
  return out;
}

}  // namespace amos::eval
