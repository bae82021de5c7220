#pragma once
// mpr-view's worker pool: persistent threads that share out the bands of one frame. A frame is
// one fork and one join (threads sleep on a condition variable in between, so an idle viewer
// and an oversubscribed machine cost no spinning); within a frame each thread takes the next
// band from an atomic counter, so the frame can be abandoned between any two bands. (One
// OpenMP parallel region per band instead costs a barrier per band, which on a loaded machine
// made two threads several times slower than one.)

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace mpr_view {

class BandPool {
public:
  /// `threads` workers in all, the calling thread of `run` included (at least 1).
  explicit BandPool(int threads) {
    for (int i = 1; i < std::max(threads, 1); ++i) {
      try {
        helpers_.emplace_back([this] { helper_loop(); });
      } catch (...) {
        break; // fewer threads, same result
      }
    }
  }
  BandPool(const BandPool&) = delete;
  BandPool& operator=(const BandPool&) = delete;
  ~BandPool() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : helpers_) t.join();
  }

  [[nodiscard]] int threads() const noexcept { return static_cast<int>(helpers_.size()) + 1; }

  /// Calls `work(b)` once for every b in [0, count), spread over the pool, and returns when all
  /// calls have returned. `work` must not throw.
  void run(int count, const std::function<void(int)>& work) {
    {
      const std::lock_guard lock(mutex_);
      work_ = &work;
      count_ = count;
      next_.store(0);
      busy_ = static_cast<int>(helpers_.size());
      ++epoch_;
    }
    start_.notify_all();
    take_bands(work, count);
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    work_ = nullptr;
  }

private:
  void take_bands(const std::function<void(int)>& work, int count) {
    for (int b = next_.fetch_add(1); b < count; b = next_.fetch_add(1)) work(b);
  }

  void helper_loop() {
    std::uint64_t seen = 0;
    for (;;) {
      const std::function<void(int)>* work = nullptr;
      int count = 0;
      {
        std::unique_lock lock(mutex_);
        start_.wait(lock, [&] { return stop_ || epoch_ != seen; });
        if (stop_) return;
        seen = epoch_;
        work = work_;
        count = count_;
      }
      take_bands(*work, count);
      {
        const std::lock_guard lock(mutex_);
        if (--busy_ == 0) done_.notify_one();
      }
    }
  }

  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* work_ = nullptr;
  int count_ = 0;
  int busy_ = 0;
  std::uint64_t epoch_ = 0;
  bool stop_ = false;
  std::atomic<int> next_{0};
  std::vector<std::thread> helpers_;
};

} // namespace mpr_view
