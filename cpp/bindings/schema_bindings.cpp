// The contract between the core and JS as data, read once at build time: scripts/generate_schema.mjs
// writes it to build/wasm/solver_schema.js, which web/lib/options.js and web/lib/errors.js import (the
// page parses scenes on the main thread, where the module is not loaded).
//   solverSchema() -> { options: [{ name, kind: 'choice'|'boolean'|'integer'|'number', default, min, max,
//                                   minOpen, maxOpen, choices, doc, expects }],
//                       errorCodes: ['invalid_argument', ...],
//                       stopCodes: [{ name, converged, reason }],
//                       cageLimits: { vertices: { min, max }, resolution: { min, max } },
//                       coordinates: { types: ['mvc', ...], pmvcResolution: { min, max, default },
//                                      harmonicResolution: { min, max, default } } }  (0: chosen from the cage)
// min and max are null where unbounded; choices is [] unless the kind is 'choice'.
#include <emscripten/bind.h>

#include <cmath>
#include <string>

#include "bindings/convert.h"
#include "core/cage/cage_generation.h"
#include "core/solver/solver_options.h"

namespace sd::bindings {
namespace {

val bound(double x) { return std::isinf(x) ? val::null() : val(x); }

val option_to_js(const OptionSpec& spec, const SolverOptions& defaults) {
  static const char* const kKinds[] = {"choice", "boolean", "integer", "number"};
  val out = val::object();
  out.set("name", std::string(spec.name));
  out.set("kind", std::string(kKinds[static_cast<int>(spec.kind)]));
  const double value = spec.get(defaults);
  val choices = val::array();
  for (const char* choice : spec.choices) choices.call<void>("push", std::string(choice));
  if (spec.kind == OptionKind::Choice) out.set("default", std::string(spec.choices[static_cast<size_t>(value)]));
  else if (spec.kind == OptionKind::Boolean) out.set("default", value != 0);
  else out.set("default", value);
  const bool ranged = spec.kind == OptionKind::Integer || spec.kind == OptionKind::Number;
  out.set("min", ranged ? bound(spec.min) : val::null());
  out.set("max", ranged ? bound(spec.max) : val::null());
  out.set("minOpen", spec.min_open);
  out.set("maxOpen", spec.max_open);
  out.set("choices", choices);
  out.set("doc", std::string(spec.doc));
  out.set("expects", spec.expects());
  return out;
}

val range_to_js(int min, int max) {
  val out = val::object();
  out.set("min", min);
  out.set("max", max);
  return out;
}

val range_with_default(int min, int max, int fallback) {
  val out = range_to_js(min, max);
  out.set("default", fallback);
  return out;
}

// The cage coordinate types (basis/cage_coordinates.h) and their resolutions' limits.
val coordinates_schema() {
  val types = val::array();
  for (CoordinateType type : all_coordinate_types()) types.call<void>("push", std::string(coordinate_type_name(type)));
  val out = val::object();
  out.set("types", types);
  out.set("pmvcResolution", range_with_default(PositiveMvcOptions::kMinResolution, PositiveMvcOptions::kMaxResolution,
                                               PositiveMvcOptions{}.resolution));
  out.set("harmonicResolution", range_with_default(HarmonicOptions::kMinResolution, HarmonicOptions::kMaxResolution,
                                                   HarmonicOptions{}.resolution));
  return out;
}

val solver_schema() {
  return guarded([] {
    const SolverOptions defaults;
    val options = val::array();
    for (const OptionSpec& spec : solver_option_table()) options.call<void>("push", option_to_js(spec, defaults));
    val error_codes = val::array();
    for (ErrorCode code : all_error_codes()) error_codes.call<void>("push", std::string(error_code_name(code)));
    val stop_codes = val::array();
    for (StopCode code : all_stop_codes()) {
      val item = val::object();
      item.set("name", std::string(stop_code_name(code)));
      item.set("converged", stop_code_converged(code));
      item.set("reason", std::string(stop_code_reason(code)));
      stop_codes.call<void>("push", item);
    }
    val out = val::object();
    out.set("options", options);
    out.set("errorCodes", error_codes);
    out.set("stopCodes", stop_codes);
    val cage_limits = val::object();
    cage_limits.set("vertices", range_to_js(kMinCageVertices, kMaxCageVertices));
    cage_limits.set("resolution", range_to_js(kMinCageResolution, kMaxCageResolution));
    out.set("cageLimits", cage_limits);
    out.set("coordinates", coordinates_schema());
    return out;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(schema) { emscripten::function("solverSchema", &solver_schema); }

}  // namespace sd::bindings
