#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/kernels/sweep_kernels.hpp>
#include <mpr/lightfield/kernels/sweep_seen_kernels.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

namespace {

using mpr::detail::SimdLevel;

std::vector<float> random_values(std::size_t n, unsigned seed, float lo = 0, float hi = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<float> v(n);
  for (float& x : v) x = u(rng);
  return v;
}

// A neighbour image of planar channels, `stride` = width + 3 floats per row (the padding zero).
struct TestImage {
  int width, height;
  std::ptrdiff_t stride;
  std::vector<float> data;
  TestImage(int w, int h, unsigned seed) : width(w), height(h), stride(w + 3), data(3 * (w + 3) * h, 0.0f) {
    const std::vector<float> v = random_values(data.size(), seed);
    for (int c = 0; c < 3; ++c)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) at(c, x, y) = v[static_cast<std::size_t>((c * h + y) * stride + x)];
  }
  float& at(int c, int x, int y) { return data[static_cast<std::size_t>((c * height + y) * stride + x)]; }
  const float* channel(int c) const { return data.data() + static_cast<std::ptrdiff_t>(c) * height * stride; }
  mpr::detail::SweepImage view() const { return {{channel(0), channel(1), channel(2)}, stride, width, height}; }
};

// The cost of one pixel against `image` at (u, v) as the old per-pixel sweep computed it: -1
// where (u, v) is outside the image (not seen).
float reference_cost(TestImage& image, float u, float v, const float ref[3], float tau) {
  if (!(u >= 0 && v >= 0 && u <= static_cast<float>(image.width - 1) && v <= static_cast<float>(image.height - 1)))
    return -1;
  const int u0 = std::min(static_cast<int>(u), std::max(image.width - 2, 0));
  const int v0 = std::min(static_cast<int>(v), std::max(image.height - 2, 0));
  const int u1 = std::min(u0 + 1, image.width - 1), v1 = std::min(v0 + 1, image.height - 1);
  const float fu = u - static_cast<float>(u0), fv = v - static_cast<float>(v0);
  float s = 0;
  for (int c = 0; c < 3; ++c) {
    const float a = image.at(c, u0, v0) * (1 - fu) + image.at(c, u1, v0) * fu;
    const float b = image.at(c, u0, v1) * (1 - fu) + image.at(c, u1, v1) * fu;
    s += std::abs((a * (1 - fv) + b * fv) - ref[c]);
  }
  return std::min(s, tau);
}

} // namespace

