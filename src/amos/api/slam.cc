// amos::Slam (include/amos/slam.h): the public face of api::Engine, the SLAM system and front end that
// `amos-slam run` drives too. Frames go through DynamicPipeline::process one at a time; internal errors
// (core::Error) are std::runtime_errors already, so they pass through unchanged.
#include "amos/slam.h"

#include <fmt/format.h>

#include <deque>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <utility>

#include "amos/api/engine.h"
#include "amos/config/settings.h"
#include "amos/core/error.h"
#include "amos/io/dataset.h"
#include "amos/io/trajectory.h"

namespace amos {

namespace {

TrackingState publicState(tracking::TrackingState state) {
  switch (state) {
    case tracking::TrackingState::kNotInitialized: return TrackingState::kNotInitialized;
    case tracking::TrackingState::kOk: return TrackingState::kOk;
    case tracking::TrackingState::kLost: return TrackingState::kLost;
  }
  return TrackingState::kLost;
}

std::vector<StampedPose> publicPoses(const std::vector<io::StampedPose>& poses) {
  std::vector<StampedPose> out;
  out.reserve(poses.size());
  for (const io::StampedPose& p : poses) out.push_back({p.timestamp, p.T_wc.matrix()});
  return out;
}

config::Settings readSettings(const Options& options) {
  if (!options.settings_file.empty()) return config::loadSettings(options.settings_file);
  core::require(!options.settings_yaml.empty(), "amos::Options: set settings_file or settings_yaml");
  return config::parseSettings(options.settings_yaml, "<Options::settings_yaml>");
}

// The keyframes mapped and not yet taken, and the user's callback; shared with the mapping thread's hook.
struct KeyFrameEvents {
  std::function<void(const KeyFrameEvent&)> callback;
  std::mutex mutex;
  std::deque<KeyFrameEvent> pending;  // guarded by mutex
};

}  // namespace

const char* toString(TrackingState state) {
  switch (state) {
    case TrackingState::kNotInitialized: return "not_initialized";
    case TrackingState::kOk: return "ok";
    case TrackingState::kLost: return "lost";
  }
  return "?";
}

struct Slam::Impl {
  config::Settings settings;
  io::ReaderOptions reader;
  bool localization_only = false;
  bool map_loaded = false;
  bool finished = false;
  std::size_t frames = 0;  // submitted
  std::unique_ptr<KeyFrameEvents> events = std::make_unique<KeyFrameEvents>();
  std::unique_ptr<api::Engine> engine;  // last: its threads stop before the rest goes

  explicit Impl(const Options& options) : settings(readSettings(options)), reader(settings.readerOptions()) {
    localization_only = options.localization_only;
    events->callback = options.on_keyframe;
    api::EngineOptions o;
    o.mode = options.mode;  // "" = Dynamic.mode
    o.models_dir = options.models_dir;
    o.installed_models_dir = options.installed_models_dir;
    o.deterministic = options.deterministic;
    o.load_map = options.map_file;
    o.localize = options.localization_only;
    o.after_keyframe = hook();
    engine = std::make_unique<api::Engine>(settings, o);
    map_loaded = !options.map_file.empty();
  }

  // Runs in the mapping thread: the keyframe's pose read under the map's shared lock (the mapping thread holds no
  // lock of the map when it calls this).
  mapping::KeyFrameHook hook() {
    return [this](const map::KeyFramePtr& kf) {
      KeyFrameEvent e;
      e.id = kf->id();
      e.timestamp = kf->timestamp();
      {
        std::shared_lock lock(engine->slam().map().mutex());
        e.T_wc = kf->T_wc().matrix();
      }
      if (events->callback) events->callback(e);
      std::lock_guard lock(events->mutex);
      events->pending.push_back(e);
    };
  }

