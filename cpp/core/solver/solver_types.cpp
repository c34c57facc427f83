#include "core/solver/solver_types.h"

namespace sd {

const std::vector<StopCode>& all_stop_codes() {
  static const std::vector<StopCode> codes = {
      StopCode::NoIterations,  StopCode::NoHandles,        StopCode::StepTolerance, StopCode::NoDescent,
      StopCode::NoDecrease,    StopCode::MeritTolerance,   StopCode::ArapEnergy,    StopCode::IterationLimit,
      StopCode::MaxIterations, StopCode::NumericalFailure, StopCode::Stalled,
  };
  return codes;
}

const char* stop_code_name(StopCode code) {
  switch (code) {
    case StopCode::NoIterations: return "no_iterations";
    case StopCode::NoHandles: return "no_handles";
    case StopCode::StepTolerance: return "step_tolerance";
    case StopCode::NoDescent: return "no_descent";
    case StopCode::NoDecrease: return "no_decrease";
    case StopCode::MeritTolerance: return "merit_tolerance";
    case StopCode::ArapEnergy: return "arap_energy";
    case StopCode::IterationLimit: return "iteration_limit";
    case StopCode::MaxIterations: return "max_iterations";
    case StopCode::NumericalFailure: return "numerical_failure";
    case StopCode::Stalled: return "stalled";
  }
  return "numerical_failure";
}

const char* stop_code_reason(StopCode code) {
  switch (code) {
    case StopCode::NoIterations: return "no iterations requested";
    case StopCode::NoHandles: return "no handles: nothing to solve";
    case StopCode::StepTolerance: return "converged: step below tolerance";
    case StopCode::NoDescent: return "converged: no descent direction";
    case StopCode::NoDecrease: return "converged: the line search found no decrease above the step tolerance";
    case StopCode::MeritTolerance: return "converged: merit stopped decreasing";
    case StopCode::ArapEnergy: return "converged: ARAP energy stopped decreasing";
    case StopCode::IterationLimit: return "iteration limit of this call";
    case StopCode::MaxIterations: return "max iterations";
    case StopCode::NumericalFailure: return "numerical failure";
    case StopCode::Stalled: return "stalled: the merit cannot be lowered although the model predicts a decrease";
  }
  return "";
}

bool stop_code_converged(StopCode code) {
  switch (code) {
    case StopCode::NoHandles:
    case StopCode::StepTolerance:
    case StopCode::NoDescent:
    case StopCode::NoDecrease:
    case StopCode::MeritTolerance:
    case StopCode::ArapEnergy: return true;
    default: return false;
  }
}

}  // namespace sd
