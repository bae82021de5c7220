#pragma once
/// \file
/// `mpr::detail::prefetch_l2` and `prefetch_l1`: software prefetches of data a kernel will read
/// a while later (the next camera's rows of a light-field tile, a tree walk's next nodes), by
/// address only.

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

/// Asks for the cache line at `bytes` past `base`, to arrive in L1: data a kernel reads within
/// the next few hundred cycles (a child node of a tree walk). Same rules as `prefetch_l2`.
MPR_ALWAYS_INLINE void prefetch_l1(const void* base, std::size_t bytes) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(base) + bytes), 0, 3);
#else
  (void)base;
  (void)bytes;
#endif
}

} // namespace mpr::detail
