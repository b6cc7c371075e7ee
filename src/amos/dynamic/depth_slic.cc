#include "amos/dynamic/depth_slic.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <utility>
#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

#if defined(__GNUC__) && defined(__x86_64__) && CV_SIMD128 && !CV_SIMD256
#include <immintrin.h>
// The assignment loop in 8 lanes on CPUs that have AVX2, chosen at run time: the library itself is built for the
// x86-64 baseline (4 lanes), as distribution packages are.
#define AMOS_SLIC_AVX2 1
#else
#define AMOS_SLIC_AVX2 0
#endif

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::dynamic {

void DepthSlicOptions::check() const {
  core::requireOption(num_superpixels >= 4, core::option(num_superpixels, "num_superpixels"),
                      fmt::format("must be at least 4, got {}", num_superpixels));
  core::requireOption(std::isfinite(scale) && scale > 0 && scale <= 1, core::option(scale, "scale"),
                      fmt::format("must lie in (0, 1], got {}", scale));
  core::requirePositive(colour_scale, "colour_scale");
  core::requirePositive(depth_scale_m, "depth_scale_m");
  core::requireAtLeast(iterations, "iterations", 1);
}

namespace {

// Working-resolution image planes, one float per pixel, so the assignment loop reads contiguous rows.
struct Planes {
  int width = 0, height = 0;
  cv::Mat L, A, B;  // CIELAB, CV_32F
  cv::Mat Z;        // depth [m], 0 where invalid, CV_32F
  cv::Mat valid;    // 1 where Z is valid, else 0, CV_32F (a multiplier that switches the depth term off)
};

struct Centre {
  float x = 0, y = 0, L = 0, A = 0, B = 0;
  float z = 0;
  float z_weight = 0;  // 1 when the centre has a valid mean depth, else 0
};

Planes makePlanes(const cv::Mat& bgr, const cv::Mat& depth, double scale) {
  Planes p;
  p.width = std::max(1, static_cast<int>(std::lround(bgr.cols * scale)));
  p.height = std::max(1, static_cast<int>(std::lround(bgr.rows * scale)));
  const cv::Size size(p.width, p.height);
  cv::Mat small_bgr, small_depth;
  if (size == bgr.size()) {
    small_bgr = bgr;
    small_depth = depth;
  } else {
    cv::resize(bgr, small_bgr, size, 0, 0, cv::INTER_AREA);
    // Nearest neighbour: averaging would blend foreground and background depths at edges and mix in zeros.
    // For an integer factor f that is every f-th pixel of every f-th row (what cv::resize's nearest neighbour
    // picks too, floor(x * f)), taken directly: OpenCV's general path costs twice the colour resize.
    if (const int f = integerFactor(depth.size(), size); f > 0) {
      small_depth.create(size, CV_32F);
      for (int y = 0; y < p.height; ++y) {
        const float* in = depth.ptr<float>(f * y);
        float* out = small_depth.ptr<float>(y);
        for (int x = 0; x < p.width; ++x) out[x] = in[f * x];
      }
    } else {
      cv::resize(depth, small_depth, size, 0, 0, cv::INTER_NEAREST);
    }
  }
  // The 8-bit conversion runs on lookup tables (several times faster than the float path) and its 1/255
  // quantisation is far below SLIC's colour scale. Undo its packing: L8 = L * 255 / 100, a8 = a + 128.
  cv::Mat lab8;
  cv::cvtColor(small_bgr, lab8, cv::COLOR_BGR2Lab);
  p.L.create(size, CV_32F), p.A.create(size, CV_32F), p.B.create(size, CV_32F);
  p.Z.create(size, CV_32F);
  p.valid.create(size, CV_32F);
  constexpr float kL8ToL = static_cast<float>(100.0 / 255.0);
  for (int y = 0; y < p.height; ++y) {
    const std::uint8_t* lab = lab8.ptr<std::uint8_t>(y);
    float *L = p.L.ptr<float>(y), *A = p.A.ptr<float>(y), *B = p.B.ptr<float>(y);
    for (int x = 0; x < p.width; ++x) {
      L[x] = static_cast<float>(lab[3 * x]) * kL8ToL;
      A[x] = static_cast<float>(lab[3 * x + 1]) - 128.f;
      B[x] = static_cast<float>(lab[3 * x + 2]) - 128.f;
    }
    const float* d = small_depth.ptr<float>(y);
    float* z = p.Z.ptr<float>(y);
    float* v = p.valid.ptr<float>(y);
    for (int x = 0; x < p.width; ++x) {
      const bool ok = std::isfinite(d[x]) && d[x] > 0.f;
      z[x] = ok ? d[x] : 0.f;
      v[x] = ok ? 1.f : 0.f;
    }
  }
  return p;
}

// Seeds on a regular grid, each moved to the lowest colour-gradient pixel of its 3x3 neighbourhood (as in
// SLIC) so that no seed starts on an edge.
std::vector<Centre> seedCentres(const Planes& p, int num_superpixels, float& step) {
  step = std::sqrt(static_cast<float>(p.width) * p.height / num_superpixels);
  const int nx = std::max(1, static_cast<int>(std::lround(p.width / step)));
  const int ny = std::max(1, static_cast<int>(std::lround(p.height / step)));
  const float sx = static_cast<float>(p.width) / nx, sy = static_cast<float>(p.height) / ny;
  auto gradient = [&](int x, int y) {
    if (x < 1 || y < 1 || x >= p.width - 1 || y >= p.height - 1) return std::numeric_limits<float>::max();
    auto diff2 = [&](int xa, int ya, int xb, int yb) {
      const float dl = p.L.at<float>(ya, xa) - p.L.at<float>(yb, xb);
      const float da = p.A.at<float>(ya, xa) - p.A.at<float>(yb, xb);
      const float db = p.B.at<float>(ya, xa) - p.B.at<float>(yb, xb);
      return dl * dl + da * da + db * db;
    };
    return diff2(x + 1, y, x - 1, y) + diff2(x, y + 1, x, y - 1);
  };
  std::vector<Centre> centres;
  centres.reserve(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      int bx = std::min(p.width - 1, static_cast<int>((i + 0.5f) * sx));
      int by = std::min(p.height - 1, static_cast<int>((j + 0.5f) * sy));
      float best = gradient(bx, by);
      const int cx = bx, cy = by;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const float g = gradient(cx + dx, cy + dy);
          if (g < best) best = g, bx = cx + dx, by = cy + dy;
        }
      Centre c;
      c.x = static_cast<float>(bx);
      c.y = static_cast<float>(by);
      c.L = p.L.at<float>(by, bx);
      c.A = p.A.at<float>(by, bx);
      c.B = p.B.at<float>(by, bx);
      c.z = p.Z.at<float>(by, bx);
      c.z_weight = p.valid.at<float>(by, bx);
      centres.push_back(c);
    }
  }
  return centres;
}

