#include <mpr/core/parallel.hpp>

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

TEST_CASE("RowBlocks hands each worker its block in order, then the fullest block's last rows", "[parallel]") {
  // 10 rows, 3 workers: blocks [0, 3), [3, 6), [6, 10).
  mpr::detail::RowBlocks rows(10, 3);
  REQUIRE(rows.valid());
  CHECK(rows.next(1) == 3);
  CHECK(rows.next(1) == 4);
  CHECK(rows.next(1) == 5);
  // Worker 1's block is empty: it takes the last row of the fullest block (worker 2's, 4 left).
  CHECK(rows.next(1) == 9);
  CHECK(rows.next(0) == 0);
  // Now blocks 0 ([1, 3): 2 left) and 2 ([6, 9): 3 left): block 2 again.
  CHECK(rows.next(1) == 8);
  // Equal (2 and 2): the first such block.
  CHECK(rows.next(1) == 2);
  CHECK(rows.next(2) == 6);
  CHECK(rows.next(2) == 7);
  CHECK(rows.next(2) == 1);
  CHECK(rows.next(0) == -1);
  CHECK(rows.next(1) == -1);
  CHECK(rows.next(2) == -1);
}

TEST_CASE("RowBlocks with more workers than rows, and no rows", "[parallel]") {
  mpr::detail::RowBlocks few(2, 5); // blocks [0,0) [0,0) [0,1) [1,1) [1,2)
  CHECK(few.next(0) == 0);          // its own block is empty: the first fullest, worker 2's
  CHECK(few.next(3) == 1);
  CHECK(few.next(4) == -1);
  mpr::detail::RowBlocks none(0, 2);
  CHECK(none.next(0) == -1);
  CHECK(none.next(1) == -1);
}

TEST_CASE("parallel rows: every row exactly once, whatever the threads and the rows' costs", "[parallel]") {
  for (const int threads : {1, 2, 3, 7, 64}) {
    for (const int count : {0, 1, 5, 67, 300}) {
      INFO(threads << " threads, " << count << " rows");
      const int begin = 11;
      std::vector<std::atomic<int>> seen(static_cast<std::size_t>(count));
      // Rows in the first half cost more, so the workers of the second half take from the first.
      const auto row = [&](int y) noexcept {
        const int i = y - begin;
        if (i < count / 2) std::this_thread::sleep_for(std::chrono::microseconds(50));
        seen[static_cast<std::size_t>(i)].fetch_add(1);
      };
      mpr::detail::parallel_rows(begin, begin + count, threads, row);
      for (const std::atomic<int>& s : seen) REQUIRE(s.load() == 1);
      for (std::atomic<int>& s : seen) s.store(0);
      mpr::detail::parallel_rows_std(begin, begin + count, threads, row); // the std::thread back end
      for (const std::atomic<int>& s : seen) REQUIRE(s.load() == 1);
    }
  }
}
