#include "core/parallel/thread_pool.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>

#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
#define SD_NO_THREADS 1  // the single-threaded wasm build: no pthreads in its runtime
#else
#include <condition_variable>
#include <system_error>
#include <thread>
#include <vector>
#endif

namespace sd::parallel {

int hardware_threads() {
#ifdef SD_NO_THREADS
  return 1;
#else
  return std::max(1u, std::thread::hardware_concurrency());
#endif
}

bool threads_supported() {
#ifdef SD_NO_THREADS
  return false;
#else
  return true;
#endif
}

#ifdef SD_NO_THREADS

int set_threads(int) { return 1; }
int threads() { return 1; }
void run_tasks(int count, const std::function<void(int)>& task) {
  for (int i = 0; i < count; ++i) task(i);
}

#else

namespace {

// Upper bound on set_threads, so a typo (set_threads(1000000)) cannot exhaust the process.
constexpr int kMaxThreads = 256;

// One run_tasks call: tasks are claimed one at a time from `next` by whichever thread is free (the caller
// and the workers), so a slow or late thread never holds up the others.
struct Job {
  const std::function<void(int)>* task = nullptr;
  int count = 0;
  int workers = 0;  // pool threads allowed to join (threads() - 1 at the start)
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;  // the first exception, written once under error_mutex
  std::mutex error_mutex;

  void work() {
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      if (failed.load(std::memory_order_relaxed)) continue;
      try {
        (*task)(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  }
};

// True on pool threads and on a caller while it runs tasks: a nested run_tasks then runs inline.
thread_local bool inside_task = false;

class Pool {
 public:
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  int set_threads(int count) {
    std::lock_guard<std::mutex> lock(mutex_);
    return set_threads_locked(count);
  }

  int threads() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (active_ == 0) set_threads_locked(0);
    return active_;
  }

  void run(int count, const std::function<void(int)>& task) {
    if (count <= 0) return;
    bool expected = false;
    if (count == 1 || inside_task || !busy_.compare_exchange_strong(expected, true)) {
      run_inline(count, task);
      return;
    }
    Job job;
    job.task = &task;
    job.count = count;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (active_ == 0) set_threads_locked(0);
      job.workers = std::min(active_ - 1, count - 1);
      if (job.workers > 0) {
        job_ = &job;
        ++generation_;
      }
    }
    if (job.workers > 0) wake_.notify_all();
    inside_task = true;
    job.work();
    inside_task = false;
    if (job.workers > 0) {
      // No thread may join from now on; wait for those that did (they finish the tasks they claimed).
      std::unique_lock<std::mutex> lock(mutex_);
      job_ = nullptr;
      done_.wait(lock, [&] { return attached_ == 0; });
    }
    busy_ = false;
    if (job.error) std::rethrow_exception(job.error);
  }

 private:
  static void run_inline(int count, const std::function<void(int)>& task) {
    const bool was_inside = inside_task;
    inside_task = true;
    try {
      for (int i = 0; i < count; ++i) task(i);
    } catch (...) {
      inside_task = was_inside;
      throw;
    }
    inside_task = was_inside;
  }

  int set_threads_locked(int count) {
    int wanted = count <= 0 ? hardware_threads() : std::min(count, kMaxThreads);
    // Threads are started once and kept (a later smaller count just leaves some idle), so that changing
    // the count never has to wait for a thread to start or stop.
    while (static_cast<int>(threads_.size()) < wanted - 1) {
      try {
        const int index = static_cast<int>(threads_.size());
        threads_.emplace_back([this, index] { worker(index); });
      } catch (const std::system_error&) {
        // No more threads can be started (the wasm build's worker pool is used up): use what we have.
        wanted = static_cast<int>(threads_.size()) + 1;
      }
    }
    active_ = wanted;
    return active_;
  }

  void worker(int index) {
    inside_task = true;
    unsigned long long seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      Job* job = job_;
      if (!job || index >= job->workers) continue;
      ++attached_;
      lock.unlock();
      job->work();
      lock.lock();
      if (--attached_ == 0) done_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;  // a new job (generation_ changed) or stop_
  std::condition_variable done_;  // attached_ dropped to 0
  std::vector<std::thread> threads_;
  unsigned long long generation_ = 0;
  Job* job_ = nullptr;  // the job threads may join, null when none
  int attached_ = 0;    // pool threads working on job_
  int active_ = 0;      // threads() (0: not yet decided, hardware_threads() on first use)
  bool stop_ = false;
  std::atomic<bool> busy_{false};  // a run() is in progress (a concurrent caller runs inline)
};

Pool& pool() {
  static Pool instance;
  return instance;
}

}  // namespace

int set_threads(int count) { return pool().set_threads(count); }
int threads() { return pool().threads(); }
void run_tasks(int count, const std::function<void(int)>& task) { pool().run(count, task); }

#endif

}  // namespace sd::parallel