#if AMOS_SLIC_AVX2
// Pixels [x, x1) of one row of a centre's window, 8 at a time, for as long as 8 remain; returns where it stopped.
// Operation by operation the arithmetic of the 4-lane loop in assignPixels (no FMA: fused operations would round
// differently), and `dx4` carries that loop's running x offsets in and out (lanes 0-3 here hold its chunk, lanes
// 4-7 its next one), so both paths give the same labels bit for bit.
// One row of a centre's window as assignRowAvx2 reads it: the working planes' row, the distance and label rows it
// updates, where the row ends, and the centre's terms of Eq. 1.
struct AssignRow {
  const float* L;
  const float* A;
  const float* B;
  const float* Z;
  const float* V;
  float* dist;
  int* lab;
  int x1;
  const Centre& c;
  float dy2, inv_colour, inv_step, depth_w;
  int k;
};

__attribute__((target("avx2"))) int assignRowAvx2(const AssignRow& row, int x, __m128& dx4) {
  const float *L = row.L, *A = row.A, *B = row.B, *Z = row.Z, *V = row.V;
  float* dist = row.dist;
  int* lab = row.lab;
  const int x1 = row.x1;
  const Centre& c = row.c;
  const float dy2 = row.dy2, inv_colour = row.inv_colour, inv_step = row.inv_step, depth_w = row.depth_w;
  const int k = row.k;
  const __m128 four = _mm_set1_ps(4.f);
  __m256 dx = _mm256_set_m128(_mm_add_ps(dx4, four), dx4);
  const __m256 v_four = _mm256_set1_ps(4.f), v_cl = _mm256_set1_ps(c.L), v_ca = _mm256_set1_ps(c.A),
               v_cb = _mm256_set1_ps(c.B), v_cz = _mm256_set1_ps(c.z), v_dy2 = _mm256_set1_ps(dy2),
               v_ic = _mm256_set1_ps(inv_colour), v_is = _mm256_set1_ps(inv_step), v_dw = _mm256_set1_ps(depth_w),
               abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const __m256 v_k = _mm256_castsi256_ps(_mm256_set1_epi32(k));
  for (; x + 8 <= x1; x += 8) {
    const __m256 dl = _mm256_sub_ps(_mm256_loadu_ps(L + x), v_cl), da = _mm256_sub_ps(_mm256_loadu_ps(A + x), v_ca),
                 db = _mm256_sub_ps(_mm256_loadu_ps(B + x), v_cb);
    const __m256 d_colour = _mm256_sqrt_ps(
        _mm256_add_ps(_mm256_mul_ps(dl, dl), _mm256_add_ps(_mm256_mul_ps(da, da), _mm256_mul_ps(db, db))));
    const __m256 d_image = _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), v_dy2));
    const __m256 d_depth =
        _mm256_mul_ps(_mm256_and_ps(_mm256_sub_ps(_mm256_loadu_ps(Z + x), v_cz), abs_mask), _mm256_loadu_ps(V + x));
    const __m256 D = _mm256_add_ps(_mm256_mul_ps(d_colour, v_ic),
                                   _mm256_add_ps(_mm256_mul_ps(d_image, v_is), _mm256_mul_ps(d_depth, v_dw)));
    const __m256 old = _mm256_loadu_ps(dist + x);
    const __m256 closer = _mm256_cmp_ps(D, old, _CMP_LT_OQ);
    _mm256_storeu_ps(dist + x, _mm256_blendv_ps(old, D, closer));
    const __m256 old_label = _mm256_loadu_ps(reinterpret_cast<const float*>(lab + x));
    _mm256_storeu_ps(reinterpret_cast<float*>(lab + x), _mm256_blendv_ps(old_label, v_k, closer));
    dx = _mm256_add_ps(_mm256_add_ps(dx, v_four), v_four);
  }
  dx4 = _mm256_castps256_ps128(dx);
  return x;
}
#endif

