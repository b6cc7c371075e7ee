// amos::Slam (include/amos/slam.h): the public face of api::Engine, the SLAM system and front end that
// `amos-slam run` drives too. Frames go through the pipeline's push (stage A) and processNext (stage B); the
// arguments are checked here first (frame_checks.h), so that an error names the caller's argument. Internal errors
// (core::Error) are std::runtime_errors already, so they pass through unchanged.
#include "amos/slam.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <deque>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <utility>

#include "amos/api/allocator_tuning.h"
#include "amos/api/dense_feed.h"
#include "amos/api/engine.h"
#include "amos/api/frame_checks.h"
#include "amos/api/logging_default.h"
#include "amos/api/run_outputs.h"
#include "amos/api/settings_overrides.h"
#include "amos/api/settings_sections.h"
#include "amos/config/settings.h"
#include "amos/core/error.h"
#include "amos/core/whole_file.h"
#include "amos/io/dataset.h"
#include "amos/io/trajectory.h"
#include "amos/report/frame_log.h"

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

std::string fileText(const std::string& path) {
  return core::readWholeFileOrThrow(path, fmt::format("amos::Options::settings_file: cannot read '{}'", path));
}

config::Settings readSettings(const Options& options) {
  if (options.overrides.empty() && !options.settings_file.empty())
    return config::loadSettings(options.settings_file, api::settingsSections());
  core::require(!options.settings_file.empty() || !options.settings_yaml.empty(),
                "amos::Options: set settings_file or settings_yaml");
  const bool file = !options.settings_file.empty();
  const std::string text = file ? fileText(options.settings_file) : options.settings_yaml;
  // Parsed under the file's own name, so that errors and relative paths are the file's.
  return config::parseSettings(api::withOverrides(text, options.overrides, "amos::Options::overrides"),
                               file ? options.settings_file : "<Options::settings_yaml>", api::settingsSections());
}

// The keyframes mapped and not yet taken, and the user's callback; shared with the mapping thread's hook.
struct KeyFrameEvents {
  std::function<void(const KeyFrame&)> callback;
  std::mutex mutex;
  std::deque<KeyFrame> pending;  // guarded by mutex
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

const char* toString(Mode mode) {
  switch (mode) {
    case Mode::kNone: return "none";
    case Mode::kPrior: return "prior";
    case Mode::kGeometry: return "geometry";
    case Mode::kFull: return "full";
    case Mode::kFromSettings: return "from_settings";
  }
  return "?";
}

Mode parseMode(const std::string& name) {
  for (const Mode m : {Mode::kNone, Mode::kPrior, Mode::kGeometry, Mode::kFull})
    if (name == toString(m)) return m;
  core::require(name.empty() || name == toString(Mode::kFromSettings),
                fmt::format("amos::parseMode: mode '{}' is not one of none, prior, geometry, full", name));
  return Mode::kFromSettings;
}

struct Slam::Impl {
  mutable std::mutex mutex;  // serialises the public calls
  config::Settings settings;
  io::ReaderOptions reader;
  bool localization_only = false;
  bool map_loaded = false;
  bool finished = false;
  std::size_t frames = 0;  // submitted
  std::optional<double> last_timestamp;
  std::unique_ptr<KeyFrameEvents> events = std::make_unique<KeyFrameEvents>();
  std::unique_ptr<api::DenseFeed> dense;  // Options::dense
  api::EngineRun run;                     // for writeOutputs (run.settings: set below)
  std::optional<std::chrono::steady_clock::time_point> first_frame, finished_at;
  std::optional<std::chrono::steady_clock::time_point> last_result;  // when next() last returned
  std::vector<report::FrameRecord> records;  // every frame's line of run's per-frame files (writeOutputs)
  report::DepthDropouts depth_dropouts;
  std::unique_ptr<api::Engine> engine;    // last: its threads stop before the rest goes

