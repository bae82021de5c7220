#pragma once
/// \file
/// Spreading the rows of a render over threads. OpenMP is used when the translation unit is
/// compiled with it (and `MPR_NO_OPENMP` is not defined), otherwise `std::thread`; both hand out
/// rows through `RowBlocks`. Each row is computed by exactly one thread with no shared state, so
/// results never depend on scheduling.

#include <mpr/core/config.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <new>
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

/// The rows [0, count) handed out to `workers` workers: worker w first takes the rows of its own
/// contiguous block [w count / workers, (w + 1) count / workers) in order, then, one at a time,
/// the last row of the block with the most rows left. Neighbouring rows of an image read
/// neighbouring rows of its sources (a light field's camera rows, a depth map's), so a worker
/// that renders a run of rows keeps those in its own cache; handing rows out round-robin made
/// each of two threads miss on every row the other had just loaded (`DepthProxy` on Chess: 10%
/// more CPU time on 2 threads than on 1; docs/performance.md). Taking from the back of the
/// fullest block keeps the workers busy to the end when rows differ in cost.
/// Lock-free; every row is handed out exactly once, whichever workers run.
class RowBlocks {
public:
  /// Preconditions: 0 <= count, 1 <= workers. `valid()` is false when out of memory.
  RowBlocks(int count, int workers) noexcept
      : blocks_(new (std::nothrow) Block[static_cast<std::size_t>(workers)]), workers_(workers) {
    if (!blocks_) return;
    for (int w = 0; w < workers; ++w) {
      const auto front = static_cast<std::uint64_t>(static_cast<std::int64_t>(count) * w / workers);
      const auto back = static_cast<std::uint64_t>(static_cast<std::int64_t>(count) * (w + 1) / workers);
      blocks_[static_cast<std::size_t>(w)].range.store(front | back << 32, std::memory_order_relaxed);
    }
  }

  [[nodiscard]] bool valid() const noexcept { return blocks_ != nullptr; }

  /// The next row for worker w (0 <= w < workers), or -1 when every row has been handed out.
  [[nodiscard]] int next(int w) noexcept {
    const int own = take(blocks_[static_cast<std::size_t>(w)], false);
    if (own >= 0) return own;
    for (;;) { // the fullest block's last row; another worker may take it first, so look again
      int fullest = -1;
      std::uint32_t most = 0;
      for (int v = 0; v < workers_; ++v) {
        const std::uint64_t r = blocks_[static_cast<std::size_t>(v)].range.load(std::memory_order_relaxed);
        const auto front = static_cast<std::uint32_t>(r), back = static_cast<std::uint32_t>(r >> 32);
        if (back > front && back - front > most) {
          most = back - front;
          fullest = v;
        }
      }
      if (fullest < 0) return -1;
      const int row = take(blocks_[static_cast<std::size_t>(fullest)], true);
      if (row >= 0) return row;
    }
  }

  /// Worker w's share: `row(begin + r)` for each row r that `next(w)` hands out.
  template <class RowFn>
  void work(int w, int begin, const RowFn& row) noexcept {
    for (int r = next(w); r >= 0; r = next(w)) row(begin + r);
  }

private:
  // [front, back) of a block: front in the low 32 bits, back in the high ones.
  struct alignas(64) Block {
    std::atomic<std::uint64_t> range{0};
  };

  // The block's first row (`last`: its last row), removed from it; -1 when it is empty.
  static int take(Block& b, bool last) noexcept {
    std::uint64_t r = b.range.load(std::memory_order_relaxed);
    for (;;) {
      const auto front = static_cast<std::uint32_t>(r), back = static_cast<std::uint32_t>(r >> 32);
      if (front >= back) return -1;
      const std::uint64_t taken = last ? (r - (std::uint64_t(1) << 32)) : r + 1;
      // Only the row index is shared: the rows' results are published by the join at the end.
      if (b.range.compare_exchange_weak(r, taken, std::memory_order_relaxed))
        return static_cast<int>(last ? back - 1 : front);
    }
  }

  std::unique_ptr<Block[]> blocks_;
  int workers_;
};

/// Calls `row(y)` for y in [begin, end) on up to `threads` std::threads (the caller included),
/// the rows handed out by `RowBlocks`. If threads cannot be started, the ones that run do the
/// remaining rows.
template <class RowFn>
void parallel_rows_std(int begin, int end, int threads, const RowFn& row) noexcept {
  if (end <= begin) return;
  threads = std::max(threads, 1);
  RowBlocks rows(end - begin, threads);
  if (!rows.valid()) { // out of memory: one thread, same result
    for (int y = begin; y < end; ++y) row(y);
    return;
  }
  const auto worker = [&](int w) noexcept { rows.work(w, begin, row); };
  std::vector<std::thread> pool;
  try {
    pool.reserve(static_cast<std::size_t>(threads - 1));
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker, i);
  } catch (...) {
    // Out of threads or memory: fewer workers, same result.
  }
  worker(0);
  for (std::thread& t : pool) t.join();
}

#if MPR_PARALLEL_OPENMP
/// OpenMP version of `parallel_rows_std` (the team may have fewer threads than asked for: the
/// others' blocks are then taken from their ends).
template <class RowFn>
void parallel_rows_openmp(int begin, int end, int threads, const RowFn& row) noexcept {
  if (end <= begin) return;
  RowBlocks rows(end - begin, threads);
  if (!rows.valid()) {
    for (int y = begin; y < end; ++y) row(y);
    return;
  }
#pragma omp parallel num_threads(threads)
  { rows.work(std::min(omp_get_thread_num(), threads - 1), begin, row); }
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