// Eq. 1's scales: the grid step S (the image term's scale and the search window), 1 / colour scale, 1 / depth scale;
// avx2: whether the CPU runs assignRowAvx2.
struct AssignWeights {
  float step, inv_colour, inv_depth;
  bool avx2;
};

// One SLIC assignment pass: every pixel within +-step of a centre takes the nearest centre under Eq. 1.
void assignPixels(const Planes& p, const std::vector<Centre>& centres, const AssignWeights& w, cv::Mat& labels,
                  cv::Mat& distance) {
  const float step = w.step, inv_colour = w.inv_colour, inv_depth = w.inv_depth;
  const bool avx2 = w.avx2;
  (void)avx2;
  distance.setTo(std::numeric_limits<float>::max());
  const float inv_step = 1.f / step;
  const int radius = static_cast<int>(std::ceil(step));
  for (int k = 0; k < static_cast<int>(centres.size()); ++k) {
    const Centre& c = centres[k];
    const int x0 = std::max(0, static_cast<int>(c.x) - radius),
              x1 = std::min(p.width, static_cast<int>(c.x) + radius + 1);
    const int y0 = std::max(0, static_cast<int>(c.y) - radius),
              y1 = std::min(p.height, static_cast<int>(c.y) + radius + 1);
    // The depth weight carries the centre's validity, so the inner loop needs no branch for it.
    const float depth_w = c.z_weight * inv_depth;
    for (int y = y0; y < y1; ++y) {
      const float* L = p.L.ptr<float>(y);
      const float* A = p.A.ptr<float>(y);
      const float* B = p.B.ptr<float>(y);
      const float* Z = p.Z.ptr<float>(y);
      const float* V = p.valid.ptr<float>(y);
      float* dist = distance.ptr<float>(y);
      int* lab = labels.ptr<int>(y);
      const float dy2 = (y - c.y) * (y - c.y);
      int x = x0;
#if CV_SIMD
      // Same arithmetic as the scalar loop below, several pixels at a time.
      {
        constexpr int kLanes = cv::v_float32::nlanes;
        float ramp[kLanes];
        for (int i = 0; i < kLanes; ++i) ramp[i] = static_cast<float>(i);
        const cv::v_float32 v_cl = cv::vx_setall_f32(c.L), v_ca = cv::vx_setall_f32(c.A), v_cb = cv::vx_setall_f32(c.B),
                            v_cz = cv::vx_setall_f32(c.z);
        const cv::v_float32 v_dy2 = cv::vx_setall_f32(dy2), v_ic = cv::vx_setall_f32(inv_colour),
                            v_is = cv::vx_setall_f32(inv_step), v_dw = cv::vx_setall_f32(depth_w),
                            v_lanes = cv::vx_setall_f32(static_cast<float>(kLanes));
        const cv::v_int32 v_k = cv::vx_setall_s32(k);
        cv::v_float32 v_dx = cv::vx_load(ramp) + cv::vx_setall_f32(x0 - c.x);
#if AMOS_SLIC_AVX2
        if (avx2) {
          const AssignRow row{L, A, B, Z, V, dist, lab, x1, c, dy2, inv_colour, inv_step, depth_w, k};
          x = assignRowAvx2(row, x, v_dx.val);
        }
#endif
        for (; x + kLanes <= x1; x += kLanes, v_dx = v_dx + v_lanes) {
          const cv::v_float32 dl = cv::vx_load(L + x) - v_cl, da = cv::vx_load(A + x) - v_ca,
                              db = cv::vx_load(B + x) - v_cb;
          const cv::v_float32 d_colour = cv::v_sqrt(cv::v_fma(dl, dl, cv::v_fma(da, da, db * db)));
          const cv::v_float32 d_image = cv::v_sqrt(cv::v_fma(v_dx, v_dx, v_dy2));
          const cv::v_float32 d_depth = cv::v_abs(cv::vx_load(Z + x) - v_cz) * cv::vx_load(V + x);
          const cv::v_float32 D = cv::v_fma(d_colour, v_ic, cv::v_fma(d_image, v_is, d_depth * v_dw));
          const cv::v_float32 old = cv::vx_load(dist + x);
          const cv::v_float32 closer = D < old;
          cv::v_store(dist + x, cv::v_select(closer, D, old));
          cv::v_store(lab + x, cv::v_select(cv::v_reinterpret_as_s32(closer), v_k, cv::vx_load(lab + x)));
        }
      }
#endif
      for (; x < x1; ++x) {
        const float dl = L[x] - c.L, da = A[x] - c.A, db = B[x] - c.B;
        const float dx = x - c.x;
        const float d_colour = std::sqrt(dl * dl + da * da + db * db);  // Eq. 2
        const float d_image = std::sqrt(dx * dx + dy2);                 // Eq. 3
        // Eq. 4, implemented as |d_i - d_c|: the printed sqrt(d_i^2 + d_c^2) is not a distance (it is not 0
        // for equal depths and grows with the absolute depth, so it would pull every pixel towards the nearest
        // surface instead of separating surfaces at different depths).
        const float d_depth = std::fabs(Z[x] - c.z) * V[x];
        const float D = d_colour * inv_colour + d_image * inv_step + d_depth * depth_w;  // Eq. 1
        if (D < dist[x]) {
          dist[x] = D;
          lab[x] = k;
        }
      }
    }
  }
}