TEST_CASE("the translated-row cost blends four texels with fixed weights and truncates", "[sweep_kernels]") {
  TestImage image(61, 9, 3);
  const int n = 40, shift = 17, row = 4;
  const std::vector<float> ref = random_values(3 * n, 4);
  const float* ref_rows[3] = {ref.data(), ref.data() + n, ref.data() + 2 * n};
  const float tau = 0.9f;
  for (const float fu : {0.0f, 0.25f, 0.7f, 1.0f})
    for (const float fv : {0.0f, 0.4f, 1.0f}) {
      mpr::detail::SweepShiftRow r{};
      r.fu = fu;
      r.fv = fv;
      for (int c = 0; c < 3; ++c) {
        r.top[c] = image.channel(c) + row * image.stride + shift;
        r.bottom[c] = image.channel(c) + (row + 1) * image.stride + shift;
      }
      std::vector<float> expected(n);
      int truncated = 0;
      for (int x = 0; x < n; ++x) {
        const float px[3] = {ref_rows[0][x], ref_rows[1][x], ref_rows[2][x]};
        expected[static_cast<std::size_t>(x)] =
            reference_cost(image, static_cast<float>(x + shift) + fu, static_cast<float>(row) + fv, px, tau);
        truncated += expected[static_cast<std::size_t>(x)] == tau;
      }
      CHECK(truncated > 0);
      CHECK(truncated < n);
      mpr_test::for_each_simd_level([&](SimdLevel level) {
        std::vector<float> out(n, -1.0f);
        mpr::detail::sweep_shift_cost(ref_rows, r, tau, out.data(), n, level);
        for (int x = 0; x < n; ++x) {
          INFO("fu " << fu << " fv " << fv << " x " << x);
          CHECK(out[static_cast<std::size_t>(x)] == Approx(expected[static_cast<std::size_t>(x)]).margin(1e-5));
        }
        // The same costs inserted into 1..4 sorted rows at once.
        for (int best = 1; best <= mpr::detail::kSweepShiftKeepBest; ++best) {
          const std::ptrdiff_t stride = n + 7;
          std::vector<float> keep(static_cast<std::size_t>(best * stride));
          std::vector<std::vector<float>> sorted(n);
          const std::vector<float> start = random_values(keep.size(), 11, 0.0f, tau);
          for (int x = 0; x < n; ++x) {
            for (int i = 0; i < best; ++i)
              sorted[static_cast<std::size_t>(x)].push_back(start[static_cast<std::size_t>(i * stride + x)]);
            std::sort(sorted[static_cast<std::size_t>(x)].begin(), sorted[static_cast<std::size_t>(x)].end());
            for (int i = 0; i < best; ++i)
              keep[static_cast<std::size_t>(i * stride + x)] =
                  sorted[static_cast<std::size_t>(x)][static_cast<std::size_t>(i)];
          }
          mpr::detail::sweep_shift_keep(ref_rows, r, tau, keep.data(), stride, best, n, level);
          for (int x = 0; x < n; ++x) {
            std::vector<float> e = sorted[static_cast<std::size_t>(x)];
            e.push_back(expected[static_cast<std::size_t>(x)]);
            std::sort(e.begin(), e.end());
            for (int i = 0; i < best; ++i) {
              INFO("fu " << fu << " fv " << fv << " x " << x << " best " << best << " rank " << i);
              CHECK(keep[static_cast<std::size_t>(i * stride + x)] ==
                    Approx(e[static_cast<std::size_t>(i)]).margin(1e-5));
            }
          }
        }
      });
    }
}

TEST_CASE("the fused translated-row kernel averages the best costs as the per-neighbour kernels do",
          "[sweep_kernels]") {
  TestImage image(61, 9, 5);
  const int width = 40;
  const std::vector<float> ref = random_values(3 * width, 9);
  const float* ref_rows[3] = {ref.data(), ref.data() + width, ref.data() + 2 * width};
  const float tau = 0.9f;
  // Four neighbours' rows: shifts, rows and sub-pixel offsets differ.
  const int shifts[4] = {17, 3, 20, 0}, rows[4] = {4, 0, 7, 2};
  const float fus[4] = {0.25f, 0.0f, 0.8f, 1.0f}, fvs[4] = {0.4f, 1.0f, 0.0f, 0.65f};
  mpr::detail::SweepShiftRow r[4];
  for (int j = 0; j < 4; ++j) {
    r[j].fu = fus[j];
    r[j].fv = fvs[j];
    for (int c = 0; c < 3; ++c) {
      r[j].top[c] = image.channel(c) + rows[j] * image.stride + shifts[j];
      r[j].bottom[c] = image.channel(c) + (rows[j] + 1) * image.stride + shifts[j];
    }
  }
  for (const int n : {0, 1, 15, 16, 17, width})
    for (int m = 1; m <= mpr::detail::kSweepShiftMeanNeighbours; ++m)
      for (int best = 1; best <= m; ++best) {
        // The reference: the m costs per pixel from the texels, sorted, the best averaged.
        std::vector<float> expected(static_cast<std::size_t>(n));
        int spread = 0; // pixels where the kept costs differ (the choice of the best matters)
        for (int x = 0; x < n; ++x) {
          const float px[3] = {ref_rows[0][x], ref_rows[1][x], ref_rows[2][x]};
          std::vector<float> c;
          for (int j = 0; j < m; ++j)
            c.push_back(reference_cost(image, static_cast<float>(x + shifts[j]) + fus[j],
                                       static_cast<float>(rows[j]) + fvs[j], px, tau));
          std::sort(c.begin(), c.end());
          spread += c.front() != c.back();
          float sum = 0;
          for (int i = 0; i < best; ++i) sum += c[static_cast<std::size_t>(i)];
          expected[static_cast<std::size_t>(x)] = sum / static_cast<float>(best);
        }
        if (n == width && m > 1) CHECK(spread > n / 2);
        mpr_test::for_each_simd_level([&](SimdLevel level) {
          // The per-neighbour kernels at the same level: the fused one must give the same bits.
          const std::ptrdiff_t stride = width + 5;
          std::vector<float> keep(static_cast<std::size_t>(best * stride), tau), mean(static_cast<std::size_t>(n) + 1);
          for (int j = 0; j < m; ++j)
            mpr::detail::sweep_shift_keep(ref_rows, r[j], tau, keep.data(), stride, best, static_cast<std::size_t>(n),
                                          level);
          float* k[4];
          for (int i = 0; i < best; ++i) k[i] = keep.data() + i * stride;
          mpr::detail::sweep_mean_best(k, best, mean.data(), static_cast<std::size_t>(n), level);
          std::vector<float> out(static_cast<std::size_t>(n) + 1, -1.0f);
          mpr::detail::sweep_shift_mean(ref_rows, r, m, best, tau, out.data(), static_cast<std::size_t>(n), level);
          for (int x = 0; x < n; ++x) {
            INFO("n " << n << " m " << m << " best " << best << " x " << x);
            CHECK(out[static_cast<std::size_t>(x)] == mean[static_cast<std::size_t>(x)]);
            CHECK(out[static_cast<std::size_t>(x)] == Approx(expected[static_cast<std::size_t>(x)]).margin(1e-5));
          }
          CHECK(out[static_cast<std::size_t>(n)] == -1.0f); // nothing written past n
        });
      }
}

