// The one table of the solver options: for every member of SolverOptions (solver_types.h) the name JS
// and scene files spell, its kind, its limits or choices and a one-line doc. The Deformer validates with
// it, the bindings convert from and to JS with it (cpp/bindings/deformer_bindings.cpp), and the build
// writes it out as the JS schema that web/lib/options.js serves to the JS API, the scene parser and the
// app. The defaults are SolverOptions{}'s. Adding an option: docs/solver.md, "Adding an option".
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/solver/solver_types.h"

namespace sd {

enum class OptionKind { Choice, Boolean, Integer, Number };

struct OptionSpec {
  const char* name;  // as JS and scene files spell it, e.g. "maxIterations"
  OptionKind kind;
  const char* doc;  // one line, for people (the docs, the app's tooltips)
  // Integer and Number: the allowed interval, ends included unless open (Integer ends are always
  // included). Every Integer range fits an int, so a value that passes converts without wrapping.
  double min;
  double max;
  bool min_open;
  bool max_open;
  std::vector<const char*> choices;  // Choice: the spellings, in the order of the enum's values
  // The member as a number: a Choice's index in `choices`, a Boolean's 0 or 1, else the value.
  double (*get)(const SolverOptions&);
  void (*set)(SolverOptions&, double);

  // What a valid value is, for messages on both sides: "an integer from 1 to 2147483647",
  // "a number in (0, 1)", "a number >= 0", "a boolean", "one of 'subspace', 'full', 'arap'".
  std::string expects() const;
  // Whether `value` (in get()'s form) is allowed: finite, in range, integral for Integer, an index of
  // `choices` for Choice, 0 or 1 for Boolean.
  bool allows(double value) const;
  // The index of `spelling` in `choices`, or -1.
  int choice_index(std::string_view spelling) const;
};

// Every option, in the order the docs and the app list them.
const std::vector<OptionSpec>& solver_option_table();
// The option named `name` (JS spelling), or nullptr.
const OptionSpec* find_solver_option(std::string_view name);

// "maxIterations must be an integer from 1 to 2147483647 (got 0)"; `got` is the offending value as text.
std::string option_error_message(const OptionSpec& spec, const std::string& got);

// Throws sd::Error (InvalidArgument) naming the first option outside its limits.
void validate_solver_options(const SolverOptions& options);

}  // namespace sd
