// Native counterpart of the wasm benchmark cases of scripts/bench.mjs: runs cpp/tools/bench_case.h
// for each "n:segments" argument and prints one JSON object per line, so the script can compare native
// and wasm on identical code and scenes.
//
//   bench_native_cases [--repeats R] [--bind-repeats B] [--solve-repeats S] [--frames F] [--no-arap]
//                      [--exact-max-n N] [--full-max-n N] [--float32] [--threads T] 5000:24 20000:49 50000:74
//   (--threads: the core's thread pool, cpp/core/parallel; default every core)
//   bench_native_cases --bandwidth     (single-thread read bandwidth in GB/s, then exit)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "core/parallel/thread_pool.h"
#include "tools/bench_case.h"

int main(int argc, char** argv) {
  sd::bench::CaseOptions base;
  std::vector<std::pair<int, int>> cases;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto next = [&](const char* flag) {
      if (a + 1 >= argc) {
        std::fprintf(stderr, "bench_native_cases: %s needs a value\n", flag);
        std::exit(2);
      }
      return std::atoi(argv[++a]);
    };
    if (arg == "--repeats") base.repeats = next("--repeats");
    else if (arg == "--bind-repeats") base.bind_repeats = next("--bind-repeats");
    else if (arg == "--solve-repeats") base.solve_repeats = next("--solve-repeats");
    else if (arg == "--frames") base.frames = next("--frames");
    else if (arg == "--exact-max-n") base.exact_max_n = next("--exact-max-n");
    else if (arg == "--full-max-n") base.full_max_n = next("--full-max-n");
    else if (arg == "--no-arap") base.arap = false;
    else if (arg == "--float32") base.float32 = true;
    else if (arg == "--threads") sd::parallel::set_threads(next("--threads"));
    else if (arg == "--bandwidth") {
      std::printf("{\"readGBs\": %.3f}\n", sd::bench::read_bandwidth_gbs());
      return 0;
    } else {
      const size_t colon = arg.find(':');
      if (colon == std::string::npos) {
        std::fprintf(stderr, "bench_native_cases: expected n:segments, got '%s'\n", arg.c_str());
        return 2;
      }
      cases.emplace_back(std::atoi(arg.substr(0, colon).c_str()), std::atoi(arg.substr(colon + 1).c_str()));
    }
  }
  if (cases.empty()) cases = {{5000, 24}, {20000, 49}};
  try {
    for (const auto& [n, segments] : cases) {
      sd::bench::CaseOptions o = base;
      o.n_target = n;
      o.cage_segments = segments;
      const sd::bench::Results r = sd::bench::run_case(o);
      std::printf("{");
      for (size_t k = 0; k < r.size(); ++k) {
        if (std::isfinite(r[k].second)) std::printf("%s\"%s\": %.10g", k ? ", " : "", r[k].first.c_str(), r[k].second);
        else std::printf("%s\"%s\": null", k ? ", " : "", r[k].first.c_str());
      }
      std::printf("}\n");
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_native_cases: %s\n", e.what());
    return 1;
  }
  return 0;
}
