#pragma once
/// \file
/// `mpr::Stratified`: n x n jittered strata per pixel.

#include <mpr/sampling/pixel_sampling.hpp>

#include <cstdint>

namespace mpr {

/// The pixel's sampling square cut into n x n equal strata, one sample per stratum at a jittered
/// position: stratum (i mod n, i div n), jitter from a hash of the pixel, the index and `seed`
/// (deterministic). n = 1 is one uniformly jittered sample per pixel.
class Stratified {
public:
  /// Largest n accepted (64 x 64 = 4096 samples per pixel).
  static constexpr int kMaxN = 64;

  /// Throws `argument_error` naming "stratified n" unless 1 <= n <= kMaxN.
  explicit Stratified(int n, std::uint32_t seed = 0) : n_(n), seed_(seed) {
    if (n < 1 || n > kMaxN) throw argument_error("stratified n", "must be in [1, 64]");
  }

  [[nodiscard]] int n() const noexcept { return n_; }
  [[nodiscard]] int count() const noexcept { return n_ * n_; }

  /// Sample `i` (in [0, n * n)) of `px`: in stratum (i mod n, i div n), in [0, 1)^2.
  [[nodiscard]] SamplePoint point(Pixel px, int i) const noexcept {
    const std::uint32_t h = detail::mix32(detail::pixel_seed(px, seed_) ^ static_cast<std::uint32_t>(i) * 0x85ebca6bU);
    const std::uint32_t h2 = detail::mix32(h ^ 0x5bd1e995U);
    // 24 random bits per axis: (stratum + jitter) / n stays below 1 in double.
    const double jx = static_cast<double>(h >> 8) * (1.0 / 16777216.0);
    const double jy = static_cast<double>(h2 >> 8) * (1.0 / 16777216.0);
    const double inv = 1.0 / n_;
    return {(static_cast<double>(i % n_) + jx) * inv, (static_cast<double>(i / n_) + jy) * inv};
  }

  /// The lens point of sample `i` (`LensSamplePattern`): stratum `shuffle(i)` of the n x n
  /// strata, with a permutation and jitter of its own per pixel, so every lens stratum is used
  /// once and lens strata are not tied to image strata.
  [[nodiscard]] SamplePoint lens_point(Pixel px, int i) const noexcept {
    const std::uint32_t seed = detail::pixel_seed(px, seed_ ^ 0x3c6ef372U);
    const auto count = static_cast<std::uint32_t>(n_ * n_);
    const int k = static_cast<int>(detail::shuffle_index(static_cast<std::uint32_t>(i), count, seed));
    const std::uint32_t h = detail::mix32(seed ^ static_cast<std::uint32_t>(i) * 0xc2b2ae35U);
    const std::uint32_t h2 = detail::mix32(h ^ 0x27d4eb2fU);
    const double jx = static_cast<double>(h >> 8) * (1.0 / 16777216.0);
    const double jy = static_cast<double>(h2 >> 8) * (1.0 / 16777216.0);
    const double inv = 1.0 / n_;
    return {(static_cast<double>(k % n_) + jx) * inv, (static_cast<double>(k / n_) + jy) * inv};
  }

private:
  int n_;
  std::uint32_t seed_;
};

} // namespace mpr
