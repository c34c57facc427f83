// The thread pool for JS: one per module instance (a page's Web Worker, or a Node process), so these are
// functions of the module, not of a Deformer session. web/lib/load.js and web/lib/node.js call setThreads
// after loading; a page that runs several solver workers at once gives each a share of the cores.
//   setThreads(n) -> the count now in effect (0: all the platform's cores; fewer when the build has fewer
//                    threads: 1 in the single-threaded build, the pre-started workers + 1 in the threaded one)
//   threads()          -> the count in effect
//   hardwareThreads()  -> navigator.hardwareConcurrency / os.cpus().length as the module sees it (1 in the
//                         single-threaded build)
//   threadsSupported() -> whether this build has threads at all
#include <emscripten/bind.h>

#include <cmath>
#include <string>

#include "bindings/convert.h"
#include "core/parallel/thread_pool.h"

namespace sd::bindings {
namespace {

int set_threads_js(const val& count) {
  return guarded([&] {
    const double n = count.isNumber() ? count.as<double>() : NAN;
    if (!(n >= 0 && n <= 1024 && n == std::floor(n)))
      throw Error(ErrorCode::InvalidArgument,
                  "setThreads: the thread count must be a whole number from 0 (all cores) to 1024");
    return parallel::set_threads(static_cast<int>(n));
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(parallel) {
  emscripten::function("setThreads", &set_threads_js);
  emscripten::function("threads", &parallel::threads);
  emscripten::function("hardwareThreads", &parallel::hardware_threads);
  emscripten::function("threadsSupported", &parallel::threads_supported);
}

}  // namespace sd::bindings