// Per-label sums of the working planes over the pixels labelled >= 0. Positions and a, b (integers in the 8-bit
// Lab conversion) sum exactly in integers; L and depth in double, where sums of these floats are exact too (their
// magnitudes and the ulps of the values span far fewer than 53 bits), so the order of the additions does not
// matter. Each run of one label along a row is summed locally and added to the label's sums once. The centre
// updates and the final superpixel means share this one pass.
struct LabelSum {
  double L = 0, z = 0;
  std::int64_t x = 0, y = 0;
  int A = 0, B = 0;
  int n = 0, nz = 0;
};

std::vector<LabelSum> sumLabels(const Planes& p, const cv::Mat& labels, std::size_t count) {
  std::vector<LabelSum> sums(count);
  for (int y = 0; y < p.height; ++y) {
    const int* lab = labels.ptr<int>(y);
    const float* L = p.L.ptr<float>(y);
    const float* A = p.A.ptr<float>(y);
    const float* B = p.B.ptr<float>(y);
    const float* Z = p.Z.ptr<float>(y);
    const float* V = p.valid.ptr<float>(y);
    for (int x = 0; x < p.width;) {
      const int k = lab[x];
      const int start = x;
      while (x < p.width && lab[x] == k) ++x;
      if (k < 0) continue;
      // The run's pixels in two interleaved sums (exact, as said above, so the grouping does not matter): two
      // chains of dependent additions instead of one. Z is 0 where it is not valid, so adding it there changes
      // nothing, and no branch is needed.
      double l0 = 0, l1 = 0, z0 = 0, z1 = 0;
      int run_a = 0, run_b = 0, run_nz = 0;
      int i = start;
      for (; i + 1 < x; i += 2) {
        l0 += L[i], l1 += L[i + 1], z0 += Z[i], z1 += Z[i + 1];
        run_a += static_cast<int>(A[i]) + static_cast<int>(A[i + 1]);
        run_b += static_cast<int>(B[i]) + static_cast<int>(B[i + 1]);
        run_nz += (V[i] > 0.f) + (V[i + 1] > 0.f);
      }
      if (i < x) {
        l0 += L[i], z0 += Z[i];
        run_a += static_cast<int>(A[i]), run_b += static_cast<int>(B[i]), run_nz += V[i] > 0.f;
      }
      const double run_l = l0 + l1, run_z = z0 + z1;
      const int n = x - start;
      LabelSum& s = sums[k];
      // x's sum over [start, x) = n * (start + x - 1) / 2.
      s.x += static_cast<std::int64_t>(n) * (start + x - 1) / 2;
      s.y += static_cast<std::int64_t>(n) * y;
      s.L += run_l, s.A += run_a, s.B += run_b, s.n += n;
      s.z += run_z, s.nz += run_nz;
    }
  }
  return sums;
}