TEST_CASE("the projective-row cost follows any homography, unseen where it leaves the image", "[sweep_kernels]") {
  TestImage image(37, 23, 5);
  const int first = 3, n = 90;
  const std::vector<float> ref = random_values(3 * (first + n), 6);
  const float* ref_rows[3] = {ref.data(), ref.data() + first + n, ref.data() + 2 * (first + n)};
  const float tau = 0.4f;
  // A row whose image point moves non-linearly (h.z varies along it) across the whole neighbour
  // image and out of both sides, and whose h.z turns negative at the end.
  mpr::detail::SweepProjectiveRow row{{-4.0f, 2.0f, 1.5f}, {0.2f, 0.6f, 0.9f}, {0.31f, 0.09f, -0.03f}, 1.3f};
  std::vector<float> expected(n);
  int unseen = 0, behind = 0, truncated = 0;
  for (int i = 0; i < n; ++i) {
    const float x = static_cast<float>(first + i);
    const float hx = row.origin[0] + row.depth * (row.base[0] + x * row.step[0]);
    const float hy = row.origin[1] + row.depth * (row.base[1] + x * row.step[1]);
    const float hz = row.origin[2] + row.depth * (row.base[2] + x * row.step[2]);
    const float px[3] = {ref_rows[0][first + i], ref_rows[1][first + i], ref_rows[2][first + i]};
    float c = hz > 0 ? reference_cost(image, hx / hz, hy / hz, px, tau) : -1;
    behind += !(hz > 0);
    if (c < 0) {
      ++unseen;
      c = tau;
    } else {
      truncated += c == tau;
    }
    expected[static_cast<std::size_t>(i)] = c;
  }
  CHECK(unseen > behind);
  CHECK(behind > 0);
  CHECK(unseen < n - 10);
  CHECK(truncated > 0);
  mpr_test::for_each_simd_level([&](SimdLevel level) {
    std::vector<float> out(n, -1.0f);
    mpr::detail::sweep_projective_cost(ref_rows, image.view(), row, first, tau, out.data(), n, level);
    for (int i = 0; i < n; ++i) {
      INFO("pixel " << first + i);
      CHECK(out[static_cast<std::size_t>(i)] == Approx(expected[static_cast<std::size_t>(i)]).margin(1e-5));
    }
  });
}

