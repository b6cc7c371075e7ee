#include "amos/synth/sequence.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <thread>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/synth/camera_path.h"
#include "amos/synth/furniture.h"
#include "amos/synth/image_assets.h"
#include "amos/synth/procedural_textures.h"
#include "amos/synth/random.h"
#include "amos/synth/room.h"
#include "amos/synth/static_surface.h"
#include "amos/synth/swept_volume.h"
#include "amos/synth/tum_writer.h"

namespace amos::synth {

using Eigen::Vector2d;
using Eigen::Vector3d;

void SequenceOptions::check() const {
  findPreset(preset);
  core::require(frames >= 0 && frames <= 100000, "synth.frames must be in [0, 100000] (0 = preset default)");
  core::require(metres_per_texel >= 0.001 && metres_per_texel <= 0.05,
                "synth.metres_per_texel must be in [0.001, 0.05]");
  core::require(start_timestamp >= 0, "synth.start_timestamp must be >= 0");
  sensor.check();
}

struct SequenceGenerator::Impl {
  SequenceOptions options;
  const Preset* preset = nullptr;
  int frames = 0;
  TextureBank textures;
  Room room;
  std::unique_ptr<CameraPath> path;
  std::vector<std::unique_ptr<Mover>> movers;
  std::vector<InstanceInfo> instances;
  std::unique_ptr<Renderer> renderer;
  std::unique_ptr<SensorModel> sensor;

