// Wall-clock time for the statistics the solver and the binding steps report (never for decisions: results
// must not depend on how fast the machine is).
#pragma once

#include <chrono>

namespace sd {

// Milliseconds on a steady clock since an arbitrary epoch.
inline double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Milliseconds since construction.
class Timer {
 public:
  Timer() : start_(now_ms()) {}
  double ms() const { return now_ms() - start_; }

 private:
  double start_;
};

}  // namespace sd
