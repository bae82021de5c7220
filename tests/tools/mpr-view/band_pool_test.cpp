#include "mpr-view/band_pool.hpp"

#include <catch2/catch.hpp>

#include <atomic>
#include <set>
#include <thread>
#include <vector>

TEST_CASE("BandPool calls every band exactly once, frame after frame", "[view]") {
  for (const int threads : {1, 2, 4}) {
    mpr_view::BandPool pool(threads);
    CHECK(pool.threads() == threads);
    for (const int count : {0, 1, 7, 100}) {
      std::vector<std::atomic<int>> calls(static_cast<std::size_t>(count));
      std::mutex mutex;
      std::set<std::thread::id> ids;
      pool.run(count, [&](int b) {
        calls[static_cast<std::size_t>(b)].fetch_add(1);
        const std::lock_guard lock(mutex);
        ids.insert(std::this_thread::get_id());
      });
      for (const std::atomic<int>& c : calls) CHECK(c.load() == 1);
      CHECK(static_cast<int>(ids.size()) <= threads);
    }
  }
}

TEST_CASE("BandPool work can stop early (a cancelled frame)", "[view]") {
  mpr_view::BandPool pool(3);
  std::atomic<bool> cancelled{false};
  std::atomic<int> rendered{0};
  pool.run(1000, [&](int b) {
    if (b == 10) cancelled = true;
    if (cancelled) return;
    ++rendered;
  });
  CHECK(rendered.load() < 1000); // the remaining bands return at once
  std::atomic<int> after{0};
  pool.run(5, [&](int) { ++after; }); // the pool is usable again
  CHECK(after.load() == 5);
}
