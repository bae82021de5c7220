#pragma once
/// \file
/// `mpr::detail::HugePageAllocator<T>`: a standard allocator for large read-mostly buffers (the
/// texels of light-field frames) that asks Linux for transparent huge pages. A tilted or scaled
/// focal plane reads each camera image along slanted lines, touching a new 4 KiB page every few
/// pixels, and an aperture reads a short run of each of many frames; with 2 MiB pages the same
/// reads fit the TLB (`CameraFrameSet` keeps all its frames in one buffer for that). Buffers of
/// at least 1 MiB are aligned and padded to 2 MiB and advised `MADV_HUGEPAGE` (honoured when the
/// system's THP setting is `madvise` or `always`); smaller buffers, other systems and a refused
/// advice get plain memory. Every buffer starts on a 64-byte boundary and has `kPadding` readable
/// bytes after its end, so that vector kernels may load a whole word that starts at the last
/// element (e.g. a 32-bit gather of a 3-byte texel).

#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mpr::detail {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  /// The huge-page size asked for, and the least buffer size that asks for it.
  static constexpr std::size_t kHugePage = std::size_t(2) << 20;
  static constexpr std::size_t kThreshold = std::size_t(1) << 20;
  /// Readable bytes after the last element.
  static constexpr std::size_t kPadding = 64;
  /// The alignment of every buffer, bytes.
  static constexpr std::size_t kAlignment = alignof(T) > 64 ? alignof(T) : 64;

  HugePageAllocator() noexcept = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  [[nodiscard]] T* allocate(std::size_t n) {
    if (n > (static_cast<std::size_t>(-1) - 2 * kHugePage) / sizeof(T)) throw std::bad_alloc();
    const std::size_t bytes = n * sizeof(T) + kPadding;
    if (bytes < kThreshold) return static_cast<T*>(::operator new(bytes, std::align_val_t(kAlignment)));
    const std::size_t padded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, padded);
    if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    (void)::madvise(p, padded, MADV_HUGEPAGE); // advice only: plain pages when refused
#endif
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) + kPadding < kThreshold)
      ::operator delete(p, std::align_val_t(kAlignment));
    else
      std::free(p);
  }

  template <class U>
  friend bool operator==(const HugePageAllocator&, const HugePageAllocator<U>&) noexcept {
    return true;
  }
};

} // namespace mpr::detail
