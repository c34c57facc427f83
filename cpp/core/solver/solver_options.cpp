#include "core/solver/solver_options.h"

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "core/error.h"

namespace sd {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Above this the straightness term's rounding (w_s^2 times 1e-16 of the samples' offsets) swamps the rest of the
// energy: the full space's line search then finds no decrease at the rest pose (1e5), and the subspace's
// preconditioner stops being positive definite (1e7). The app's slider ends at 30.
constexpr double kMaxStraightnessWeight = 1000;
// w_pos^2 weighs the handle rows against the Laplacian's in N and in every product: at 1e6 the handles outweigh the
// rest 1e12 times, about as far as double precision keeps the Laplacian's digits beside them; at 1e300 the square
// overflowed and the preconditioner's factor failed, blaming the basis or a weight "not positive".
constexpr double kMaxPositionWeight = 1e6;

// Reads and writes one member of SolverOptions as a number (enums by index, bools as 0/1).
template <auto Member>
double get_member(const SolverOptions& o) {
  return static_cast<double>(o.*Member);
}
template <auto Member>
void set_member(SolverOptions& o, double value) {
  using T = std::remove_reference_t<decltype(o.*Member)>;
  if constexpr (std::is_enum_v<T>) o.*Member = static_cast<T>(static_cast<int>(value));
  else if constexpr (std::is_same_v<T, bool>) o.*Member = value != 0;
  else o.*Member = static_cast<T>(value);
}

template <auto Member>
OptionSpec choice(const char* name, std::vector<const char*> choices, const char* doc) {
  return {
      name, OptionKind::Choice, doc, 0, 0, false, false, std::move(choices), &get_member<Member>, &set_member<Member>};
}
template <auto Member>
OptionSpec boolean(const char* name, const char* doc) {
  return {name, OptionKind::Boolean, doc, 0, 1, false, false, {}, &get_member<Member>, &set_member<Member>};
}
template <auto Member>
OptionSpec integer(const char* name, int min, int max, const char* doc) {
  return {name,
          OptionKind::Integer,
          doc,
          double(min),
          double(max),
          false,
          false,
          {},
          &get_member<Member>,
          &set_member<Member>};
}
// A number in the interval from min to max; `open` ends are excluded (e.g. "(0, 1)").
enum Ends { Closed, OpenMin, OpenMax, Open };
template <auto Member>
OptionSpec number(const char* name, double min, double max, Ends ends, const char* doc) {
  return {name,
          OptionKind::Number,
          doc,
          min,
          max,
          ends == OpenMin || ends == Open,
          ends == OpenMax || ends == Open,
          {},
          &get_member<Member>,
          &set_member<Member>};
}

