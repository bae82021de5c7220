#pragma once
/// \file
/// `mpr::detail::prefetch_l2`: a software prefetch of data a kernel will read a while later
/// (the next camera's rows of a light-field tile), by address only.

#include <mpr/core/config.hpp>

#include <cstddef>
#include <cstdint>

namespace mpr::detail {

/// Asks for the cache line at `bytes` past `base`, to arrive in L2 (GCC and Clang; nothing
/// elsewhere). The address is computed as an integer, so it may lie past the end of the object
/// `base` points into (a prefetch never faults and nothing is read). Always inlined: GCC finds an
/// out-of-line function of prefetches free of side effects and drops its calls.
MPR_ALWAYS_INLINE void prefetch_l2(const void* base, std::size_t bytes) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(base) + bytes), 0, 2);
#else
  (void)base;
  (void)bytes;
#endif
}

} // namespace mpr::detail
