#include "core/parallel/parallel_for.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/mesh/mesh_check.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace sd::parallel {
namespace {

// Restores the process-wide thread count after a test changes it.
struct ThreadCountGuard {
  int saved = threads();
  ~ThreadCountGuard() { set_threads(saved); }
};

TEST(ThreadPool, CountsAreClampedAndZeroMeansTheHardware) {
  ThreadCountGuard guard;
  EXPECT_GE(hardware_threads(), 1);
  EXPECT_EQ(set_threads(0), hardware_threads());
  EXPECT_EQ(threads(), hardware_threads());
  EXPECT_EQ(set_threads(1), 1);
  EXPECT_EQ(set_threads(-3), hardware_threads());  // negative: as 0
  ASSERT_TRUE(threads_supported());                // natively always
  EXPECT_EQ(set_threads(3), 3);
  EXPECT_EQ(threads(), 3);
}

TEST(ParallelFor, VisitsEveryIndexExactlyOnceInFixedBlocks) {
  ThreadCountGuard guard;
  for (int t : {1, 2, 4, 7})
    for (int n : {0, 1, 5, 64, 1000, 1001}) {
      set_threads(t);
      std::vector<std::atomic<int>> visits(static_cast<size_t>(n) + 3);
      std::atomic<int> bad_block{0};
      parallel_for(3, n + 3, 64, [&](int lo, int hi) {
        if ((lo - 3) % 64 != 0 || hi - lo > 64 || hi <= lo) ++bad_block;  // blocks start at multiples of 64
        for (int i = lo; i < hi; ++i) ++visits[static_cast<size_t>(i)];
      });
      EXPECT_EQ(bad_block, 0);
      for (int i = 0; i < n + 3; ++i)
        EXPECT_EQ(visits[static_cast<size_t>(i)], i < 3 ? 0 : 1) << "t " << t << " n " << n;
    }
}

// Terms whose sum depends on the order of addition (mixed magnitudes), so a reduction that combined
// partial sums in a thread-dependent order would show it in the last bits.
double term(int i) { return std::sin(0.37 * i) * std::pow(10.0, (i * 7919) % 17 - 8); }

TEST(ParallelReduce, BitIdenticalForAnyThreadCountAndEqualToTheBlockOrderSum) {
  ThreadCountGuard guard;
  const int n = 100003, block = 1000;
  double expected = 0.0;  // the definition: per-block sums, added in block order
  for (int lo = 0; lo < n; lo += block) {
    double s = 0.0;
    for (int i = lo; i < std::min(n, lo + block); ++i) s += term(i);
    expected += s;
  }
  for (int t : {1, 2, 3, 4, 8}) {
    set_threads(t);
    for (int repeat = 0; repeat < 3; ++repeat) {
      const double sum = parallel_sum(0, n, block, [](int lo, int hi) {
        double s = 0.0;
        for (int i = lo; i < hi; ++i) s += term(i);
        return s;
      });
      EXPECT_EQ(std::memcmp(&sum, &expected, sizeof sum), 0) << t << " threads: " << sum << " vs " << expected;
    }
  }
}

TEST(ParallelReduce, OneBlockIsThePlainLoop) {
  double plain = 0.0;
  for (int i = 0; i < 500; ++i) plain += term(i);
  const double sum = parallel_sum(0, 500, 512, [](int lo, int hi) {
    double s = 0.0;
    for (int i = lo; i < hi; ++i) s += term(i);
    return s;
  });
  EXPECT_EQ(sum, plain);
}

// A condition that tasks on different threads wait for: set() wakes every waiter. wait() gives up after a
// minute only so that a broken pool fails its test instead of hanging it; no test relies on that time.
class Signal {
 public:
  void set() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      set_ = true;
    }
    changed_.notify_all();
  }
  bool wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, std::chrono::minutes(1), [&] { return set_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool set_ = false;
};

TEST(ThreadPool, TasksRunOnSeveralThreads) {
  ThreadCountGuard guard;
  ASSERT_EQ(set_threads(4), 4);
  std::mutex mutex;
  std::set<std::thread::id> ids;
  Signal second_thread;
  // Each task waits until tasks have run on two threads, so the caller cannot finish them all alone.
  run_tasks(16, [&](int) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      ids.insert(std::this_thread::get_id());
      if (ids.size() >= 2) second_thread.set();
    }
    second_thread.wait();
  });
  EXPECT_GE(ids.size(), 2u);
  EXPECT_LE(ids.size(), 4u);
}

TEST(ThreadPool, AnExceptionReachesTheCallerAndThePoolKeepsWorking) {
  ThreadCountGuard guard;
  set_threads(4);
  EXPECT_THROW(run_tasks(32,
                         [](int i) {
                           if (i == 13) throw std::runtime_error("task 13 failed");
                         }),
               std::runtime_error);
  std::atomic<int> done{0};
  run_tasks(32, [&](int) { ++done; });
  EXPECT_EQ(done, 32);
}

// Runs `count` tasks where a pool thread (never the caller) throws `error`: the caller's task waits until
// one has, so the exception is sure to cross threads.
template <class E>
void throw_on_a_pool_thread(const E& error) {
  const std::thread::id caller = std::this_thread::get_id();
  Signal thrown;
  run_tasks(8, [&](int) {
    if (std::this_thread::get_id() != caller) {
      thrown.set();
      throw error;
    }
    thrown.wait();
  });
}

// The core's errors keep their type, code and findings when a pool thread throws them, so the bindings
// turn them into the same JS errors as a throw on the caller (code MeshOutsideCage with its findings,
// Cancelled).
TEST(ThreadPool, ErrorsFromAPoolThreadKeepTheirTypeCodeAndFindings) {
  ThreadCountGuard guard;
  set_threads(4);
  CheckReport report;
  report.findings.push_back({Severity::Error, "outside_cage", "1 of 8 mesh vertices is outside the cage (first: 7)"});
  try {
    throw_on_a_pool_thread(MeshError(report));
    FAIL() << "no exception reached the caller";
  } catch (const MeshError& e) {
    EXPECT_EQ(e.code(), ErrorCode::MeshOutsideCage);
    ASSERT_EQ(e.findings().size(), 1u);
    EXPECT_EQ(e.findings()[0].code, "outside_cage");
    EXPECT_NE(std::string(e.what()).find("outside the cage"), std::string::npos);
  }
  try {
    throw_on_a_pool_thread(Error(ErrorCode::Cancelled, "binding cancelled"));
    FAIL() << "no exception reached the caller";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Cancelled);
    EXPECT_STREQ(e.what(), "binding cancelled");
  }
}

TEST(ThreadPool, NestedLoopsRunInlineWithoutDeadlock) {
  ThreadCountGuard guard;
  set_threads(4);
  std::vector<int> cells(64 * 64, 0);
  parallel_for(0, 64, 4, [&](int lo, int hi) {
    for (int i = lo; i < hi; ++i)
      parallel_for(0, 64, 8, [&](int jlo, int jhi) {
        for (int j = jlo; j < jhi; ++j) ++cells[static_cast<size_t>(64 * i + j)];
      });
  });
  for (int c : cells) EXPECT_EQ(c, 1);
}

TEST(ThreadPool, ConcurrentCallersBothFinish) {
  ThreadCountGuard guard;
  set_threads(3);
  std::atomic<long long> total{0};
  auto caller = [&] {
    for (int r = 0; r < 50; ++r) run_tasks(20, [&](int i) { total += i; });
  };
  std::thread other(caller);
  caller();
  other.join();
  EXPECT_EQ(total, 2LL * 50 * 190);
}

}  // namespace
}  // namespace sd::parallel