  explicit Impl(const Options& options) : settings(readSettings(options)), reader(settings.readerOptions()) {
    // First: without Open3D, Options::dense is refused before the models are loaded.
    if (options.dense) dense = std::make_unique<api::DenseFeed>(settings);
    if (options.tune_allocator) api::tuneAllocatorOnce();
    localization_only = options.localization_only;
    events->callback = options.on_keyframe;
    api::EngineOptions o;
    o.mode = options.mode == Mode::kFromSettings ? "" : toString(options.mode);
    o.models_dir = options.models_dir;
    o.installed_models_dir = options.installed_models_dir;
    o.deterministic = options.deterministic;
    o.load_map = options.map_file;
    o.localize = options.localization_only;
    o.after_keyframe = hook();
    o.model_option_names = {"Options::models_dir", "Set amos::Options::models_dir (Python: models_dir=)",
                            "Mode::kGeometry or Mode::kNone"};
    engine = std::make_unique<api::Engine>(settings, o);
    map_loaded = !options.map_file.empty();
    run.settings = &settings;
    run.settings_file = options.settings_file;
    run.mode = o.mode;
    run.deterministic = options.deterministic;
  }

  double wallTimeS() const {
    if (!first_frame) return 0;
    const auto end = finished_at.value_or(std::chrono::steady_clock::now());
    return std::chrono::duration<double>(end - *first_frame).count();
  }

  cv::Size imageSize() const { return {reader.width, reader.height}; }

