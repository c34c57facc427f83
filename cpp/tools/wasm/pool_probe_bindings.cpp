// Test-only binding of the bench module (never in the module pages load): throws an error from a thread
// of the pool, not from the calling thread, so tests/js/threads.test.js can check that the threaded wasm
// builds carry an exception between threads with its type, code and findings. The pool rethrows a task's
// exception on the caller (core/parallel/thread_pool.h); natively tests/cpp/parallel/parallel_for_test.cpp
// checks the same, but in wasm the exception object crosses Web Workers (or worker_threads) through the
// shared heap, which only a wasm run can show.
//   benchThrowInPool(kind) with kind 'outside_cage' (a MeshError with one finding), 'cancelled' or
//   'out_of_memory' (std::bad_alloc) -> throws it from a pool thread; returns nothing. Needs threads() >= 2
//   (else it refuses: nothing would run off the caller).
#include <emscripten/bind.h>

#include <atomic>
#include <chrono>
#include <new>
#include <string>
#include <thread>

#include "bindings/convert.h"
#include "core/error.h"
#include "core/mesh/mesh_check.h"
#include "core/parallel/thread_pool.h"

namespace sd::bindings {
namespace {

[[noreturn]] void throw_kind(const std::string& kind) {
  if (kind == "outside_cage") {
    CheckReport report;
    report.findings.push_back({Severity::Error, "outside_cage", "1 of 8 mesh vertices is outside the cage (first: 7)"});
    throw MeshError(report);
  }
  if (kind == "cancelled") throw Error(ErrorCode::Cancelled, "cancelled on a pool thread");
  if (kind == "out_of_memory") throw std::bad_alloc();
  throw Error(ErrorCode::InvalidArgument, "benchThrowInPool: unknown kind '" + kind + "'");
}

void throw_in_pool(const std::string& kind) {
  guarded([&] {
    const int threads = parallel::threads();
    if (threads < 2) throw Error(ErrorCode::InvalidArgument, "benchThrowInPool: needs at least 2 threads (setThreads)");
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<bool> thrown{false};
    // The caller's task waits until a pool thread has thrown (tasks are claimed one at a time, so the
    // others go to the pool); a pool thread's task throws. The pool then skips what is left.
    parallel::run_tasks(threads, [&](int) {
      if (std::this_thread::get_id() != caller) {
        thrown = true;
        throw_kind(kind);
      }
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (!thrown.load()) {
        if (std::chrono::steady_clock::now() > give_up)
          throw Error(ErrorCode::Internal, "benchThrowInPool: no pool thread ran a task within 20 s");
        std::this_thread::yield();
      }
    });
    throw Error(ErrorCode::Internal, "benchThrowInPool: the pool thread's exception did not reach the caller");
  });
}

}  // namespace
}  // namespace sd::bindings

EMSCRIPTEN_BINDINGS(pool_probe) { emscripten::function("benchThrowInPool", &sd::bindings::throw_in_pool); }
