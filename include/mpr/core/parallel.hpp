#pragma once
/// \file
/// Spreading the rows of a render over threads. OpenMP is used when the translation unit is
/// compiled with it (and `MPR_NO_OPENMP` is not defined), otherwise `std::thread`. Each row is
/// computed by exactly one thread with no shared state, so results never depend on scheduling.

#include <mpr/core/config.hpp>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#if MPR_PARALLEL_OPENMP
#include <omp.h>
#endif

namespace mpr::detail {

/// The number of threads to use for a request of `requested` (<= 0: all hardware threads),
/// never more than `rows`.
[[nodiscard]] inline int resolve_thread_count(int requested, int rows) noexcept {
  int n = requested;
  if (n <= 0) n = static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(n, 1, std::max(rows, 1));
}

/// Calls `row(y)` for y in [begin, end) on up to `threads` std::threads (the caller included).
/// If threads cannot be started, the caller does the remaining rows itself.
template <class RowFn>
void parallel_rows_std(int begin, int end, int threads, const RowFn& row) noexcept {
  std::atomic<int> next{begin};
  const auto worker = [&]() noexcept {
    for (int y = next.fetch_add(1, std::memory_order_relaxed); y < end;
         y = next.fetch_add(1, std::memory_order_relaxed))
      row(y);
  };
  std::vector<std::thread> pool;
  try {
    pool.reserve(static_cast<std::size_t>(threads - 1));
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
  } catch (...) {
    // Out of threads or memory: fewer workers, same result.
  }
  worker();
  for (std::thread& t : pool) t.join();
}

#if MPR_PARALLEL_OPENMP
/// OpenMP version of `parallel_rows_std`.
template <class RowFn>
void parallel_rows_openmp(int begin, int end, int threads, const RowFn& row) noexcept {
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int y = begin; y < end; ++y) row(y);
}
#endif

/// Calls `row(y)` for every y in [begin, end), on `resolve_thread_count(threads)` threads.
template <class RowFn>
void parallel_rows(int begin, int end, int threads, const RowFn& row) noexcept {
  if (end <= begin) return;
  const int n = resolve_thread_count(threads, end - begin);
  if (n == 1) {
    for (int y = begin; y < end; ++y) row(y);
    return;
  }
#if MPR_PARALLEL_OPENMP
  parallel_rows_openmp(begin, end, n, row);
#else
  parallel_rows_std(begin, end, n, row);
#endif
}

} // namespace mpr::detail