TEST_CASE("the best-of-m network keeps the smallest costs and averages them", "[sweep_kernels]") {
  const std::size_t n = 53;
  const float tau = 0.5f;
  for (const int m : {1, 3, 4, 7})
    for (int best = 1; best <= m; ++best) {
      std::vector<std::vector<float>> rows;
      for (int j = 0; j < m; ++j) {
        std::vector<float> r = random_values(n, static_cast<unsigned>(10 * m + j), 0.0f, 0.6f);
        for (float& v : r) v = std::min(v, tau);
        rows.push_back(r);
      }
      std::vector<float> expected(n);
      for (std::size_t x = 0; x < n; ++x) {
        std::vector<float> c;
        for (int j = 0; j < m; ++j) c.push_back(rows[static_cast<std::size_t>(j)][x]);
        std::sort(c.begin(), c.end());
        float s = 0;
        for (int j = 0; j < best; ++j) s += c[static_cast<std::size_t>(j)];
        expected[x] = s / static_cast<float>(best);
      }
      mpr_test::for_each_simd_level([&](SimdLevel level) {
        std::vector<std::vector<float>> keep(static_cast<std::size_t>(best), std::vector<float>(n, tau));
        float* k[32];
        for (int i = 0; i < best; ++i) k[i] = keep[static_cast<std::size_t>(i)].data();
        for (int j = 0; j < m; ++j) {
          std::vector<float> v = rows[static_cast<std::size_t>(j)];
          mpr::detail::sweep_keep_best(k, best, v.data(), n, level);
        }
        std::vector<float> out(n), body(n);
        mpr::detail::sweep_mean_best(k, best, out.data(), n, level);
        mpr::detail::sweep_mean_best_body(k, best, body.data(), n); // the generic loops, every best
        for (std::size_t x = 0; x < n; ++x) {
          INFO("m " << m << " best " << best << " x " << x);
          CHECK(out[x] == Approx(expected[x]).margin(1e-6));
          CHECK(out[x] == body[x]); // the one-pass form for best <= 4: the same sums, bit for bit
          for (int i = 1; i < best; ++i)
            CHECK(keep[static_cast<std::size_t>(i - 1)][x] <= keep[static_cast<std::size_t>(i)][x]);
        }
      });
    }
}

TEST_CASE("the domain-transform passes match the serial recurrence", "[sweep_kernels]") {
  const int n = 45, rows = mpr::detail::kSweepLockstepRows;
  const std::ptrdiff_t stride = n + 5;
  const std::vector<float> values = random_values(static_cast<std::size_t>(rows * stride), 7);
  const std::vector<float> feedback = random_values(static_cast<std::size_t>(rows * stride), 8, 0.0f, 0.99f);
  // The serial reference: forward then backward along each row.
  std::vector<float> expected = values;
  for (int r = 0; r < rows; ++r) {
    float* v = expected.data() + r * stride;
    const float* a = feedback.data() + r * stride;
    for (int k = 1; k < n; ++k) v[k] += a[k] * (v[k - 1] - v[k]);
    for (int k = n - 2; k >= 0; --k) v[k] += a[k + 1] * (v[k + 1] - v[k]);
  }
  mpr_test::for_each_simd_level([&](SimdLevel level) {
    std::vector<float> block = values, single = values;
    mpr::detail::sweep_dt_rows(block.data(), feedback.data(), stride, n, level);
    for (int r = 0; r < rows; ++r)
      mpr::detail::sweep_dt_row(single.data() + r * stride, feedback.data() + r * stride, n, level);
    for (int r = 0; r < rows; ++r)
      for (int k = 0; k < stride; ++k) {
        const std::size_t i = static_cast<std::size_t>(r * stride + k);
        INFO("row " << r << " k " << k);
        CHECK(block[i] == Approx(expected[i]).margin(1e-6));
        CHECK(single[i] == Approx(expected[i]).margin(1e-6));
      }
    // The vertical link: one row pulled towards the previous one.
    std::vector<float> cur = values;
    mpr::detail::sweep_dt_link(cur.data(), values.data() + stride, feedback.data(), static_cast<std::size_t>(n), level);
    for (int k = 0; k < n; ++k) {
      const std::size_t i = static_cast<std::size_t>(k);
      CHECK(cur[i] ==
            Approx(values[i] + feedback[i] * (values[i + static_cast<std::size_t>(stride)] - values[i])).margin(1e-6));
    }
  });
}