  // Runs in the mapping thread: the keyframe's pose read under the map's shared lock (the mapping thread holds no
  // lock of the map when it calls this).
  mapping::KeyFrameHook hook() {
    return [this](const map::KeyFramePtr& kf) {
      KeyFrame e;
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

  std::size_t pending() const { return finished ? 0 : engine->pipeline().waiting(); }

  void submit(const cv::Mat& bgr, const cv::Mat& depth, double timestamp, const cv::Mat& prior_mask) {
    core::require(!finished, "amos::Slam::submit: finish() was called; frames are no longer accepted");
    core::require(!localization_only || map_loaded,
                  "amos::Slam: localization_only needs a map (Options::map_file, or loadMap before the first frame)");
    core::require(pending() < kMaxPending,
                  fmt::format("amos::Slam::submit: {} frames already wait (at most {}): call next() first",
                              pending(), kMaxPending));
    api::checkFrame({bgr, depth, timestamp, prior_mask}, imageSize(), last_timestamp, "amos::Slam::track");
    if (!first_frame) first_frame = std::chrono::steady_clock::now();
    engine->pipeline().push(frame(bgr, depth, timestamp), prior_mask.empty() ? cv::Mat() : prior_mask.clone());
    last_timestamp = timestamp;
    ++frames;
  }

  FrameResult next() {
    core::require(pending() > 0, "amos::Slam::next: no frame was submitted");
    const system::ProcessedFrame out = engine->pipeline().processNext();
    FrameResult r;
    r.frame = out.frame.index;
    r.timestamp = out.frame.timestamp;
    r.state = publicState(out.slam.track.state);
    if (r.state == TrackingState::kOk) r.T_wc = out.slam.track.T_cw.inverse().matrix();
    r.new_keyframe = out.slam.track.new_keyframe;
    r.relocalized = out.slam.track.relocalized;
    r.dynamic_mask =
        out.dynamic_mask.empty() ? cv::Mat::zeros(out.frame.bgr.size(), CV_8U) : out.dynamic_mask.clone();
    r.keypoints = out.slam.keypoints + out.slam.removed_dynamic;  // the core counts the kept ones
    r.keypoints_removed = out.slam.removed_dynamic;
    r.extract_ms = out.slam.extract_ms;
    r.build_ms = out.slam.build_ms;
    r.track_ms = out.slam.track_ms;
    if (dense) dense->push(out);
    keepRecord(out);
    return r;
  }

  // What `amos-slam run`'s per-frame files and stats.json say of the frame (run/controller.cc keeps the same).
  void keepRecord(const system::ProcessedFrame& out) {
    const auto now = std::chrono::steady_clock::now();
    report::FrameRecord record = report::frameRecord(out);
    record.frame_ms = std::chrono::duration<double, std::milli>(now - last_result.value_or(*first_frame)).count();
    last_result = now;
    records.push_back(std::move(record));
    report::countDepthDropout(out, depth_dropouts);
  }

  void finish() {
    if (finished) return;
    while (pending() > 0) next();  // frames submitted and not taken: their poses belong in the trajectory
    engine->pipeline().finish();
    if (dense) dense->finish();
    finished = true;
    finished_at = std::chrono::steady_clock::now();
  }
};

namespace {

// The Slam's state, for the call `method`; a moved-from Slam is an error naming it. (A template: Slam::Impl is
// private.)
template <typename Pointer>
auto& useSlam(const Pointer& impl, const char* method) {
  core::require(impl != nullptr, fmt::format("amos::Slam::{}: this Slam was moved from", method));
  return *impl;
}

}  // namespace

Slam::Slam(const Options& options) : impl_((api::useDefaultLoggingOnce(), std::make_unique<Impl>(options))) {}

Slam::~Slam() {
  if (!impl_) return;
  try {
    finish();
  } catch (const std::exception& e) {
    spdlog::error("amos::Slam: finishing in the destructor failed: {}", e.what());
  }
}

Slam::Slam(Slam&&) noexcept = default;

Slam& Slam::operator=(Slam&& other) noexcept {
  if (this == &other) return *this;
  if (impl_) {
    try {
      finish();
    } catch (const std::exception& e) {
      spdlog::error("amos::Slam: finishing the Slam assigned over failed: {}", e.what());
    }
  }
  impl_ = std::move(other.impl_);
  return *this;
}

FrameResult Slam::track(const cv::Mat& bgr, const cv::Mat& depth, double timestamp, const cv::Mat& prior_mask) {
  auto& impl = useSlam(impl_, "track");
  std::lock_guard lock(impl.mutex);
  core::require(impl.pending() == 0, "amos::Slam::track: frames submitted with submit() wait: take them with next()");
  impl.submit(bgr, depth, timestamp, prior_mask);
  return impl.next();
}

std::size_t Slam::trackFrames(const std::function<std::optional<InputFrame>()>& source,
                              const std::function<void(const FrameResult&)>& on_result) {
  core::require(static_cast<bool>(source), "amos::Slam::trackFrames: argument 'source' is empty");
  core::require(pending() == 0, "amos::Slam::trackFrames: frames submitted with submit() wait: take them first");
  std::size_t done = 0;
  bool more = true;
  const auto feed = [&] {
    std::optional<InputFrame> f = source();
    if (f) submit(f->bgr, f->depth, f->timestamp, f->prior_mask);
    more = f.has_value();
  };
  try {
    feed();  // one frame of look-ahead: stage A of frame k+1 runs while frame k is tracked
    while (pending() > 0) {
      if (more && pending() < 2) feed();
      const FrameResult result = next();
      ++done;
      if (on_result) on_result(result);
    }
  } catch (...) {
    while (pending() > 0) next();  // the frames taken are tracked, their poses kept
    throw;
  }
  return done;
}

void Slam::submit(const cv::Mat& bgr, const cv::Mat& depth, double timestamp, const cv::Mat& prior_mask) {
  auto& impl = useSlam(impl_, "submit");
  std::lock_guard lock(impl.mutex);
  impl.submit(bgr, depth, timestamp, prior_mask);
}

FrameResult Slam::next() {
  auto& impl = useSlam(impl_, "next");
  std::lock_guard lock(impl.mutex);
  return impl.next();
}

std::size_t Slam::pending() const {
  const auto& impl = useSlam(impl_, "pending");
  std::lock_guard lock(impl.mutex);
  return impl.pending();
}

void Slam::loadMap(const std::string& path) {
  auto& impl = useSlam(impl_, "loadMap");
  std::lock_guard lock(impl.mutex);
  core::require(impl.frames == 0, "amos::Slam::loadMap: only before the first frame");
  impl.engine->slam().loadMap(path);
  impl.map_loaded = true;
}

void Slam::finish() {
  auto& impl = useSlam(impl_, "finish");
  std::lock_guard lock(impl.mutex);
  impl.finish();
}

bool Slam::finished() const {
  const auto& impl = useSlam(impl_, "finished");
  std::lock_guard lock(impl.mutex);
  return impl.finished;
}

void Slam::saveMap(const std::string& path) const {
  const auto& impl = useSlam(impl_, "saveMap");
  std::lock_guard lock(impl.mutex);
  impl.engine->slam().saveMap(path);
}

void Slam::writeOutputs(const std::string& dir, const RunDescription& run) const {
  const auto& impl = useSlam(impl_, "writeOutputs");
  std::lock_guard lock(impl.mutex);
  api::EngineRun engine_run = impl.run;
  engine_run.wall_time_s = impl.wallTimeS();
  engine_run.frames = &impl.records;
  engine_run.depth_dropouts = impl.depth_dropouts;
  api::writeRunOutputs(dir, *impl.engine, engine_run, run);
}

std::vector<std::string> Slam::outputNames() { return api::runOutputNames(); }

std::vector<StampedPose> Slam::trajectory() const {
  const auto& impl = useSlam(impl_, "trajectory");
  std::lock_guard lock(impl.mutex);
  return publicPoses(impl.engine->slam().trajectory());
}

void Slam::writeTrajectory(const std::string& path) const {
  const auto& impl = useSlam(impl_, "writeTrajectory");
  std::lock_guard lock(impl.mutex);
  io::writeTumTrajectory(path, impl.engine->slam().trajectory());
}

std::vector<KeyFrame> Slam::keyFrames() const {
  const auto& impl = useSlam(impl_, "keyFrames");
  std::lock_guard lock(impl.mutex);
  const map::Map& map = impl.engine->slam().map();
  std::vector<KeyFrame> out;
  std::shared_lock map_lock(map.mutex());
  for (const map::KeyFramePtr& kf : map.keyFrames())
    if (!kf->isBad()) out.push_back({kf->id(), kf->timestamp(), kf->T_wc().matrix()});
  return out;
}

std::vector<KeyFrame> Slam::takeKeyFrameEvents() {
  auto& impl = useSlam(impl_, "takeKeyFrameEvents");
  std::lock_guard lock(impl.events->mutex);
  std::vector<KeyFrame> out(impl.events->pending.begin(), impl.events->pending.end());
  impl.events->pending.clear();
  return out;
}

std::vector<Eigen::Vector3d> Slam::mapPoints() const {
  const auto& impl = useSlam(impl_, "mapPoints");
  std::lock_guard lock(impl.mutex);
  return impl.engine->slam().mapPointPositions();
}

MapSummary Slam::summary() const {
  const auto& impl = useSlam(impl_, "summary");
  std::lock_guard lock(impl.mutex);
  const system::SlamStats s = impl.engine->slam().stats();
  MapSummary m;
  m.keyframes = s.keyframes;
  m.map_points = s.map_points;
  m.loops_closed = s.loops_closed;
  m.frames = s.frames;
  m.tracked = s.tracked;
  m.lost = s.lost;
  return m;
}

DenseMap Slam::denseMap() const {
  const auto& impl = useSlam(impl_, "denseMap");
  std::lock_guard lock(impl.mutex);
  core::require(impl.dense != nullptr, "amos::Slam::denseMap: the Slam was made without Options::dense");
  core::require(impl.finished, "amos::Slam::denseMap: only after finish() (the map is fused with the final "
                               "trajectory)");
  return impl.dense->fuse(impl.engine->slam().trajectory());
}

std::optional<DenseSnapshot> Slam::denseSnapshot() const {
  const auto& impl = useSlam(impl_, "denseSnapshot");
  std::lock_guard lock(impl.mutex);
  core::require(impl.dense != nullptr, "amos::Slam::denseSnapshot: the Slam was made without Options::dense");
  return impl.dense->snapshot();
}

std::optional<OccupancyGrid> Slam::denseLiveGrid() const {
  const auto& impl = useSlam(impl_, "denseLiveGrid");
  std::vector<io::StampedPose> trajectory;
  {
    std::lock_guard lock(impl.mutex);
    core::require(impl.dense != nullptr, "amos::Slam::denseLiveGrid: the Slam was made without Options::dense");
    trajectory = impl.engine->slam().trajectory();
  }
  return impl.dense->liveGrid(trajectory);  // outside the lock: tracking goes on while the grid is built
}

cv::Size Slam::imageSize() const { return useSlam(impl_, "imageSize").imageSize(); }

}  // namespace amos
