#include "amos/synth/tum_writer.h"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "amos/core/error.h"
#include "amos/synth/png_writer.h"

namespace amos::synth {

namespace fs = std::filesystem;

std::string formatTimestamp(double t) { return fmt::format("{:.6f}", t); }

namespace {
void openIndex(std::ofstream& out, const fs::path& path, const std::string& what, const std::string& title,
               const std::string& columns) {
  out.open(path);
  core::require(out.good(), "synth: cannot write " + path.string());
  out << "# " << what << "\n# file: '" << title << "'\n# " << columns << "\n";
}

}  // namespace

TumWriter::TumWriter(const std::string& output_dir, const SequenceGenerator& generator)
    : dir_(output_dir), generator_(generator) {
  std::error_code ec;
  for (const char* sub : {"rgb", "depth", "masks"}) fs::create_directories(fs::path(dir_) / sub, ec);
  core::require(!ec && fs::is_directory(fs::path(dir_) / "masks"),
                "synth: cannot create " + output_dir + ": " + ec.message());
  const SequenceOptions& o = generator.options();
  const std::string title =
      fmt::format("amos synth preset {} seed {}{}", o.preset, o.seed, o.movers ? "" : " no movers");
  openIndex(rgb_, fs::path(dir_) / "rgb.txt", "color images", title, "timestamp filename");
  openIndex(depth_, fs::path(dir_) / "depth.txt", "depth maps", title, "timestamp filename");
  openIndex(masks_, fs::path(dir_) / "masks.txt", "instance masks (16-bit, 0 = static, else instance id)", title,
            "timestamp filename");
  openIndex(gt_, fs::path(dir_) / "groundtruth.txt", "ground truth trajectory", title,
            "timestamp tx ty tz qx qy qz qw");
  assoc_.open(fs::path(dir_) / "associations.txt");
  core::require(assoc_.good(), "synth: cannot write associations.txt in " + output_dir);
}

void TumWriter::add(const SyntheticFrame& f) {
  const std::string stamp = formatTimestamp(f.timestamp);
  const std::string depth_stamp = formatTimestamp(f.depth_timestamp);  // differs with a depth time offset
  writePng((fs::path(dir_) / "rgb" / (stamp + ".png")).string(), f.bgr);
  writePng((fs::path(dir_) / "depth" / (depth_stamp + ".png")).string(), f.depth_raw);
  writePng((fs::path(dir_) / "masks" / (stamp + ".png")).string(), f.mask);
  rgb_ << stamp << " rgb/" << stamp << ".png\n";
  depth_ << depth_stamp << " depth/" << depth_stamp << ".png\n";
  masks_ << stamp << " masks/" << stamp << ".png\n";
  assoc_ << stamp << " rgb/" << stamp << ".png " << depth_stamp << " depth/" << depth_stamp << ".png\n";
  const Eigen::Quaterniond q(f.T_wc.linear());
  const Eigen::Vector3d t = f.T_wc.translation();
  gt_ << stamp
      << fmt::format(" {:.6f} {:.6f} {:.6f} {:.9f} {:.9f} {:.9f} {:.9f}\n", t.x(), t.y(), t.z(), q.x(), q.y(), q.z(),
                     q.w());
  for (std::uint16_t id : f.moving) {
    auto& ranges = moving_ranges_[id];
    if (!ranges.empty() && ranges.back().second == f.index - 1)
      ranges.back().second = f.index;
    else
      ranges.emplace_back(f.index, f.index);
  }
  ++frames_;
}

void TumWriter::finish() {
  const SequenceOptions& o = generator_.options();
  const Preset& p = generator_.preset();
  nlohmann::json j;
  j["instances"] = nlohmann::json::object();
  for (const InstanceInfo& info : generator_.instances()) {
    nlohmann::json ranges = nlohmann::json::array();
    for (const auto& r : moving_ranges_[info.id]) ranges.push_back({r.first, r.second});
    j["instances"][std::to_string(info.id)] = {
        {"class", info.category}, {"name", info.name}, {"moving_frames", ranges}};
  }
  const core::CameraIntrinsics& k = o.sensor.intrinsics;
  j["sequence"] = {
      {"preset", o.preset},
      {"description", p.description},
      {"seed", o.seed},
      {"frames", frames_},
      {"movers", o.movers},
      {"camera_motion", toString(p.motion)},
      {"static_counterpart", p.static_counterpart},
      {"fps", o.sensor.fps},
      {"camera", {{"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}, {"width", k.width}, {"height", k.height}}},
      {"depth_factor", o.sensor.depth.depth_factor},
      {"depth_noise",
       {{"enabled", o.sensor.depth.enabled},
        {"sigma", fmt::format("{} + {} * (z - {})^2", o.sensor.depth.sigma_base_m, o.sensor.depth.sigma_quadratic,
                              o.sensor.depth.sigma_offset_m)},
        {"min_range_m", o.sensor.depth.min_range_m},
        {"max_range_m", o.sensor.depth.max_range_m}}},
      {"motion_blur", o.sensor.motion_blur},
      {"mask_convention", "masks/*.png 16-bit: 0 = static scene, otherwise the instance id"}};
  // The sensor effects one by one, written only when one of the later switches is used (colour and depth noise
  // apart, disparity steps, timing), so that the sequences rendered before them keep their bytes.
  const SensorOptions& so = o.sensor;
  if (so.color.enabled != so.depth.enabled || so.disparity.enabled || so.timingEffects()) {
    j["sequence"]["sensor_effects"] = {
        {"depth_noise", so.depth.enabled},
        {"color_noise", so.color.enabled},
        {"disparity_quantisation", so.disparity.enabled},
        {"depth_time_offset_s", so.depth_time_offset_s},
        {"rolling_shutter_s", so.rolling_shutter_s},
        {"rolling_shutter_band_rows", so.rolling_shutter_band_rows},
        {"motion_blur", so.motion_blur},
        {"ground_truth", "camera pose at the colour image's time stamp (mid-exposure; middle row)"}};
  }
  std::ofstream out(fs::path(dir_) / "instances.json");
  core::require(out.good(), "synth: cannot write instances.json in " + dir_);
  out << j.dump(2) << "\n";
  for (std::ofstream* s : {&rgb_, &depth_, &masks_, &assoc_, &gt_}) s->flush();
}

}  // namespace amos::synth
