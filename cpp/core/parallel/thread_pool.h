// One process-wide pool of worker threads for the core's parallel loops (parallel_for.h builds on it).
//
// Process-wide, not per session: the machine's cores are one resource. In the browser every Web Worker
// holds its own module instance and so its own pool; a page that runs several workers at once (the app's
// compare mode) gives each a share of the cores with set_threads. The calling thread always takes part,
// so `threads` counts it: threads() == 1 means everything runs on the caller.
//
// Builds without threads (the single-threaded WebAssembly build) keep threads() at 1 and run every loop
// inline; the code that uses the pool is the same in every build.
#pragma once

#include <functional>

namespace sd::parallel {

// Logical cores the platform reports (std::thread::hardware_concurrency; in wasm the browser's
// navigator.hardwareConcurrency or Node's os.cpus()), at least 1.
int hardware_threads();

// Sets how many threads parallel loops use (the caller included); 0 means hardware_threads(). Returns the
// count now in effect, which is lower than asked when no more threads can be started (a build without
// threads: 1; the threaded wasm build: its pre-started pool of Web Workers plus the caller).
int set_threads(int count);
// The count in effect (hardware_threads() until set_threads is called, within the same limits).
int threads();
// Whether this build can run threads at all (false for the single-threaded wasm build).
bool threads_supported();

// Runs task(0) .. task(count - 1), each exactly once, on up to threads() threads, and returns when all
// have finished. Tasks must write disjoint outputs. The first exception a task throws is rethrown here
// (tasks not yet started are skipped). A call from inside a task, or while another thread is inside
// run_tasks, runs all its tasks inline on the calling thread: nesting never deadlocks, and since results
// never depend on which thread ran a task (parallel_for.h), nothing changes but the speed.
void run_tasks(int count, const std::function<void(int)>& task);

}  // namespace sd::parallel
