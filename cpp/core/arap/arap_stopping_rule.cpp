#include "core/arap/arap_stopping_rule.h"

#include <cmath>

namespace sd {

std::optional<StopCode> ArapStoppingRule::after_iteration(const IterationStats& s,
                                                          const ArapStopTolerances& tolerances) {
  const double previous = last_energy_;
  last_energy_ = s.energy;
  if (s.step < tolerances.step) return StopCode::StepTolerance;
  const bool small =
      std::isfinite(previous) && s.energy <= previous && previous - s.energy <= tolerances.energy * previous;
  small_decreases_ = small && s.fallbacks == 0 ? small_decreases_ + 1 : 0;
  if (small_decreases_ >= (tolerances.accelerated ? 2 : 1)) return StopCode::ArapEnergy;
  return std::nullopt;
}

}  // namespace sd
