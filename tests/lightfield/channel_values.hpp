#pragma once
// The stored channels of the row-kernel tests, as the kernels read them: 8-bit sRGB codes go
// through the 16-bit linear table (`Srgb8Texel::linear16()`), other channels are their value;
// `scale` maps the stored value to linear light (1/65535 for table values and 16-bit channels).
#include <mpr/lightfield/frame_set.hpp>

#include <cstdint>
#include <type_traits>

namespace mpr_test {

template <class C>
struct ChannelValues {
  const std::uint16_t* lut = std::is_same_v<C, std::uint8_t> ? mpr::Srgb8Texel::linear16() : nullptr;
  float scale = std::is_same_v<C, float> ? 1.0f : 1.0f / 65535.0f;

  /// The stored value of channel c (before `scale`), in long double.
  [[nodiscard]] long double value(C c) const {
    if constexpr (std::is_same_v<C, std::uint8_t>)
      return static_cast<long double>(lut[c]);
    else
      return static_cast<long double>(c);
  }
};

} // namespace mpr_test