void updateCentres(const Planes& p, const cv::Mat& labels, std::vector<Centre>& centres) {
  const std::vector<LabelSum> sums = sumLabels(p, labels, centres.size());
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const LabelSum& s = sums[k];
    if (s.n == 0) continue;  // an empty centre keeps its place; it may win pixels back next round
    Centre& c = centres[k];
    c.x = static_cast<float>(static_cast<double>(s.x) / s.n);
    c.y = static_cast<float>(static_cast<double>(s.y) / s.n);
    c.L = static_cast<float>(s.L / s.n);
    c.A = static_cast<float>(static_cast<double>(s.A) / s.n);
    c.B = static_cast<float>(static_cast<double>(s.B) / s.n);
    c.z = s.nz > 0 ? static_cast<float>(s.z / s.nz) : 0.f;
    c.z_weight = s.nz > 0 ? 1.f : 0.f;
  }
}

// SLIC's connectivity post-processing: splits every label into 4-connected components and merges each component
// smaller than min_size into the adjacent component nearest to it under Eq. 1 without the position term (mean
// colour and mean depth). Plain SLIC merges into the component met first in raster order, which on textured
// surfaces glues fragments across depth edges. Relabels consecutively; returns the label count.
int enforceConnectivity(const Planes& p, cv::Mat& labels, int min_size, float inv_colour, float inv_depth) {
  const int w = labels.cols, h = labels.rows;
  cv::Mat comp(labels.size(), CV_32S);
  struct Stats {
    double L = 0, A = 0, B = 0, z = 0;
    int n = 0, nz = 0;
  };
  // 4-connected components as runs of one label along the rows, joined by union-find to the runs of the row above
  // that overlap them with the same label; then numbered in the raster order of their first pixel.
  struct Run {
    int x0, x1, label, node;
  };
  std::vector<Run> runs;
  runs.reserve(static_cast<std::size_t>(h) * 32);
  std::vector<int> row_start(h + 1, 0);
  std::vector<int> run_parent;
  auto run_root = [&](int i) {
    while (run_parent[i] != i) i = run_parent[i] = run_parent[run_parent[i]];
    return i;
  };
  for (int y = 0; y < h; ++y) {
    row_start[y] = static_cast<int>(runs.size());
    const int* row = labels.ptr<int>(y);
    for (int x0 = 0; x0 < w;) {
      int x1 = x0 + 1;
      while (x1 < w && row[x1] == row[x0]) ++x1;
      const int node = static_cast<int>(run_parent.size());
      run_parent.push_back(node);
      runs.push_back({x0, x1, row[x0], node});
      x0 = x1;
    }
  }
  row_start[h] = static_cast<int>(runs.size());
  for (int y = 1; y < h; ++y) {
    int above = row_start[y - 1];
    for (int r = row_start[y]; r < row_start[y + 1]; ++r) {
      const Run& run = runs[r];
      while (above < row_start[y] && runs[above].x1 <= run.x0) ++above;  // runs of the row above ending before
      for (int a = above; a < row_start[y] && runs[a].x0 < run.x1; ++a) {
        if (runs[a].label != run.label) continue;
        const int ra = run_root(runs[a].node), rb = run_root(run.node);
        if (ra != rb) run_parent[std::max(ra, rb)] = std::min(ra, rb);  // the earlier run stays the root
      }
    }
  }
  std::vector<int> id_of_root(run_parent.size(), -1);
  std::vector<Stats> stats;
  for (int y = 0; y < h; ++y) {
    int* out = comp.ptr<int>(y);
    const float *Lp = p.L.ptr<float>(y), *Ap = p.A.ptr<float>(y), *Bp = p.B.ptr<float>(y);
    const float *Zp = p.Z.ptr<float>(y), *Vp = p.valid.ptr<float>(y);
    for (int r = row_start[y]; r < row_start[y + 1]; ++r) {
      const Run& run = runs[r];
      int& id = id_of_root[run_root(run.node)];
      if (id < 0) id = static_cast<int>(stats.size()), stats.emplace_back();
      Stats& st = stats[id];
      std::fill(out + run.x0, out + run.x1, id);
      // The sums in locals, added in the same order as into `st` directly (same result), so that they stay in
      // registers instead of a store and a load per pixel. Z is 0 where not valid, so adding it there changes
      // nothing.
      double sl = st.L, sa = st.A, sb = st.B, sz = st.z;
      int nz = st.nz;
      for (int x = run.x0; x < run.x1; ++x) {
        sl += Lp[x], sa += Ap[x], sb += Bp[x];
        sz += Zp[x], nz += Vp[x] > 0.f;
      }
      st.L = sl, st.A = sa, st.B = sb, st.z = sz, st.nz = nz;
      st.n += run.x1 - run.x0;
    }
  }
  const int count = static_cast<int>(stats.size());
  // Neighbours of the small components.
  std::vector<std::vector<int>> neighbours(count);
  auto link = [&](int a, int b) {
    if (a == b) return;
    // Big components only need their list once a small one merges into them and keeps growing.
    if (stats[a].n < min_size) neighbours[a].push_back(b);
    if (stats[b].n < min_size) neighbours[b].push_back(a);
  };
  for (int y = 0; y < h; ++y) {
    const int* row = comp.ptr<int>(y);
    const int* below = y + 1 < h ? comp.ptr<int>(y + 1) : nullptr;
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) link(row[x], row[x + 1]);
      if (below) link(row[x], below[x]);
    }
  }
  std::vector<int> parent(count);
  for (int i = 0; i < count; ++i) parent[i] = i;
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<int> order;
  for (int i = 0; i < count; ++i)
    if (stats[i].n < min_size) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return stats[a].n < stats[b].n; });
  for (int small : order) {
    const int a = root(small);
    if (stats[a].n >= min_size) continue;  // already grown by earlier merges
    const Stats& sa = stats[a];
    int best = -1;
    double best_d = std::numeric_limits<double>::max();
    for (int nb : neighbours[a]) {
      const int b = root(nb);
      if (b == a) continue;
      const Stats& sb = stats[b];
      const double dl = sa.L / sa.n - sb.L / sb.n, da = sa.A / sa.n - sb.A / sb.n, db = sa.B / sa.n - sb.B / sb.n;
      double d = std::sqrt(dl * dl + da * da + db * db) * inv_colour;
      if (sa.nz > 0 && sb.nz > 0) d += std::fabs(sa.z / sa.nz - sb.z / sb.nz) * inv_depth;
      if (d < best_d) best_d = d, best = b;
    }
    if (best < 0) continue;
    parent[a] = best;
    Stats& sb = stats[best];
    sb.L += sa.L, sb.A += sa.A, sb.B += sa.B, sb.z += sa.z, sb.n += sa.n, sb.nz += sa.nz;
    // The merged component's neighbours are those of both parts.
    neighbours[best].insert(neighbours[best].end(), neighbours[a].begin(), neighbours[a].end());
  }
  std::vector<int> final_label(count, -1);
  int next = 0;
  for (int y = 0; y < h; ++y) {
    int* out = labels.ptr<int>(y);
    const int* c = comp.ptr<int>(y);
    for (int x = 0; x < w; ++x) {
      const int r = root(c[x]);
      if (final_label[r] < 0) final_label[r] = next++;
      out[x] = final_label[r];
    }
  }
  return next;
}