TEST_CASE("the argmin bookkeeping tracks the cheapest plane and its neighbours' costs", "[sweep_kernels]") {
  const std::size_t n = 37;
  const int planes = 17;
  std::vector<std::vector<float>> costs;
  for (int p = 0; p < planes; ++p) costs.push_back(random_values(n, static_cast<unsigned>(100 + p)));
  // Ties: the first of equal costs stays the best.
  costs[5][3] = costs[2][3] = -1.0f;
  // The reference: the old per-pixel update.
  std::vector<float> best_cost(n, INFINITY), left(n, 0), right(n, 0), previous(n, 0), sum(n, 0);
  std::vector<int> best_plane(n, 0);
  for (int p = 0; p < planes; ++p)
    for (std::size_t k = 0; k < n; ++k) {
      const float c = costs[static_cast<std::size_t>(p)][k];
      sum[k] += c;
      if (best_plane[k] == p - 1) right[k] = c;
      if (c < best_cost[k]) {
        best_cost[k] = c;
        best_plane[k] = p;
        left[k] = p > 0 ? previous[k] : c;
        right[k] = c;
      }
      previous[k] = c;
    }
  CHECK(best_plane[3] == 2);
  mpr_test::for_each_simd_level([&](SimdLevel level) {
    // The state starts as garbage: the first batch (plane 0) writes it without reading it.
    const float garbage = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> bc(n, garbage), l(n, garbage), r(n, garbage), pr(n, garbage), s(n, garbage);
    std::vector<int> bp(n, -7);
    // The planes in batches of 8, 4, 3, 1 and 1 (counts the kernel takes), `stride` apart.
    const std::size_t stride = n + 3;
    int p = 0;
    for (const int count : {8, 4, 3, 1, 1}) {
      std::vector<float> rows(static_cast<std::size_t>(count) * stride);
      for (int i = 0; i < count; ++i)
        std::copy(costs[static_cast<std::size_t>(p + i)].begin(), costs[static_cast<std::size_t>(p + i)].end(),
                  rows.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(i) * stride));
      mpr::detail::sweep_track(
          rows.data(), static_cast<std::ptrdiff_t>(stride), count,
          mpr::detail::SweepTrackRow{bc.data(), bp.data(), l.data(), r.data(), pr.data(), s.data()}, p, n, level);
      p += count;
    }
    REQUIRE(p == planes);
    for (std::size_t k = 0; k < n; ++k) {
      INFO("pixel " << k);
      CHECK(bp[k] == best_plane[k]);
      CHECK(bc[k] == best_cost[k]);
      CHECK(l[k] == left[k]);
      CHECK(r[k] == right[k]);
      CHECK(s[k] == Approx(sum[k]).margin(1e-6));
    }
  });
}

