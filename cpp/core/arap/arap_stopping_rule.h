// When ARAP's iterations stop (docs/method.md section 13). Local-global never raises the energy at fixed
// targets, so a decrease in [0, tolerance x E) means the linear tail has flattened: further iterations move the
// mesh by ever less. With Anderson acceleration an iteration whose extrapolation was rejected (fallbacks) is a
// plain local-global step from a point the next extrapolations may still leave quickly, so it does not count,
// and two small decreases in a row are required. The history carries over from one step(k) call to the next;
// the session forgets it (reset) when the targets, the handles or the positions change.
#pragma once

#include <limits>
#include <optional>

#include "core/solver/solver_types.h"

namespace sd {

struct ArapStopTolerances {
  double step = 0;           // a largest vertex move below this (mesh units) stops: StepTolerance
  double energy = 0;         // a relative decrease of at most this stops: ArapEnergy
  bool accelerated = false;  // Anderson acceleration is on: two such decreases in a row are needed
};

class ArapStoppingRule {
 public:
  // After an iteration (its energy, step and fallbacks): the code to stop with, or nothing to go on.
  std::optional<StopCode> after_iteration(const IterationStats& s, const ArapStopTolerances& tolerances);
  // Forgets the history: the next iteration's energy has nothing to compare with.
  void reset() { *this = ArapStoppingRule{}; }

 private:
  double last_energy_ = std::numeric_limits<double>::quiet_NaN();  // after the last iteration (NaN: none)
  int small_decreases_ = 0;  // iterations in a row that lowered it by less than the tolerance
};

}  // namespace sd