bool cpuHasAvx2() {
#if AMOS_SLIC_AVX2
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

}  // namespace

void prepareDepthSlic() {
  cv::Mat lab;
  cv::cvtColor(cv::Mat(1, 1, CV_8UC3, cv::Scalar::all(0)), lab, cv::COLOR_BGR2Lab);
}

int integerFactor(cv::Size big, cv::Size small) {
  if (small.width <= 0 || small.height <= 0 || big.width % small.width != 0) return 0;
  const int f = big.width / small.width;
  return f >= 1 && big.height == f * small.height ? f : 0;
}

SuperpixelSegmentation computeDepthSlic(const cv::Mat& bgr, const cv::Mat& depth, const DepthSlicOptions& options) {
  static const bool avx2 = cpuHasAvx2();
  return detail::computeDepthSlic(bgr, depth, options, avx2);
}

namespace detail {

SuperpixelSegmentation computeDepthSlic(const cv::Mat& bgr, const cv::Mat& depth, const DepthSlicOptions& options,
                                        bool avx2) {
  options.check();
  core::require(!bgr.empty() && bgr.type() == CV_8UC3, "computeDepthSlic: bgr must be a non-empty CV_8UC3 image");
  core::require(depth.type() == CV_32F && depth.size() == bgr.size(),
                "computeDepthSlic: depth must be CV_32F with the size of the colour image");

  const Planes p = makePlanes(bgr, depth, options.scale);
  float step = 0;
  std::vector<Centre> centres = seedCentres(p, options.num_superpixels, step);
  cv::Mat labels(p.height, p.width, CV_32S, cv::Scalar(-1));
  cv::Mat distance(p.height, p.width, CV_32F);
  const AssignWeights weights{step, static_cast<float>(1.0 / options.colour_scale),
                              static_cast<float>(1.0 / options.depth_scale_m), avx2};
  for (int it = 0; it < options.iterations; ++it) {
    assignPixels(p, centres, weights, labels, distance);
    updateCentres(p, labels, centres);
  }
  // Pixels farther than one step from every centre (possible after centres drift) keep -1; give them to their
  // left/upper neighbour's superpixel before the connectivity pass.
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      if (labels.at<int>(y, x) < 0)
        labels.at<int>(y, x) = x > 0 ? labels.at<int>(y, x - 1) : (y > 0 ? labels.at<int>(y - 1, x) : 0);
  const int min_size = std::max(1, static_cast<int>(step * step / 4));
  const int count = enforceConnectivity(p, labels, min_size, weights.inv_colour, weights.inv_depth);

  SuperpixelSegmentation result;
  result.superpixels.resize(count);
  {
    const std::vector<LabelSum> sums = sumLabels(p, labels, static_cast<std::size_t>(count));
    // Working pixel centre x maps to full-resolution coordinate (x + 0.5) / s - 0.5.
    const double fx = static_cast<double>(bgr.cols) / p.width, fy = static_cast<double>(bgr.rows) / p.height;
    for (int k = 0; k < count; ++k) {
      const LabelSum& sum = sums[k];
      const int n = sum.n;
      Superpixel& s = result.superpixels[k];
      s.pixel_count = n;
      s.x = static_cast<float>((static_cast<double>(sum.x) / n + 0.5) * fx - 0.5);
      s.y = static_cast<float>((static_cast<double>(sum.y) / n + 0.5) * fy - 0.5);
      s.L = static_cast<float>(sum.L / n);
      s.A = static_cast<float>(static_cast<double>(sum.A) / n);
      s.B = static_cast<float>(static_cast<double>(sum.B) / n);
      s.depth = sum.nz > 0 ? static_cast<float>(sum.z / sum.nz) : 0.f;
      s.valid_depth_fraction = static_cast<float>(sum.nz) / n;
    }
  }
  result.working_labels = labels;
  if (labels.size() == bgr.size()) {
    result.labels = labels;
  } else if (const int f = integerFactor(bgr.size(), labels.size()); f > 0) {
    // Every working label as an f x f block (cv::resize's nearest neighbour gives the same, through its general
    // per-pixel index tables at several times the cost).
    result.labels.create(bgr.size(), CV_32S);
    for (int y = 0; y < labels.rows; ++y) {
      const int* in = labels.ptr<int>(y);
      int* out = result.labels.ptr<int>(f * y);
      for (int x = 0; x < labels.cols; ++x)
        for (int k = 0; k < f; ++k) out[f * x + k] = in[x];
      for (int r = 1; r < f; ++r) std::copy(out, out + bgr.cols, result.labels.ptr<int>(f * y + r));
    }
  } else {
    cv::resize(labels, result.labels, bgr.size(), 0, 0, cv::INTER_NEAREST);
  }
  return result;
}

}  // namespace detail

}  // namespace amos::dynamic