TEST_CASE("the chunked kernel averages the best costs of the neighbours that see each pixel", "[sweep_kernels]") {
  // Twelve neighbours' translated rows over a row of 53 pixels (three chunks of 16 and a
  // remainder of 5), each seen over its own span: whole, from or up to inside a chunk, one pixel,
  // none. The expected value per pixel: the costs of the neighbours that see it (from the
  // texels), tau for the others, sorted, the best averaged.
  TestImage image(80, 12, 21);
  const int width = 53, m = 12;
  const std::vector<float> ref = random_values(3 * width, 23);
  const float* ref_rows[3] = {ref.data(), ref.data() + width, ref.data() + 2 * width};
  const float tau = 0.8f;
  const int shifts[m] = {0, 3, 17, 9, 20, 1, 5, 12, 7, 2, 14, 11}, rows[m] = {0, 4, 7, 2, 9, 1, 3, 5, 8, 6, 10, 0};
  const int xbs[m] = {0, 5, 16, 0, 20, 31, 0, 47, 52, 10, 3, 0},
            xes[m] = {53, 53, 32, 17, 21, 50, 48, 53, 53, 10, 40, 53};
  const float fus[m] = {0.25f, 0.0f, 0.8f, 1.0f, 0.5f, 0.1f, 0.9f, 0.33f, 0.6f, 0.2f, 0.75f, 0.05f};
  const float fvs[m] = {0.4f, 1.0f, 0.0f, 0.65f, 0.3f, 0.7f, 0.15f, 0.5f, 0.95f, 0.2f, 0.45f, 0.85f};
  mpr::detail::SweepSeenRow seen[m];
  for (int j = 0; j < m; ++j) {
    seen[j].row.fu = fus[j];
    seen[j].row.fv = fvs[j];
    for (int c = 0; c < 3; ++c) {
      seen[j].row.top[c] = image.channel(c) + rows[j] * image.stride + shifts[j] + xbs[j];
      seen[j].row.bottom[c] = image.channel(c) + (rows[j] + 1) * image.stride + shifts[j] + xbs[j];
    }
    seen[j].xb = xbs[j];
    seen[j].xe = xes[j];
  }
  for (int best = 1; best <= m; ++best) {
    std::vector<float> expected(static_cast<std::size_t>(width));
    for (int x = 0; x < width; ++x) {
      const float px[3] = {ref_rows[0][x], ref_rows[1][x], ref_rows[2][x]};
      std::vector<float> c;
      for (int j = 0; j < m; ++j)
        c.push_back(x >= xbs[j] && x < xes[j] ? reference_cost(image, static_cast<float>(x + shifts[j]) + fus[j],
                                                               static_cast<float>(rows[j]) + fvs[j], px, tau)
                                              : tau);
      std::sort(c.begin(), c.end());
      float sum = 0;
      for (int i = 0; i < best; ++i) sum += c[static_cast<std::size_t>(i)];
      expected[static_cast<std::size_t>(x)] = sum / static_cast<float>(best);
    }
    mpr_test::for_each_simd_level([&](SimdLevel level) {
      std::vector<float> out(static_cast<std::size_t>(width) + 1, -1.0f);
      mpr::detail::sweep_shift_mean_seen(ref_rows, seen, m, best, tau, out.data(), width, level);
      for (int x = 0; x < width; ++x) {
        INFO("best " << best << " x " << x);
        CHECK(out[static_cast<std::size_t>(x)] == Approx(expected[static_cast<std::size_t>(x)]).margin(1e-5));
      }
      CHECK(out[static_cast<std::size_t>(width)] == -1.0f); // nothing written past the row
    });
  }
}

TEST_CASE("the chunked float kernel takes one register of the level", "[sweep_kernels]") {
#if defined(__GNUC__)
  using mpr::detail::SimdLevel;
  using mpr::detail::sweep_seen_lanes;
  // A vector type wider than the level's registers is lowered to scalar code.
  STATIC_REQUIRE(sizeof(mpr::detail::SweepSeenVectors<sweep_seen_lanes(SimdLevel::portable)>::Lanes) == 16);
  STATIC_REQUIRE(sizeof(mpr::detail::SweepSeenVectors<sweep_seen_lanes(SimdLevel::avx2)>::Lanes) == 32);
  STATIC_REQUIRE(sizeof(mpr::detail::SweepSeenVectors<sweep_seen_lanes(SimdLevel::avx512)>::Lanes) == 64);
#else
  SUCCEED("the compiler has no vector types: the kernel is scalar");
#endif
}
