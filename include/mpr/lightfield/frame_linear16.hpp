#pragma once
/// \file
/// The 16-bit linear copy of a frame set's 8-bit frames (`CameraFrameSet::linear16`): every code
/// replaced by its entry of the 16-bit decode table, built once when the set is, for the levels
/// whose kernels read it instead of decoding codes (`CameraFrameSet::holds_linear16`).

#include <mpr/core/detail/huge_page_allocator.hpp>
#include <mpr/core/image.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace mpr::detail {

/// One buffer of 16-bit values, in huge pages where the allocator can.
using Linear16Vector = std::vector<std::uint16_t, HugePageAllocator<std::uint16_t>>;

/// Every image's channels as 16-bit values `lut[code]`, from its texels `at[i]` (`Texel::c`: the
/// image's 3 width height codes in a row), in one buffer: each image from a multiple of 32 values
/// (64 bytes) and followed by at least 32. `out[i]` receives image i's first value.
template <class Px, class Texel>
[[nodiscard]] std::shared_ptr<const Linear16Vector>
linear16_copy(const std::vector<std::shared_ptr<const Image<Px>>>& images, const std::vector<const Texel*>& at,
              const std::uint16_t* lut, std::vector<const std::uint16_t*>& out) {
  constexpr std::size_t kAlign = 32;
  out.clear();
  std::vector<std::size_t> offsets(images.size(), 0);
  std::size_t total = 0;
  for (std::size_t i = 0; i < images.size(); ++i) {
    offsets[i] = total;
    const std::size_t n =
        3 * static_cast<std::size_t>(images[i]->width()) * static_cast<std::size_t>(images[i]->height());
    total += (n + kAlign) / kAlign * kAlign + kAlign;
  }
  auto buffer = std::make_shared<Linear16Vector>(total);
  for (std::size_t i = 0; i < images.size(); ++i) {
    std::uint16_t* v = buffer->data() + offsets[i];
    const std::uint8_t* codes = at[i]->c;
    const std::size_t n =
        3 * static_cast<std::size_t>(images[i]->width()) * static_cast<std::size_t>(images[i]->height());
    for (std::size_t k = 0; k < n; ++k) v[k] = lut[codes[k]];
    out.push_back(v);
  }
  return buffer;
}

} // namespace mpr::detail