// Text that reads back as v, with 15 digits where they suffice (1e-12, not 9.9999999999999998e-13).
std::string number_text(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.15g", v);
  if (std::strtod(buffer, nullptr) != v) std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace

// The table. Methods and Jacobian modes are listed in the order of their enums (Method, JacobianMode).
const std::vector<OptionSpec>& solver_option_table() {
  using O = SolverOptions;
  static const std::vector<OptionSpec> table = {
      choice<&O::method>("method", {"subspace", "full", "arap"},
                         "deformation method: the cage subspace (needs a cage), the full space, or ARAP"),
      choice<&O::jacobian>("jacobian", {"exact", "fast"},
                           "Gauss-Newton step: dense reference (exact) or matrix-free PCG (fast)"),
      boolean<&O::volume>("volume", "hard volume constraint: the deformed mesh keeps its rest volume"),
      choice<&O::weighting>("weighting", {"area", "uniform"},
                            "energy terms weighted by area, so the shape is the same at every mesh resolution, or "
                            "uniformly per vertex, as in the original report"),
      choice<&O::integration>("integration", {"full", "reduced"},
                              "subspace method: sum the Laplacian term over every vertex, or by a reduced rule "
                              "(one rotation per cluster of vertices: an iteration then costs about two passes over "
                              "the basis, however large the mesh); a reduced solve finishes on every vertex"),
      number<&O::position_weight>("positionWeight", 0, kMaxPositionWeight, OpenMin,
                                  "weight of the handle positions against the Laplacian coordinates"),
      number<&O::straightness_weight>(
          "straightnessWeight", 0, kMaxStraightnessWeight, Closed,
          "skeleton: each bone's samples pulled onto the segment between its joints, each like a point handle of "
          "this weight (0: only its middle is held, where the space can; above 1000 its rounding swamps the energy)"),
      number<&O::armijo_c1>("c1", 0, 1, Open, "Armijo sufficient-decrease constant of the line search"),
      number<&O::armijo_c2>("c2", 0, 1, Open, "line-search backtracking factor: alpha <- c2 alpha"),
      integer<&O::max_iterations>("maxIterations", 1, INT_MAX, "iteration cap of a solve to convergence"),
      number<&O::step_tolerance>("stepTolerance", 0, kInf, Closed,
                                 "stop when a step moves less than this times the bounding-box diagonal"),
      number<&O::merit_tolerance>("meritTolerance", 0, kInf, Closed,
                                  "stop when the merit decreases by less than this, relatively"),
      // Below 1e-12 the PCG residual is rounding noise (its products are accurate to ~1e-16 times the condition
      // number): such a tolerance cannot be met and only wastes products.
      number<&O::cg_tolerance>("cgTolerance", 1e-12, 1, OpenMax, "fast mode: relative residual of the inner PCG"),
      integer<&O::cg_max_iterations>("cgMaxIterations", 1, INT_MAX, "fast mode: iteration cap of the inner PCG"),
      choice<&O::preconditioner>("preconditioner", {"gauss-newton", "constant"},
                                 "fast subspace mode: PCG preconditioned by W^T (L^T L + handles) W plus, where the "
                                 "products it saves pay for it, a kept factor with the stiffest vertices' rotation "
                                 "terms; or by the constant W^T (L^T L + handles) W alone"),
      integer<&O::cg_memory>("cgMemory", 0, 500,
                             "fast subspace mode: L-BFGS pairs that update the PCG preconditioner (0: none)"),
      number<&O::arap_energy_tolerance>("arapEnergyTolerance", 0, kInf, Closed,
                                        "ARAP stops when an iteration lowers its energy by less than this, relatively"),
      integer<&O::arap_acceleration>("arapAcceleration", 0, 50,
                                     "ARAP: Anderson acceleration over this many iterations (0: plain local-global)"),
      number<&O::cage_regularization>("cageRegularization", 0, 1, Closed,
                                      "cage subspace: weight of the cage's smoothness term relative to the mesh energy "
                                      "(keeps cage vertices that barely move the mesh in place; 0: off)"),
  };
  return table;
}

const OptionSpec* find_solver_option(std::string_view name) {
  for (const OptionSpec& spec : solver_option_table())
    if (name == spec.name) return &spec;
  return nullptr;
}

std::string OptionSpec::expects() const {
  switch (kind) {
    case OptionKind::Choice: {
      std::string out = "one of ";
      for (size_t i = 0; i < choices.size(); ++i) out += (i ? ", '" : "'") + std::string(choices[i]) + "'";
      return out;
    }
    case OptionKind::Boolean: return "a boolean";
    case OptionKind::Integer: return "an integer from " + number_text(min) + " to " + number_text(max);
    case OptionKind::Number:
      if (std::isinf(max) && min == 0 && min_open) return "a positive number";
      if (std::isinf(max)) return std::string("a number ") + (min_open ? "> " : ">= ") + number_text(min);
      return std::string("a number in ") + (min_open ? "(" : "[") + number_text(min) + ", " + number_text(max) +
             (max_open ? ")" : "]");
  }
  return "";
}

bool OptionSpec::allows(double value) const {
  switch (kind) {
    case OptionKind::Choice: return value == std::floor(value) && value >= 0 && value < double(choices.size());
    case OptionKind::Boolean: return value == 0 || value == 1;
    case OptionKind::Integer: return value == std::floor(value) && value >= min && value <= max;
    case OptionKind::Number:
      return std::isfinite(value) && (min_open ? value > min : value >= min) && (max_open ? value < max : value <= max);
  }
  return false;
}

int OptionSpec::choice_index(std::string_view spelling) const {
  for (size_t i = 0; i < choices.size(); ++i)
    if (spelling == choices[i]) return static_cast<int>(i);
  return -1;
}

std::string option_error_message(const OptionSpec& spec, const std::string& got) {
  return std::string(spec.name) + " must be " + spec.expects() + " (got " + got + ")";
}

void validate_solver_options(const SolverOptions& options) {
  for (const OptionSpec& spec : solver_option_table()) {
    const double value = spec.get(options);
    if (!spec.allows(value)) throw Error("solver options: " + option_error_message(spec, number_text(value)));
  }
}

}  // namespace sd