  io::RgbdFrame frame(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
    io::AssociatedFrame names;
    names.t_rgb = names.t_depth = timestamp;
    names.rgb_file = fmt::format("track(bgr) of frame {}", frames);
    names.depth_file = fmt::format("track(depth) of frame {}", frames);
    // Copied: the pipeline may still read the colour image (a late segmentation) after track() returned.
    io::RgbdFrame f = io::rgbdFrameFromImages(names, bgr.clone(), depth, reader, frames);
    f.rgb_file = fmt::format("{:.6f}.png", timestamp);  // outputs name a frame by its stem, as for live frames
    f.arrival = std::chrono::steady_clock::now();
    return f;
  }
};

Slam::Slam(const Options& options) : impl_(std::make_unique<Impl>(options)) {}

Slam::Slam(const std::string& settings_file, const std::string& mode, bool deterministic) {
  Options o;
  o.settings_file = settings_file;
  o.mode = mode;
  o.deterministic = deterministic;
  impl_ = std::make_unique<Impl>(o);
}

Slam::~Slam() {
  if (impl_) finish();
}
Slam::Slam(Slam&&) noexcept = default;
Slam& Slam::operator=(Slam&&) noexcept = default;

FrameResult Slam::track(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
  submit(bgr, depth, timestamp);
  return next();
}

void Slam::submit(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
  core::require(impl_ != nullptr, "amos::Slam: this Slam was moved from");
  core::require(!impl_->finished, "amos::Slam::submit: finish() was called; frames are no longer accepted");
  core::require(!impl_->localization_only || impl_->map_loaded,
                "amos::Slam: localization_only needs a map (Options::map_file, or loadMap before the first frame)");
  core::require(pending() < kMaxPending,
                fmt::format("amos::Slam::submit: {} frames already wait (at most {}): call next() first", pending(),
                            kMaxPending));
  impl_->engine->pipeline().push(impl_->frame(bgr, depth, timestamp));
  ++impl_->frames;
}

FrameResult Slam::next() {
  core::require(impl_ != nullptr, "amos::Slam: this Slam was moved from");
  core::require(pending() > 0, "amos::Slam::next: no frame was submitted");
  const system::ProcessedFrame out = impl_->engine->pipeline().processNext();
  FrameResult r;
  r.frame = out.frame.index;
  r.timestamp = out.frame.timestamp;
  r.state = publicState(out.slam.track.state);
  r.T_wc = out.slam.track.T_cw.inverse().matrix();
  r.new_keyframe = out.slam.track.new_keyframe;
  r.relocalized = out.slam.track.relocalized;
  r.dynamic_mask =
      out.dynamic_mask.empty() ? cv::Mat::zeros(out.frame.bgr.size(), CV_8U) : out.dynamic_mask.clone();
  r.keypoints = out.slam.keypoints;
  r.keypoints_removed = out.slam.removed_dynamic;
  return r;
}

std::size_t Slam::pending() const { return impl_->finished ? 0 : impl_->engine->pipeline().waiting(); }

void Slam::loadMap(const std::string& path) {
  core::require(impl_->frames == 0, "amos::Slam::loadMap: only before the first frame");
  impl_->engine->slam().loadMap(path);
  impl_->map_loaded = true;
}

void Slam::finish() {
  if (impl_->finished) return;
  impl_->engine->pipeline().finish();
  impl_->finished = true;
}

void Slam::saveMap(const std::string& path) const { impl_->engine->slam().saveMap(path); }

std::vector<StampedPose> Slam::trajectory() const { return publicPoses(impl_->engine->slam().trajectory()); }

void Slam::writeTrajectory(const std::string& path) const {
  io::writeTumTrajectory(path, impl_->engine->slam().trajectory());
}

std::vector<StampedPose> Slam::keyFrames() const { return publicPoses(impl_->engine->slam().keyframeTrajectory()); }

std::vector<KeyFrameEvent> Slam::takeKeyFrameEvents() {
  std::lock_guard lock(impl_->events->mutex);
  std::vector<KeyFrameEvent> out(impl_->events->pending.begin(), impl_->events->pending.end());
  impl_->events->pending.clear();
  return out;
}

std::vector<Eigen::Vector3d> Slam::mapPoints() const { return impl_->engine->slam().mapPointPositions(); }

MapSummary Slam::summary() const {
  const system::SlamStats s = impl_->engine->slam().stats();
  MapSummary m;
  m.keyframes = s.keyframes;
  m.map_points = s.map_points;
  m.loops_closed = s.loops_closed;
  m.frames = s.frames;
  m.tracked = s.tracked;
  m.lost = s.lost;
  return m;
}

}  // namespace amos
