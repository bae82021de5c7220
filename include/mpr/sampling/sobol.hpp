#pragma once
/// \file
/// `mpr::OwenSobol`: the first two dimensions of the Sobol sequence with per-pixel nested
/// uniform (Owen) scrambling, a low-discrepancy pattern for any sample count.

#include <mpr/sampling/pixel_sampling.hpp>

#include <cstdint>

namespace mpr {

namespace detail {

/// `v` with its 32 bits in reverse order.
[[nodiscard]] constexpr std::uint32_t reverse_bits(std::uint32_t v) noexcept {
  v = ((v >> 1) & 0x55555555U) | ((v & 0x55555555U) << 1);
  v = ((v >> 2) & 0x33333333U) | ((v & 0x33333333U) << 2);
  v = ((v >> 4) & 0x0f0f0f0fU) | ((v & 0x0f0f0f0fU) << 4);
  v = ((v >> 8) & 0x00ff00ffU) | ((v & 0x00ff00ffU) << 8);
  return (v >> 16) | (v << 16);
}

/// Sobol dimension 0 of index `i` as 32 fraction bits: the van der Corput radical inverse.
[[nodiscard]] constexpr std::uint32_t sobol_dim0(std::uint32_t i) noexcept { return reverse_bits(i); }

/// Sobol dimension 1 of index `i` as 32 fraction bits: generator matrix of primitive
/// polynomial x + 1, column k = v_k with v_0 = 2^31 and v_{k+1} = v_k ^ (v_k >> 1).
[[nodiscard]] constexpr std::uint32_t sobol_dim1(std::uint32_t i) noexcept {
  std::uint32_t result = 0, v = 0x80000000U;
  for (; i != 0; i >>= 1, v ^= v >> 1)
    if ((i & 1U) != 0) result ^= v;
  return result;
}

/// The Laine-Karras hash: each output bit depends only on the input bits at and below it.
[[nodiscard]] constexpr std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) noexcept {
  x += seed;
  x ^= x * 0x6c50b47cU;
  x ^= x * 0xb82f1e52U;
  x ^= x * 0xc7afe638U;
  x ^= x * 0x8d22f6e6U;
  return x;
}

/// Nested uniform scrambling of the 32 fraction bits `x`: each bit is flipped by a hash of
/// `seed` and the bits above it (Laine and Karras' hash on the bit-reversed value: addition and
/// multiplication by even constants only carry towards higher bits of the reversed value, i.e.
/// lower digits of the fraction), so the digits of a (0, m, 2)-net stay a (0, m, 2)-net.
[[nodiscard]] constexpr std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) noexcept {
  return reverse_bits(laine_karras(reverse_bits(x), seed));
}

/// owen_scramble(sobol_dim0(i), seed) with the two bit reversals that cancel left out.
[[nodiscard]] constexpr std::uint32_t owen_sobol_dim0(std::uint32_t i, std::uint32_t seed) noexcept {
  return reverse_bits(laine_karras(i, seed));
}

} // namespace detail

/// `count` points per pixel: Sobol points 0 .. count-1 of dimensions 0 and 1, each dimension
/// Owen-scrambled with seeds hashed from the pixel and `seed`. For count = 2^m the points of a
/// pixel form a (0, m, 2)-net: every elementary box of area 1/count holds exactly one.
class OwenSobol {
public:
  /// Largest sample count accepted.
  static constexpr int kMaxCount = 65536;

  /// Throws `argument_error` naming "samples per pixel" unless 1 <= count <= kMaxCount.
  explicit OwenSobol(int count, std::uint32_t seed = 0) : count_(count), seed_(seed) {
    if (count < 1 || count > kMaxCount) throw argument_error("samples per pixel", "must be in [1, 65536]");
  }

  [[nodiscard]] int count() const noexcept { return count_; }

  /// Sample `i` (in [0, count)) of `px`, in [0, 1)^2.
  [[nodiscard]] SamplePoint point(Pixel px, int i) const noexcept {
    const std::uint32_t s = detail::pixel_seed(px, seed_);
    const auto index = static_cast<std::uint32_t>(i);
    const std::uint32_t x = detail::owen_sobol_dim0(index, detail::mix32(s ^ 0x68bc21ebU));
    const std::uint32_t y = detail::owen_scramble(detail::sobol_dim1(index), detail::mix32(s ^ 0x02e5be93U));
    return {detail::unit_from_bits(x), detail::unit_from_bits(y)};
  }

  /// The lens point of sample `i` (`LensSamplePattern`): the same scrambled Sobol points with
  /// seeds of their own, taken in an order shuffled per pixel (detail::shuffle_index), so the
  /// pixel's lens points are again a (0, m, 2)-net for count = 2^m, decorrelated from its image
  /// points.
  [[nodiscard]] SamplePoint lens_point(Pixel px, int i) const noexcept {
    const std::uint32_t s = detail::pixel_seed(px, seed_ ^ 0x9e3779b9U);
    const std::uint32_t index =
        detail::shuffle_index(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(count_), detail::mix32(s));
    const std::uint32_t x = detail::owen_sobol_dim0(index, detail::mix32(s ^ 0x68bc21ebU));
    const std::uint32_t y = detail::owen_scramble(detail::sobol_dim1(index), detail::mix32(s ^ 0x02e5be93U));
    return {detail::unit_from_bits(x), detail::unit_from_bits(y)};
  }

private:
  int count_;
  std::uint32_t seed_;
};

} // namespace mpr