  void buildMovers(const std::vector<cv::Mat>& photos, const std::vector<PersonCutout>& cutouts);
  SceneGeometry moverGeometry(double t, const Vector3d& camera) const {
    SceneGeometry g;
    for (const auto& m : movers) m->addGeometry(t, camera, g);
    return g;
  }
};

void SequenceGenerator::Impl::buildMovers(const std::vector<cv::Mat>& photos,
                                          const std::vector<PersonCutout>& cutouts) {
  Random rng(deriveSeed(options.seed, Stream::kMovers));
  AssetContext ctx{textures, rng, photos, options.metres_per_texel};
  const RoomLayout& L = room.layout;
  std::uint16_t next_id = 1;
  std::size_t next_standing = 0, next_sitting = 0;
  const std::size_t cutout_offset = cutouts.empty() ? 0 : options.seed % cutouts.size();
  // Cut-outs: walkers take standing (or leg-less) photos, sitters prefer seated ones.
  auto pickCutout = [&](bool sitting) -> const PersonCutout* {
    std::vector<const PersonCutout*> preferred, other;
    for (std::size_t i = 0; i < cutouts.size(); ++i) {
      const PersonCutout& c = cutouts[(i + cutout_offset) % cutouts.size()];
      const bool seated = c.kind == PersonCutout::Kind::kSitting;
      (seated == sitting ? preferred : other).push_back(&c);
    }
    if (!preferred.empty()) return preferred[(sitting ? next_sitting++ : next_standing++) % preferred.size()];
    if (!other.empty()) return other[(sitting ? next_sitting++ : next_standing++) % other.size()];
    return nullptr;
  };
  auto lookFor = [&](bool sitting) {
    const PersonCutout* c = pickCutout(sitting);
    return c ? cutoutLook(ctx, *c) : proceduralLook(ctx);
  };
  for (MoverKind kind : preset->movers) {
    InstanceInfo info;
    info.id = next_id++;
    const double offset = rng.uniform(0, 20);
    switch (kind) {
      case MoverKind::kWalkerAcross:
        info = {info.id, "person", "walker_across"};
        movers.push_back(std::make_unique<WalkingPerson>(
            info, lookFor(false), PingPongPath({{1.05, -1.1}, {1.05, 1.2}}, rng.uniform(0.8, 1.0), 1.2, 0.25, offset)));
        break;
      case MoverKind::kWalkerAround:
        info = {info.id, "person", "walker_around"};
        movers.push_back(std::make_unique<WalkingPerson>(
            info, lookFor(false),
            PingPongPath({{0.5, 1.9}, {2.2, 1.65}, {3.2, 0.95}, {3.2, -0.75}, {2.7, -1.0}, {2.2, -1.5}, {0.6, -1.3}},
                         rng.uniform(0.7, 0.9), 1.5, 0.25, offset)));
        break;
      case MoverKind::kSitterLeft:
      case MoverKind::kSitterRight: {
        const bool left = kind == MoverKind::kSitterLeft;
        info = {info.id, "person", left ? "sitter_left" : "sitter_right"};
        movers.push_back(std::make_unique<SittingPerson>(info, lookFor(true), L.seats[left ? 0 : 1], M_PI,
                                                         L.seat_height, rng.bits()));
        break;
      }
      case MoverKind::kPushedBox:
        info = {info.id, "object", "pushed_box"};
        movers.push_back(std::make_unique<SlidingObject>(info, cardboardBox(ctx, {0.6, 0.5, 0.5}),
                                                         PingPongPath({{1.2, -1.6}, {1.2, 1.5}}, 0.3, 1.5, 1.0, offset),
                                                         0.1, 0.12));
        break;
      case MoverKind::kRollingChair:
        info = {info.id, "object", "rolling_chair"};
        movers.push_back(std::make_unique<SlidingObject>(
            info, officeChair(ctx), PingPongPath({{0.45, 1.3}, {0.5, 0.2}, {0.45, -1.0}}, 0.45, 2.0, 0.8, offset), M_PI,
            1.5));
        break;
      case MoverKind::kSwingingDoor:
        info = {info.id, "object", "swinging_door"};
        movers.push_back(std::make_unique<SwingingDoor>(
            info, doorLeaf(ctx, L.door_width, L.door_height, 0.04),
            Vector3d(L.half_extent.x() - 0.03, L.door_hinge_y + L.door_width, 0), M_PI, -1.3, 9.0, offset));
        break;
      // Movers that change state: one traversal of a path (eased start and stop, PingPongPath's forward leg from
      // its start at time `begin`), at rest before and after it (ScheduledMover).
      case MoverKind::kBoxStarts:
      case MoverKind::kBoxStops: {
        const bool starts = kind == MoverKind::kBoxStarts;
        info = {info.id, "object", starts ? "box_starting" : "box_stopping"};
        // 2 m at 0.4 m/s (starts: 4 s .. 9 s) or 0.5 m/s (stops: 0 s .. 4 s; then 6 s at rest).
        const double begin = starts ? 4.0 : 0.0, speed = starts ? 0.4 : 0.5, end = begin + 2.0 / speed;
        auto box = std::make_unique<SlidingObject>(info, cardboardBox(ctx, {0.6, 0.5, 0.5}),
                                                   PingPongPath({{1.2, -1.0}, {1.2, 1.0}}, speed, 1.0, 1.0, -begin),
                                                   0.1, 0.12);
        movers.push_back(std::make_unique<ScheduledMover>(std::move(box), begin, end));
        break;
      }
      case MoverKind::kChairPush: {
        // The chair rolls 1.6 m along +y from 3 s on; the person walks 0.55 m behind it on the same schedule, a
        // hand's reach from its back. Both stand still (in view) before and after.
        const double begin = 3.0, speed = 0.35, end = begin + 1.6 / speed;
        const InstanceInfo person{info.id, "person", "chair_pusher"};
        movers.push_back(std::make_unique<ScheduledMover>(
            std::make_unique<WalkingPerson>(person, lookFor(false),
                                            PingPongPath({{1.0, -1.05}, {1.0, 0.55}}, speed, 1.0, 1.0, -begin)),
            begin, end));
        instances.push_back(person);
        info = {next_id++, "object", "pushed_chair"};
        movers.push_back(std::make_unique<ScheduledMover>(
            std::make_unique<SlidingObject>(info, officeChair(ctx),
                                            PingPongPath({{1.0, -0.5}, {1.0, 1.1}}, speed, 1.0, 1.0, -begin),
                                            -M_PI / 2, 0.3),
            begin, end));
        break;
      }
      case MoverKind::kStandingLeaves: {
        // Stands facing the camera (the forward leg's first waypoint) until 1.5 s, then walks 3 m to the right,
        // out of the view (at 1.8 m from the camera the view is 2.2 m wide), and stays there.
        info = {info.id, "person", "standing_leaves"};
        const double begin = 1.5, speed = 1.2, end = begin + 3.0 / speed;
        movers.push_back(std::make_unique<ScheduledMover>(
            std::make_unique<WalkingPerson>(info, lookFor(false),
                                            PingPongPath({{1.4, 0.35}, {1.4, -2.65}}, speed, 1.0, 0.3, -begin)),
            begin, end));
        break;
      }
      case MoverKind::kDisguisedWalker: {
        info = {info.id, "person", "disguised_walker"};
        PersonLook disguise = proceduralLook(ctx);
        const Surface plain = ctx.add(textures::metal(cv::Size(32, 32), cv::Scalar(150, 158, 162), ctx.rng));
        disguise.shirt = disguise.trousers = disguise.skin = disguise.head = disguise.shoes = plain;
        movers.push_back(std::make_unique<DisguisedPerson>(
            info, lookFor(false), std::move(disguise),
            PingPongPath({{1.05, -1.1}, {1.05, 1.2}}, rng.uniform(0.8, 1.0), 1.2, 0.25, offset), 0.6, 2.4));
        break;
      }
      case MoverKind::kBorderWalker:
        // Along the left edge of the view (the camera at (-0.4, 0) looks along +x with 31 degrees to each side):
        // the body's centre on the edge, half of it in view, as the camera's sway moves the edge.
        info = {info.id, "person", "border_walker"};
        movers.push_back(std::make_unique<WalkingPerson>(
            info, lookFor(false), PingPongPath({{0.6, 0.6}, {2.6, 1.8}}, rng.uniform(0.8, 1.0), 0.8, 0.25, offset)));
        break;
    }
    instances.push_back(info);
  }
}

SequenceGenerator::SequenceGenerator(const SequenceOptions& options) : impl_(std::make_unique<Impl>()) {
  options.check();
  Impl& m = *impl_;
  m.options = options;
  m.preset = &findPreset(options.preset);
  m.frames = options.frames > 0 ? options.frames : m.preset->default_frames;
  std::vector<cv::Mat> photos;
  if (!options.photo_dir.empty()) photos = loadPhotos(options.photo_dir);
  std::vector<PersonCutout> cutouts;
  if (!options.person_cutout_dir.empty() && options.movers) cutouts = loadPersonCutouts(options.person_cutout_dir);
  RoomOptions room_options;
  room_options.metres_per_texel = options.metres_per_texel;
  room_options.door_is_mover = m.preset->hasMover(MoverKind::kSwingingDoor);
  m.room = buildRoom(room_options, options.seed, m.textures, photos);
  m.path = std::make_unique<CameraPath>(m.preset->motion, m.room.layout.stage, options.seed);
  if (options.movers) m.buildMovers(photos, cutouts);
  m.renderer = std::make_unique<Renderer>(options.sensor.intrinsics);
  m.sensor = std::make_unique<SensorModel>(options.sensor);
}

SequenceGenerator::~SequenceGenerator() = default;

int SequenceGenerator::frameCount() const { return impl_->frames; }
double SequenceGenerator::time(int index) const { return index / impl_->options.sensor.fps; }
double SequenceGenerator::timestamp(int index) const { return impl_->options.start_timestamp + time(index); }
core::SE3 SequenceGenerator::poseWc(int index) const { return impl_->path->poseWc(time(index)); }
const Preset& SequenceGenerator::preset() const { return *impl_->preset; }
const SequenceOptions& SequenceGenerator::options() const { return impl_->options; }
const std::vector<InstanceInfo>& SequenceGenerator::instances() const { return impl_->instances; }
const core::CameraIntrinsics& SequenceGenerator::intrinsics() const { return impl_->options.sensor.intrinsics; }

SceneGeometry SequenceGenerator::moverGeometry(double t, const Vector3d& camera) const {
  return impl_->moverGeometry(t, camera);
}

std::vector<std::uint16_t> SequenceGenerator::movingInstances(double t) const {
  // A mover moves at t if any of its defining points moved by more than 1 mm over the last 0.1 s, i.e. faster
  // than 1 cm/s (seen from one camera position, so cut-outs turning to the camera do not count). A seated person
  // shifting slowly moves by less than a millimetre per frame, hence the window.
  std::vector<std::uint16_t> ids;
  const double window = 0.1;
  const double t0 = t >= window ? t - window : t + window;
  const Vector3d camera = impl_->path->poseWc(t).translation();
  for (const auto& mover : impl_->movers) {
    SceneGeometry a, b;
    mover->addGeometry(t, camera, a);
    mover->addGeometry(t0, camera, b);
    if (a.maxDisplacement(b) > 1e-3) ids.push_back(mover->info().id);
  }
  return ids;
}

RenderedImage SequenceGenerator::renderExact(int index, bool with_static, bool with_movers, bool with_color) const {
  return renderExactAt(time(index), with_static, with_movers, with_color);
}

RenderedImage SequenceGenerator::renderExactAt(double t, bool with_static, bool with_movers, bool with_color,
                                               const RowBand& band) const {
  const Impl& m = *impl_;
  const core::SE3 T_wc = m.path->poseWc(t);
  const SceneGeometry dynamic = m.moverGeometry(t, T_wc.translation());
  std::vector<const SceneGeometry*> parts;
  if (with_static) parts.push_back(&m.room.geometry);
  if (with_movers) parts.push_back(&dynamic);
  return m.renderer->render(parts, m.textures, m.room.lighting, T_wc.inverse(), with_color, band);
}

namespace {

// The colour image exposed at time t: one render, or under a rolling shutter one render per row band, each at its
// band's time, stacked (colour, depth, instances and incidence alike).
RenderedImage exposeColor(const SequenceGenerator& generator, double t) {
  const std::vector<ExposureBand> bands = exposureBands(generator.options().sensor, t);
  if (bands.size() == 1) return generator.renderExactAt(bands[0].t, true, true, true);
  const core::CameraIntrinsics& k = generator.intrinsics();
  RenderedImage out;
  out.color = cv::Mat(k.height, k.width, CV_32FC3);
  out.depth = cv::Mat(k.height, k.width, CV_32F);
  out.instance = cv::Mat(k.height, k.width, CV_16U);
  out.incidence = cv::Mat(k.height, k.width, CV_32F);
  for (const ExposureBand& b : bands) {
    const RenderedImage part = generator.renderExactAt(b.t, true, true, true, {b.begin, b.end});
    const cv::Range rows(b.begin, b.end);
    part.color.copyTo(out.color.rowRange(rows));
    part.depth.copyTo(out.depth.rowRange(rows));
    part.instance.copyTo(out.instance.rowRange(rows));
    part.incidence.copyTo(out.incidence.rowRange(rows));
  }
  return out;
}

}  // namespace

SyntheticFrame SequenceGenerator::render(int index) const {
  core::require(index >= 0 && index < impl_->frames, "synth: frame index out of range");
  const Impl& m = *impl_;
  const SensorOptions& so = m.options.sensor;
  SyntheticFrame f;
  f.index = index;
  f.timestamp = timestamp(index);
  f.depth_timestamp = f.timestamp + so.depth_time_offset_s;
  const double t = time(index);
  f.T_wc = m.path->poseWc(t);
  RenderedImage img = exposeColor(*this, t);
  if (so.motion_blur && so.motion_blur_samples > 1 && so.exposure_s > 0) {
    // Average the colour over the exposure; depth and masks stay at mid-exposure (the time stamp).
    cv::Mat sum = img.color.clone();
    for (int i = 0; i < so.motion_blur_samples; ++i) {
      const double ts = t + so.exposure_s * (i / (so.motion_blur_samples - 1.0) - 0.5);
      if (std::abs(ts - t) < 1e-12) continue;
      sum += exposeColor(*this, ts).color;
    }
    const int used = so.motion_blur_samples % 2 == 1 ? so.motion_blur_samples : so.motion_blur_samples + 1;
    img.color = sum / used;
  }
  // Depth: a global-shutter image at t + offset; the colour render's own when that is the same image.
  const RenderedImage depth_img =
      so.timingEffects() ? renderExactAt(t + so.depth_time_offset_s, true, true, false) : RenderedImage{};
  const RenderedImage& depth_source = so.timingEffects() ? depth_img : img;
  Random rng(deriveSeed(m.options.seed, Stream::kSensor, static_cast<std::uint64_t>(index)));
  f.bgr = m.sensor->measureColor(img.color, rng);
  f.depth_raw = m.sensor->measureDepth(depth_source.depth, depth_source.incidence, rng);
  f.depth_raw.convertTo(f.depth, CV_32F, 1.0 / so.depth.depth_factor);
  f.exact_depth = depth_source.depth;
  f.mask = img.instance;
  f.moving = movingInstances(t);
  if (m.preset->coveredAt(t)) {  // a hand over the lens: no light, no infrared pattern
    f.bgr.setTo(cv::Scalar::all(0));
    f.depth_raw.setTo(0);
    f.depth.setTo(0);
  }
  return f;
}

SequenceSummary renderSequence(const SequenceOptions& options, const std::string& output_dir) {
  core::Stopwatch total;
  const SequenceGenerator generator(options);
  SequenceSummary summary;
  summary.setup_ms = total.elapsedMs();
  TumWriter writer(output_dir, generator);
  double render_ms = 0, write_ms = 0;
  for (int k = 0; k < generator.frameCount(); ++k) {
    core::Stopwatch sw;
    const SyntheticFrame frame = generator.render(k);
    render_ms += sw.elapsedMs();
    sw.restart();
    writer.add(frame);
    write_ms += sw.elapsedMs();
    if ((k + 1) % 100 == 0) spdlog::debug("synth: {} / {} frames", k + 1, generator.frameCount());
  }
  writer.finish();
  writeSurfacePly((std::filesystem::path(output_dir) / kStaticSurfaceFile).string(), staticSurfaceSamples(generator));
  writeSweptVolumePly((std::filesystem::path(output_dir) / kSweptVolumeFile).string(), sweptVolumeOf(generator));
  summary.frames = generator.frameCount();
  summary.render_ms_per_frame = render_ms / std::max(1, summary.frames);
  summary.write_ms_per_frame = write_ms / std::max(1, summary.frames);
  summary.total_s = total.elapsedMs() / 1000.0;
  return summary;
}

std::string cachedSequence(const std::string& cache_root, const std::string& preset, std::uint32_t seed, int frames) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(cache_root) / fmt::format("{}_seed{}_{}", preset, seed, frames);
  if (fs::is_directory(dir)) return dir.string();
  const fs::path partial = fs::path(cache_root) / fmt::format(".{}.partial-{}-{}", dir.filename().string(), ::getpid(),
                                                              std::hash<std::thread::id>{}(std::this_thread::get_id()));
  fs::remove_all(partial);
  SequenceOptions options;
  options.preset = preset;
  options.seed = seed;
  options.frames = frames;
  renderSequence(options, partial.string());
  std::error_code ec;
  fs::rename(partial, dir, ec);  // fails when another caller got there first: its rendering is the same
  if (ec) fs::remove_all(partial);
  core::require(fs::is_directory(dir),
                fmt::format("cannot render the sequence into '{}': {}", dir.string(), ec.message()));
  return dir.string();
}

}  // namespace amos::synth
