// Native counterpart of the wasm integration benchmark of scripts/bench.mjs (--integration): runs
// cpp/tools/bench_integration.h for each "n:segments" argument and prints one JSON object per line.
//
//   bench_integration [--frames F] [--float32] [--no-solve] [--threads T] 5000:24 50000:24 280000:24
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/parallel/thread_pool.h"
#include "tools/bench_integration.h"

int main(int argc, char** argv) {
  sd::bench::IntegrationOptions base;
  std::vector<std::pair<int, int>> cases;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if ((arg == "--frames" || arg == "--threads") && a + 1 >= argc) {
      std::fprintf(stderr, "bench_integration: %s needs a value\n", arg.c_str());
      return 2;
    }
    if (arg == "--frames") base.frames = std::atoi(argv[++a]);
    else if (arg == "--threads") sd::parallel::set_threads(std::atoi(argv[++a]));
    else if (arg == "--float32") base.float32 = true;
    else if (arg == "--no-solve") base.solve = false;
    else {
      const size_t colon = arg.find(':');
      if (colon == std::string::npos) {
        std::fprintf(stderr, "bench_integration: expected n:segments, got '%s'\n", arg.c_str());
        return 2;
      }
      cases.emplace_back(std::atoi(arg.substr(0, colon).c_str()), std::atoi(arg.substr(colon + 1).c_str()));
    }
  }
  try {
    for (const auto& [n, segments] : cases) {
      sd::bench::IntegrationOptions o = base;
      o.n_target = n;
      o.cage_segments = segments;
      std::string json = "{";
      for (const auto& [key, value] : sd::bench::run_integration_case(o)) {
        char number[64];
        std::snprintf(number, sizeof number, "%.17g", value);
        json += (json.size() > 1 ? ", \"" : "\"") + key + "\": " + (std::isfinite(value) ? number : "null");
      }
      std::printf("%s}\n", json.c_str());
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_integration: %s\n", e.what());
    return 1;
  }
  return 0;
}
