#include "amos/synth/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "amos/core/error.h"

namespace amos::synth {

void RenderOptions::check() const {
  core::require(near_m > 0 && near_m < 1, "synth.render.near_m must be in (0, 1) metres");
}

namespace {

using Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Kind { kQuad, kCylinder, kSphere };

// A primitive moved into the camera frame, with what its per-pixel tests need precomputed.
struct Prepared {
  Kind kind = Kind::kQuad;
  const Surface* surface = nullptr;
  std::uint16_t instance = 0;
  Vector3d o = Vector3d::Zero();  // quad origin / cylinder base / sphere centre
  Vector3d n = Vector3d::Zero();  // quad unit normal / cylinder axis / sphere up
  Vector3d du = Vector3d::Zero(),
           dv =
               Vector3d::Zero();  // quad: dual basis (a = (p - o) . du); cylinder and sphere: front and side directions
  double n_dot_o = 0, du_dot_o = 0, dv_dot_o = 0;
  double radius = 0, length = 0;
  bool capped = false;
  double texels_per_m = 0;  // geometric mean over the two texture axes, for the mip level
  std::array<Vector3d, 4> corners{Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero(),
                                  Vector3d::Zero()};  // quads only
};

double texelsPerMetre(const Surface& s, const TextureBank& textures, double metres_u, double metres_v) {
  if (s.texture < 0) return 0;
  const Texture& tex = textures[s.texture];
  const double tu = tex.width() * s.repeat_u / std::max(metres_u, 1e-9);
  const double tv = tex.height() * s.repeat_v / std::max(metres_v, 1e-9);
  return std::sqrt(tu * tv);
}

// Nearest intersection of the ray t * d (t > near) with a prepared cylinder; +inf if none.
double hitCylinder(const Prepared& p, const Vector3d& d, double near) {
  const double dd = d.dot(p.n);
  const double wa = -p.o.dot(p.n);
  const Vector3d dp = d - dd * p.n;
  const Vector3d wp = -p.o - wa * p.n;
  double best = kInf;
  const double A = dp.squaredNorm();
  if (A > 1e-14) {
    const double B = 2 * dp.dot(wp), C = wp.squaredNorm() - p.radius * p.radius;
    const double disc = B * B - 4 * A * C;
    if (disc >= 0) {
      const double sq = std::sqrt(disc);
      const double roots[2] = {(-B - sq) / (2 * A), (-B + sq) / (2 * A)};
      for (int i = 0; i < 2; ++i) {
        const double t = roots[i];
        if (t <= near) continue;
        const double h = t * dd + wa;
        if (h >= 0 && h <= p.length) {
          best = t;
          break;
        }
        if (p.capped) break;  // a closed cylinder's far wall is hidden behind a cap
      }
    }
  }
  if (p.capped && std::abs(dd) > 1e-12) {
    for (double h0 : {0.0, p.length}) {
      const double t = (h0 - wa) / dd;
      if (t <= near || t >= best) continue;
      const Vector3d q = t * d - p.o - h0 * p.n;
      if (q.squaredNorm() <= p.radius * p.radius) best = t;
    }
  }
  return best;
}

double hitSphere(const Prepared& p, const Vector3d& d, double near) {
  const double A = d.squaredNorm(), B = -2 * d.dot(p.o), C = p.o.squaredNorm() - p.radius * p.radius;
  const double disc = B * B - 4 * A * C;
  if (disc < 0) return kInf;
  const double sq = std::sqrt(disc);
  const double t1 = (-B - sq) / (2 * A);
  if (t1 > near) return t1;
  const double t2 = (-B + sq) / (2 * A);
  return t2 > near ? t2 : kInf;
}

// log2 to about 0.01, enough to pick a mip level: exponent bits plus a quadratic in the mantissa.
inline float fastLog2(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const float exponent = static_cast<float>(static_cast<int>((bits >> 23) & 0xff) - 128);  // the polynomial adds 1
  bits = (bits & 0x007fffffu) | 0x3f800000u;                                               // mantissa in [1, 2)
  float m;
  std::memcpy(&m, &bits, sizeof m);
  return exponent + (-0.34484843f * m + 2.02466578f) * m - 0.67487759f;
}

// Polygon of a quad clipped to z >= near (Sutherland-Hodgman against one plane).
std::vector<Vector3d> clipNear(const std::vector<Vector3d>& poly, double near) {
  std::vector<Vector3d> out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vector3d& a = poly[i];
    const Vector3d& b = poly[(i + 1) % poly.size()];
    const bool ain = a.z() >= near, bin = b.z() >= near;
    if (ain) out.push_back(a);
    if (ain != bin) out.push_back(a + (b - a) * ((near - a.z()) / (b.z() - a.z())));
  }
  return out;
}

}  // namespace

