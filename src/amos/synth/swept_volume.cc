#include "amos/synth/swept_volume.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "amos/core/error.h"
#include "amos/synth/sequence.h"

namespace amos::synth {

using Eigen::Vector3d;

namespace {

constexpr long kIndexOffset = 1L << 20;  // cell indices in [-2^20, 2^20): +-20 km at 2 cm
constexpr int kIndexBits = 21;
constexpr const char* kCellComment = "comment swept_volume cell ";

// Six consecutive back-culled quads (SceneGeometry::addBox) bound a box when the centre of their face centres lies
// behind every face.
bool boundsASolid(const std::vector<Quad>& quads, std::size_t first) {
  Vector3d centre = Vector3d::Zero();
  for (std::size_t f = first; f < first + 6; ++f) centre += quads[f].origin + 0.5 * (quads[f].edge_u + quads[f].edge_v);
  centre /= 6;
  for (std::size_t f = first; f < first + 6; ++f) {
    const Vector3d n = quads[f].edge_v.cross(quads[f].edge_u);
    if (!((centre - quads[f].origin).dot(n) < 0)) return false;
  }
  return true;
}

// Distance from p to the parallelogram (exact for rectangles, which is what the movers use).
double distanceToQuad(const Quad& q, const Vector3d& p) {
  const Vector3d d = p - q.origin;
  Eigen::Matrix2d gram;
  gram << q.edge_u.squaredNorm(), q.edge_u.dot(q.edge_v), q.edge_u.dot(q.edge_v), q.edge_v.squaredNorm();
  const Eigen::Vector2d ab = gram.ldlt().solve(Eigen::Vector2d(d.dot(q.edge_u), d.dot(q.edge_v)));
  const Vector3d nearest = q.origin + std::clamp(ab.x(), 0.0, 1.0) * q.edge_u + std::clamp(ab.y(), 0.0, 1.0) * q.edge_v;
  return (p - nearest).norm();
}

void extend(Vector3d& lo, Vector3d& hi, const Vector3d& p) {
  lo = lo.cwiseMin(p);
  hi = hi.cwiseMax(p);
}

}  // namespace

void SweptVolumeOptions::check() const {
  core::require(cell >= 0.001 && cell <= 1.0, "swept volume: cell must be in [0.001, 1] m");
  core::require(open_margin >= 0 && open_margin <= 1.0, "swept volume: open_margin must be in [0, 1] m");
  core::require(max_step > 0 && max_step <= 1.0, "swept volume: max_step must be in (0, 1] m");
  core::require(max_substeps >= 1 && max_substeps <= 10000, "swept volume: max_substeps must be in [1, 10000]");
}

SweptVolume::SweptVolume(double cell) : cell_(cell) {
  core::require(cell > 0 && std::isfinite(cell), "swept volume: the cell size must be positive");
}

std::uint64_t SweptVolume::keyOf(long i, long j, long k) const {
  const auto part = [](long v) {
    return static_cast<std::uint64_t>(std::clamp(v + kIndexOffset, 0L, 2 * kIndexOffset - 1));
  };
  return part(i) << (2 * kIndexBits) | part(j) << kIndexBits | part(k);
}

template <typename Inside>
void SweptVolume::markBox(const Vector3d& lo, const Vector3d& hi, const Inside& inside) {
  const auto first = [&](double v) { return static_cast<long>(std::floor(v / cell_)); };
  for (long i = first(lo.x()); i <= first(hi.x()); ++i)
    for (long j = first(lo.y()); j <= first(hi.y()); ++j)
      for (long k = first(lo.z()); k <= first(hi.z()); ++k) {
        const Vector3d c((i + 0.5) * cell_, (j + 0.5) * cell_, (k + 0.5) * cell_);
        if (inside(c)) cells_.insert(keyOf(i, j, k));
      }
}

void SweptVolume::mark(const SceneGeometry& g, double open_margin) {
  const double h = cell_ / 2;  // a centre within half a cell of the geometry marks its cell
  const double open = h + open_margin;
  for (const Sphere& s : g.spheres) {
    const double r = s.radius + h;
    markBox((s.centre.array() - r).matrix(), (s.centre.array() + r).matrix(), [&](const Vector3d& c) { return (c - s.centre).norm() <= r; });
  }
  for (const Cylinder& cyl : g.cylinders) {
    const double grow = cyl.capped ? h : open;
    const Vector3d tip = cyl.base + cyl.length * cyl.axis;
    const double r = cyl.radius + grow;
    markBox((cyl.base.cwiseMin(tip).array() - r).matrix(), (cyl.base.cwiseMax(tip).array() + r).matrix(), [&](const Vector3d& c) {
      const Vector3d d = c - cyl.base;
      const double s = d.dot(cyl.axis), radial = (d - s * cyl.axis).norm();
      const double along = std::max({0.0, -s, s - cyl.length});
      if (cyl.capped) {  // distance to the solid
        const double out = std::max(0.0, radial - cyl.radius);
        return out * out + along * along <= h * h;
      }
      const double side = radial - cyl.radius;  // distance to the tube's wall
      return side * side + along * along <= open * open;
    });
  }
  const std::vector<Quad>& quads = g.quads;
  for (std::size_t q = 0; q < quads.size();) {
    if (quads[q].cull_back && q + 6 <= quads.size() &&
        std::all_of(quads.begin() + q, quads.begin() + q + 6, [](const Quad& f) { return f.cull_back; }) &&
        boundsASolid(quads, q)) {
      Vector3d lo = quads[q].origin, hi = lo;
      std::vector<std::pair<Vector3d, Vector3d>> planes;  // (point, outward unit normal)
      for (std::size_t f = q; f < q + 6; ++f) {
        const Quad& face = quads[f];
        for (const Vector3d& p : {face.origin, Vector3d(face.origin + face.edge_u), Vector3d(face.origin + face.edge_v),
                                  Vector3d(face.origin + face.edge_u + face.edge_v)})
          extend(lo, hi, p);
        planes.emplace_back(face.origin, face.edge_v.cross(face.edge_u).normalized());
      }
      markBox((lo.array() - h).matrix(), (hi.array() + h).matrix(), [&](const Vector3d& c) {
        for (const auto& [point, normal] : planes)
          if ((c - point).dot(normal) > h) return false;
        return true;
      });
      q += 6;
      continue;
    }
    const Quad& face = quads[q];  // an open surface
    Vector3d lo = face.origin, hi = lo;
    extend(lo, hi, face.origin + face.edge_u);
    extend(lo, hi, face.origin + face.edge_v);
    extend(lo, hi, face.origin + face.edge_u + face.edge_v);
    markBox((lo.array() - open).matrix(), (hi.array() + open).matrix(), [&](const Vector3d& c) { return distanceToQuad(face, c) <= open; });
    ++q;
  }
}

void SweptVolume::markPoint(const Vector3d& p) {
  cells_.insert(keyOf(static_cast<long>(std::floor(p.x() / cell_)), static_cast<long>(std::floor(p.y() / cell_)),
                      static_cast<long>(std::floor(p.z() / cell_))));
}

bool SweptVolume::containsPoint(const Vector3d& p) const {
  return marked(static_cast<long>(std::floor(p.x() / cell_)), static_cast<long>(std::floor(p.y() / cell_)),
                static_cast<long>(std::floor(p.z() / cell_)));
}

double SweptVolume::distanceTo(const Vector3d& p, double max_distance) const {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  if (cells_.empty()) return kNone;
  const long i0 = static_cast<long>(std::floor(p.x() / cell_)), j0 = static_cast<long>(std::floor(p.y() / cell_)),
             k0 = static_cast<long>(std::floor(p.z() / cell_));
  if (marked(i0, j0, k0)) return 0;
  const long r = static_cast<long>(std::ceil(std::max(0.0, max_distance) / cell_));
  double best = kNone;
  for (long i = i0 - r; i <= i0 + r; ++i)
    for (long j = j0 - r; j <= j0 + r; ++j)
      for (long k = k0 - r; k <= k0 + r; ++k) {
        if (!marked(i, j, k)) continue;
        const Vector3d lo(i * cell_, j * cell_, k * cell_), hi = lo + Vector3d::Constant(cell_);
        const Vector3d out = (lo - p).cwiseMax(p - hi).cwiseMax(Vector3d::Zero());
        best = std::min(best, out.norm());
      }
  return best <= max_distance ? best : kNone;
}

std::vector<Eigen::Vector3f> SweptVolume::centres() const {
  std::vector<std::uint64_t> keys(cells_.begin(), cells_.end());
  std::sort(keys.begin(), keys.end());
  std::vector<Eigen::Vector3f> out;
  out.reserve(keys.size());
  const std::uint64_t mask = (1ULL << kIndexBits) - 1;
  for (std::uint64_t key : keys) {
    const auto index = [&](int shift) { return static_cast<long>((key >> shift) & mask) - kIndexOffset; };
    out.emplace_back(static_cast<float>((index(2 * kIndexBits) + 0.5) * cell_),
                     static_cast<float>((index(kIndexBits) + 0.5) * cell_), static_cast<float>((index(0) + 0.5) * cell_));
  }
  return out;
}

SweptVolume sweep(const GeometryAt& geometry_at, const std::vector<double>& times, const SweptVolumeOptions& options) {
  options.check();
  SweptVolume volume(options.cell);
  if (times.empty()) return volume;
  SceneGeometry previous = geometry_at(times.front());
  volume.mark(previous, options.open_margin);
  for (std::size_t n = 1; n < times.size(); ++n) {
    const double ta = times[n - 1], tb = times[n];
    SceneGeometry next = geometry_at(tb);
    const double moved = previous.maxDisplacement(next);
    if (moved > 0) {  // geometry at rest marks what it marked already
      const int steps = std::isfinite(moved) ? std::clamp(static_cast<int>(std::ceil(moved / options.max_step)), 1,
                                                          options.max_substeps)
                                             : options.max_substeps;
      for (int s = 1; s < steps; ++s) volume.mark(geometry_at(ta + (tb - ta) * s / steps), options.open_margin);
      volume.mark(next, options.open_margin);
    }
    previous = std::move(next);
  }
  return volume;
}

SweptVolume sweptVolumeOf(const SequenceGenerator& generator, const SweptVolumeOptions& options) {
  const int frames = generator.frameCount();
  if (frames <= 0) return SweptVolume(options.cell);
  // The depth image is taken at t + depth_time_offset_s, a rolling-shutter colour image's rows around t: cover both.
  const SensorOptions& sensor = generator.options().sensor;
  const double before = std::min(0.0, sensor.depth_time_offset_s) - sensor.rolling_shutter_s / 2;
  const double after = std::max(0.0, sensor.depth_time_offset_s) + sensor.rolling_shutter_s / 2;
  std::vector<double> times;
  if (before < 0) times.push_back(generator.time(0) + before);
  for (int k = 0; k < frames; ++k) times.push_back(generator.time(k));
  if (after > 0) times.push_back(generator.time(frames - 1) + after);
  const double fps = sensor.fps;
  const auto geometry_at = [&](double t) {
    const int nearest = std::clamp(static_cast<int>(std::lround(t * fps)), 0, frames - 1);
    return generator.moverGeometry(t, generator.poseWc(nearest).translation());
  };
  return sweep(geometry_at, times, options);
}

void writeSweptVolumePly(const std::string& path, const SweptVolume& volume) {
  const std::vector<Eigen::Vector3f> centres = volume.centres();
  std::ofstream out(path, std::ios::binary);
  core::require(out.good(), fmt::format("cannot write {}", path));
  out << "ply\nformat binary_little_endian 1.0\n"
      << "comment amos-slam synth: cells the movers swept, centres (ground truth frame)\n"
      << kCellComment << fmt::format("{:.17g}", volume.cell()) << "\n"
      << "element vertex " << centres.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "end_header\n";
  for (const Eigen::Vector3f& c : centres) out.write(reinterpret_cast<const char*>(c.data()), 3 * sizeof(float));
  core::require(out.good(), fmt::format("cannot write {}", path));
}

SweptVolume readSweptVolumePly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  core::require(in.good(), fmt::format("{}: cannot be read", path));
  std::string line, header;
  std::size_t count = 0;
  double cell = 0;
  while (std::getline(in, line)) {
    header += line + "\n";
    if (line.rfind("element vertex ", 0) == 0) count = std::stoul(line.substr(15));
    if (line.rfind(kCellComment, 0) == 0) std::istringstream(line.substr(std::string(kCellComment).size())) >> cell;
    if (line == "end_header") break;
  }
  core::require(header.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0 &&
                    header.find("property float x\nproperty float y\nproperty float z\nend_header\n") !=
                        std::string::npos &&
                    cell > 0,
                fmt::format("{}: not a swept volume file (binary PLY of x y z floats with a '{}<metres>' line)", path,
                            kCellComment));
  SweptVolume volume(cell);
  for (std::size_t n = 0; n < count; ++n) {
    float c[3];
    in.read(reinterpret_cast<char*>(c), sizeof(c));
    core::require(in.good(), fmt::format("{}: truncated ({} cells announced)", path, count));
    volume.markPoint(Vector3d(c[0], c[1], c[2]));
  }
  return volume;
}

}  // namespace amos::synth
