// Stop codes: every code has its own stable snake_case name, and StepResult::finish sets converged from
// the code.
#include "core/solver/solver_types.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "test_support.h"

namespace sd {
namespace {

TEST(StopCodes, DistinctNamesAndConvergedOnlyForConvergence) {
  std::set<std::string> names;
  for (StopCode code : all_stop_codes()) {
    const std::string name = stop_code_name(code);
    EXPECT_TRUE(test::is_snake_case(name)) << name;
    EXPECT_TRUE(names.insert(name).second) << "twice: " << name;
    StepResult r;
    r.finish(code);
    EXPECT_EQ(r.stop, code);
    EXPECT_EQ(r.stop_reason, stop_code_reason(code));
    // The converged codes are exactly those whose text says so (and "no handles": nothing to solve).
    const bool says_converged = r.stop_reason.rfind("converged", 0) == 0 || code == StopCode::NoHandles;
    EXPECT_EQ(r.converged, says_converged) << name;
  }
  EXPECT_EQ(names.size(), static_cast<size_t>(StopCode::Stalled) + 1);  // the last code
  StepResult detailed;
  detailed.finish(StopCode::NumericalFailure, "numerical failure: the step is not finite");
  EXPECT_EQ(detailed.stop_reason, "numerical failure: the step is not finite");
  EXPECT_FALSE(detailed.converged);
}

}  // namespace
}  // namespace sd