Renderer::Renderer(const core::CameraIntrinsics& intrinsics, const RenderOptions& options)
    : intr_(intrinsics), options_(options) {
  intr_.check();
  options_.check();
  core::require(!intr_.hasDistortion(), "synth renderer: the synthetic camera has no lens distortion");
  ray_x_.resize(static_cast<std::size_t>(intr_.width));
  ray_y_.resize(static_cast<std::size_t>(intr_.height));
  for (int x = 0; x < intr_.width; ++x) ray_x_[static_cast<std::size_t>(x)] = (x - intr_.cx) / intr_.fx;
  for (int y = 0; y < intr_.height; ++y) ray_y_[static_cast<std::size_t>(y)] = (y - intr_.cy) / intr_.fy;
}

RenderedImage Renderer::render(const std::vector<const SceneGeometry*>& parts, const TextureBank& textures,
                               const Lighting& lighting, const core::SE3& T_cw, bool with_color,
                               const RowBand& band) const {
  const int W = intr_.width;
  const int row0 = band.begin, row1 = band.end < 0 ? intr_.height : band.end;  // rows [row0, row1)
  core::require(row0 >= 0 && row0 < row1 && row1 <= intr_.height, "synth renderer: row band outside the image");
  const int H = row1 - row0;  // rows rendered; buffers and outputs are indexed by y - row0
  const double near = options_.near_m;
  const Eigen::Matrix3d R = T_cw.linear();

  // 1. Primitives in the camera frame.
  std::vector<Prepared> prims;
  for (const SceneGeometry* part : parts) {
    for (const Quad& q : part->quads) {
      Prepared p;
      p.kind = Kind::kQuad;
      p.surface = &q.surface;
      p.instance = q.instance;
      p.o = T_cw * q.origin;
      const Vector3d eu = R * q.edge_u, ev = R * q.edge_v;
      const Vector3d normal = ev.cross(eu);
      if (normal.norm() < 1e-12) continue;
      p.n = normal.normalized();
      p.n_dot_o = p.n.dot(p.o);
      // Seen from behind (camera on the back side of the plane): p.n . (camera - o) = -n_dot_o < 0.
      if (q.cull_back && p.n_dot_o >= 0) continue;
      const double guu = eu.dot(eu), guv = eu.dot(ev), gvv = ev.dot(ev);
      const double det = guu * gvv - guv * guv;
      p.du = (gvv * eu - guv * ev) / det;
      p.dv = (guu * ev - guv * eu) / det;
      p.du_dot_o = p.du.dot(p.o);
      p.dv_dot_o = p.dv.dot(p.o);
      p.texels_per_m = texelsPerMetre(q.surface, textures, std::sqrt(guu), std::sqrt(gvv));
      p.corners = {p.o, p.o + eu, p.o + eu + ev, p.o + ev};
      prims.push_back(p);
    }
    for (const Cylinder& c : part->cylinders) {
      Prepared p;
      p.kind = Kind::kCylinder;
      p.surface = &c.surface;
      p.instance = c.instance;
      p.o = T_cw * c.base;
      p.n = R * c.axis;
      p.du = R * c.front;
      p.dv = p.n.cross(p.du);
      p.radius = c.radius;
      p.length = c.length;
      p.capped = c.capped;
      p.texels_per_m = texelsPerMetre(c.surface, textures, 2 * M_PI * c.radius, c.length);
      prims.push_back(p);
    }
    for (const Sphere& s : part->spheres) {
      Prepared p;
      p.kind = Kind::kSphere;
      p.surface = &s.surface;
      p.instance = s.instance;
      p.o = T_cw * s.centre;
      p.n = R * s.up;
      p.du = R * s.front;
      p.dv = p.n.cross(p.du);
      p.radius = s.radius;
      p.texels_per_m = texelsPerMetre(s.surface, textures, 2 * M_PI * s.radius, M_PI * s.radius);
      prims.push_back(p);
    }
  }

  // 2. Visibility: z-buffer of the nearest hit and which primitive it belongs to.
  const std::size_t npix = static_cast<std::size_t>(W) * H;
  std::vector<float> zbuf(npix, std::numeric_limits<float>::infinity());
  std::vector<int> idbuf(npix, -1);

  for (int id = 0; id < static_cast<int>(prims.size()); ++id) {
    const Prepared& p = prims[static_cast<std::size_t>(id)];
    if (p.kind == Kind::kQuad) {
      const std::vector<Vector3d> poly = clipNear({p.corners[0], p.corners[1], p.corners[2], p.corners[3]}, near);
      if (poly.size() < 3) continue;
      std::vector<double> pu(poly.size()), pv(poly.size());
      double vmin = kInf, vmax = -kInf;
      for (std::size_t i = 0; i < poly.size(); ++i) {
        pu[i] = intr_.fx * poly[i].x() / poly[i].z() + intr_.cx;
        pv[i] = intr_.fy * poly[i].y() / poly[i].z() + intr_.cy;
        vmin = std::min(vmin, pv[i]);
        vmax = std::max(vmax, pv[i]);
      }
      const int y0 = std::max(row0, static_cast<int>(std::floor(vmin)) - 1);
      const int y1 = std::min(row1 - 1, static_cast<int>(std::ceil(vmax)) + 1);
      const Texture* alpha_tex =
          p.surface->alpha_test && p.surface->texture >= 0 ? &textures[p.surface->texture] : nullptr;
      for (int y = y0; y <= y1; ++y) {
        // Conservative span: the polygon's x-extent over the band [y - 1, y + 1]; the exact test decides.
        double xl = kInf, xr = -kInf;
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const std::size_t j = (i + 1) % poly.size();
          const double va = std::min(pv[i], pv[j]), vb = std::max(pv[i], pv[j]);
          if (vb < y - 1 || va > y + 1) continue;
          if (vb - va < 1e-12) {  // horizontal edge: both end points
            xl = std::min({xl, pu[i], pu[j]});
            xr = std::max({xr, pu[i], pu[j]});
            continue;
          }
          for (double v : {std::max(va, y - 1.0), std::min(vb, y + 1.0)}) {
            const double u = pu[i] + (v - pv[i]) / (pv[j] - pv[i]) * (pu[j] - pu[i]);
            xl = std::min(xl, u);
            xr = std::max(xr, u);
          }
        }
        if (!(xl <= xr)) continue;
        const int x0 = std::max(0, static_cast<int>(std::floor(xl)) - 1);
        const int x1 = std::min(W - 1, static_cast<int>(std::ceil(xr)) + 1);
        const double ry = ray_y_[static_cast<std::size_t>(y)];
        const double ny = p.n.y() * ry + p.n.z(), uy = p.du.y() * ry + p.du.z(), vy = p.dv.y() * ry + p.dv.z();
        float* zrow = zbuf.data() + static_cast<std::size_t>(y - row0) * W;
        int* idrow = idbuf.data() + static_cast<std::size_t>(y - row0) * W;
        for (int x = x0; x <= x1; ++x) {
          const double rx = ray_x_[static_cast<std::size_t>(x)];
          const double denom = p.n.x() * rx + ny;
          if (std::abs(denom) < 1e-12) continue;
          const double t = p.n_dot_o / denom;
          if (t <= near || t >= zrow[x]) continue;
          const double a = t * (p.du.x() * rx + uy) - p.du_dot_o;
          if (a < -1e-9 || a > 1 + 1e-9) continue;
          const double b = t * (p.dv.x() * rx + vy) - p.dv_dot_o;
          if (b < -1e-9 || b > 1 + 1e-9) continue;
          if (alpha_tex && alpha_tex->alpha(a * p.surface->repeat_u, b * p.surface->repeat_v) < 0.5f) continue;
          zrow[x] = static_cast<float>(t);
          idrow[x] = id;
        }
      }
      continue;
    }

    // Cylinders and spheres: the screen rectangle of their bounding box, then exact ray tests.
    std::vector<Vector3d> box;
    if (p.kind == Kind::kCylinder) {
      for (double h : {0.0, p.length})
        for (double sf : {-1.0, 1.0})
          for (double ss : {-1.0, 1.0}) box.push_back(p.o + h * p.n + p.radius * (sf * p.du + ss * p.dv));
    } else {
      for (double a : {-1.0, 1.0})
        for (double b : {-1.0, 1.0})
          for (double c : {-1.0, 1.0}) box.push_back(p.o + p.radius * Vector3d(a, b, c));
    }
    int x0 = 0, x1 = W - 1, y0 = row0, y1 = row1 - 1;
    bool any_in_front = false, all_in_front = true;
    for (const Vector3d& c : box) {
      any_in_front |= c.z() > near;
      all_in_front &= c.z() > near;
    }
    if (!any_in_front) continue;
    if (all_in_front) {
      double umin = kInf, umax = -kInf, vmin = kInf, vmax = -kInf;
      for (const Vector3d& c : box) {
        const double u = intr_.fx * c.x() / c.z() + intr_.cx, v = intr_.fy * c.y() / c.z() + intr_.cy;
        umin = std::min(umin, u);
        umax = std::max(umax, u);
        vmin = std::min(vmin, v);
        vmax = std::max(vmax, v);
      }
      x0 = std::max(0, static_cast<int>(std::floor(umin)) - 1);
      x1 = std::min(W - 1, static_cast<int>(std::ceil(umax)) + 1);
      y0 = std::max(row0, static_cast<int>(std::floor(vmin)) - 1);
      y1 = std::min(row1 - 1, static_cast<int>(std::ceil(vmax)) + 1);
    }
    for (int y = y0; y <= y1; ++y) {
      float* zrow = zbuf.data() + static_cast<std::size_t>(y - row0) * W;
      int* idrow = idbuf.data() + static_cast<std::size_t>(y - row0) * W;
      for (int x = x0; x <= x1; ++x) {
        const Vector3d d(ray_x_[static_cast<std::size_t>(x)], ray_y_[static_cast<std::size_t>(y)], 1.0);
        const double t = p.kind == Kind::kCylinder ? hitCylinder(p, d, near) : hitSphere(p, d, near);
        if (t < zrow[x]) {
          zrow[x] = static_cast<float>(t);
          idrow[x] = id;
        }
      }
    }
  }

  // 3. Outputs; deferred shading of the one visible primitive per pixel.
  RenderedImage out;
  out.depth = cv::Mat(H, W, CV_32F, cv::Scalar(0));
  out.instance = cv::Mat(H, W, CV_16U, cv::Scalar(0));
  out.incidence = cv::Mat(H, W, CV_32F, cv::Scalar(0));
  if (with_color) out.color = cv::Mat(H, W, CV_32FC3, cv::Scalar::all(0));
  struct LightTerm {
    float x, y, z, intensity, inv_falloff2;
  };
  std::vector<LightTerm> light_terms;
  for (const PointLight& l : lighting.lights) {
    const Vector3d p = T_cw * l.position_w;
    light_terms.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()),
                           static_cast<float>(l.intensity), static_cast<float>(1.0 / (l.falloff_m * l.falloff_m))});
  }
  const double f_mean = std::sqrt(intr_.fx * intr_.fy);

  for (int y = row0; y < row1; ++y) {
    float* zrow = out.depth.ptr<float>(y - row0);
    std::uint16_t* irow = out.instance.ptr<std::uint16_t>(y - row0);
    float* crow = out.incidence.ptr<float>(y - row0);
    cv::Vec3f* colrow = with_color ? out.color.ptr<cv::Vec3f>(y - row0) : nullptr;
    for (int x = 0; x < W; ++x) {
      const std::size_t k = static_cast<std::size_t>(y - row0) * W + x;
      const int id = idbuf[k];
      if (id < 0) continue;
      const Prepared& p = prims[static_cast<std::size_t>(id)];
      const double z = zbuf[k];
      const Vector3d d(ray_x_[static_cast<std::size_t>(x)], ray_y_[static_cast<std::size_t>(y)], 1.0);
      const Vector3d hit = z * d;
      Vector3d normal = Vector3d::UnitZ();
      double s = 0, t = 0;
      switch (p.kind) {
        case Kind::kQuad:
          normal = p.n;
          s = z * p.du.dot(d) - p.du_dot_o;
          t = z * p.dv.dot(d) - p.dv_dot_o;
          break;
        case Kind::kCylinder: {
          const Vector3d q = hit - p.o;
          const double h = q.dot(p.n);
          const Vector3d radial = q - h * p.n;
          const bool cap = radial.squaredNorm() < 0.998 * p.radius * p.radius &&
                           (h < 1e-6 * (1 + p.length) || h > p.length * (1 - 1e-6) - 1e-9);
          normal = cap ? (h < p.length / 2 ? Vector3d(-p.n) : p.n) : radial.normalized();
          s = 0.5 + std::atan2(radial.dot(p.dv), radial.dot(p.du)) / (2 * M_PI);
          t = std::clamp((p.length - h) / p.length, 0.0, 1.0);
          break;
        }
        case Kind::kSphere: {
          normal = (hit - p.o) / p.radius;
          s = 0.5 + std::atan2(normal.dot(p.dv), normal.dot(p.du)) / (2 * M_PI);
          t = std::acos(std::clamp(normal.dot(p.n), -1.0, 1.0)) / M_PI;
          break;
        }
      }
      if (normal.dot(d) > 0) normal = -normal;  // two-sided: light the side facing the camera
      const double cos_inc = std::abs(normal.dot(d)) / d.norm();
      zrow[x] = static_cast<float>(z);
      irow[x] = p.instance;
      crow[x] = static_cast<float>(cos_inc);
      if (!with_color) continue;

      const Surface& surf = *p.surface;
      cv::Vec3f albedo(180, 180, 180);
      if (surf.texture >= 0) {
        const double footprint_m = z / f_mean / std::sqrt(std::max(cos_inc, 0.02));
        const double lod = fastLog2(static_cast<float>(std::max(p.texels_per_m * footprint_m, 1e-6)));
        albedo = textures[surf.texture].sample(s * surf.repeat_u, t * surf.repeat_v, lod);
      }
      // Lambert with a soft inverse-square falloff: intensity * cos / (1 + (d / falloff)^2), in float with one
      // square root and one division per light (this loop was half of the shading time).
      float irradiance = static_cast<float>(lighting.ambient);
      const float hx = static_cast<float>(hit.x()), hy = static_cast<float>(hit.y()), hz = static_cast<float>(hit.z());
      const float nx = static_cast<float>(normal.x()), ny = static_cast<float>(normal.y()),
                  nz = static_cast<float>(normal.z());
      for (const LightTerm& l : light_terms) {
        const float lx = l.x - hx, ly = l.y - hy, lz = l.z - hz;
        const float n_dot_l = nx * lx + ny * ly + nz * lz;
        if (n_dot_l <= 0) continue;
        const float d2 = lx * lx + ly * ly + lz * lz;
        irradiance += l.intensity * n_dot_l / (std::sqrt(d2) * (1 + d2 * l.inv_falloff2));
      }
      const float g = irradiance;
      colrow[x] = cv::Vec3f(albedo[0] * surf.tint[0] * g, albedo[1] * surf.tint[1] * g, albedo[2] * surf.tint[2] * g);
    }
  }
  return out;
}

}  // namespace amos::synth
