// The solver options table: every option is named once, its default is valid, its choices map onto the
// enums, and values outside the limits are refused with a message naming the real limit.
#include "core/solver/solver_options.h"

#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <set>
#include <string>

#include "core/error.h"

namespace sd {
namespace {

const OptionSpec& spec(const char* name) {
  const OptionSpec* s = find_solver_option(name);
  EXPECT_NE(s, nullptr) << name;
  return *s;
}

// The message validate_solver_options gives for `o`, or "" when it passes.
std::string refusal(const SolverOptions& o) {
  try {
    validate_solver_options(o);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidArgument) << e.what();
    return e.what();
  }
  return "";
}

TEST(SolverOptions, EveryOptionOnceWithAValidDefaultAndADoc) {
  const SolverOptions defaults;
  std::set<std::string> names;
  for (const OptionSpec& s : solver_option_table()) {
    EXPECT_TRUE(names.insert(s.name).second) << "twice: " << s.name;
    EXPECT_GT(std::string(s.doc).size(), 10u) << s.name;
    EXPECT_TRUE(s.allows(s.get(defaults))) << s.name << " default " << s.get(defaults) << " is not " << s.expects();
    EXPECT_EQ(find_solver_option(s.name), &s);
    if (s.kind == OptionKind::Integer) EXPECT_LE(s.max, double(INT_MAX)) << s.name;
    if (s.kind == OptionKind::Choice) EXPECT_GE(s.choices.size(), 2u) << s.name;
  }
  EXPECT_EQ(find_solver_option("maxIters"), nullptr);
  EXPECT_EQ(refusal(defaults), "");
}

// Setting a value through the table and reading it back gives it again, and lands in the member the
// solver reads (choices by the enum's order).
TEST(SolverOptions, SetAndGetRoundTripIntoTheMembers) {
  SolverOptions o;
  const OptionSpec& method = spec("method");
  method.set(o, method.choice_index("full"));
  EXPECT_EQ(o.method, Method::Full);
  method.set(o, method.choice_index("arap"));
  EXPECT_EQ(o.method, Method::Arap);
  method.set(o, method.choice_index("subspace"));
  EXPECT_EQ(o.method, Method::Subspace);
  EXPECT_EQ(method.choice_index("magic"), -1);
  const OptionSpec& jacobian = spec("jacobian");
  jacobian.set(o, jacobian.choice_index("exact"));
  EXPECT_EQ(o.jacobian, JacobianMode::Exact);
  jacobian.set(o, jacobian.choice_index("fast"));
  EXPECT_EQ(o.jacobian, JacobianMode::Fast);
  spec("volume").set(o, 0);
  EXPECT_FALSE(o.volume);
  spec("maxIterations").set(o, 7);
  EXPECT_EQ(o.max_iterations, 7);
  spec("c2").set(o, 0.25);
  EXPECT_EQ(o.armijo_c2, 0.25);
  spec("cgMemory").set(o, 3);
  EXPECT_EQ(o.cg_memory, 3);
  spec("arapEnergyTolerance").set(o, 2e-6);
  EXPECT_EQ(o.arap_energy_tolerance, 2e-6);
  for (const OptionSpec& s : solver_option_table()) {
    SolverOptions copy;
    const double value = s.get(copy);
    s.set(copy, value);
    EXPECT_EQ(s.get(copy), value) << s.name;
  }
}

TEST(SolverOptions, LimitsAreNamedAndNothingWrapsAround) {
  const OptionSpec& iterations = spec("maxIterations");
  EXPECT_EQ(iterations.expects(), "an integer from 1 to 2147483647");
  for (double bad : {0.0, -1.0, 1.5, 2147483648.0, 1e300, std::nan(""), double(INFINITY)})
    EXPECT_FALSE(iterations.allows(bad)) << bad;
  EXPECT_TRUE(iterations.allows(2147483647.0));
  EXPECT_EQ(spec("cgMemory").expects(), "an integer from 0 to 500");
  EXPECT_EQ(spec("c1").expects(), "a number in (0, 1)");
  EXPECT_EQ(spec("positionWeight").expects(), "a number in (0, 1000000]");
  EXPECT_EQ(spec("stepTolerance").expects(), "a number >= 0");
  EXPECT_EQ(spec("method").expects(), "one of 'subspace', 'full', 'arap'");
  EXPECT_EQ(spec("volume").expects(), "a boolean");
  EXPECT_FALSE(spec("stepTolerance").allows(INFINITY));
  EXPECT_FALSE(spec("c1").allows(1.0));
  EXPECT_FALSE(spec("positionWeight").allows(0.0));
  // Its square weighs the handles in N: at 1e300 it overflowed and the factor failed, blaming the basis.
  EXPECT_TRUE(spec("positionWeight").allows(1e6));
  EXPECT_FALSE(spec("positionWeight").allows(1.01e6));
  EXPECT_FALSE(spec("positionWeight").allows(1e300));

  SolverOptions o;
  o.max_iterations = 0;
  EXPECT_EQ(refusal(o), "solver options: maxIterations must be an integer from 1 to 2147483647 (got 0)");
  o = SolverOptions();
  o.cg_memory = 501;
  EXPECT_EQ(refusal(o), "solver options: cgMemory must be an integer from 0 to 500 (got 501)");
  o = SolverOptions();
  o.armijo_c1 = 1;
  EXPECT_EQ(refusal(o), "solver options: c1 must be a number in (0, 1) (got 1)");
  o = SolverOptions();
  o.merit_tolerance = std::nan("");
  EXPECT_EQ(refusal(o), "solver options: meritTolerance must be a number >= 0 (got nan)");
}

}  // namespace
}  // namespace sd
