// Conversions and error handling shared by every embind file. Only this folder includes emscripten, and it
// includes only the core's public headers (none under an internal/ folder).
//   - Bulk data crosses as typed arrays: Float64Array (row-major xyz) and Uint32Array (indices), copied
//     in and out in the same call, so no JS view into wasm memory outlives a heap growth.
//   - Every C++ failure reaches JS as an Error carrying { code, message } and, for a mesh that failed
//     its checks, findings (an uncaught C++ exception would arrive as a bare number): wrap each binding
//     body in `guarded`, which hands the error over only after the C++ frames have unwound
//     (js_bridge.h). web/lib/errors.js turns these into typed errors.
#pragma once

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <exception>
#include <functional>
#include <new>
#include <string>
#include <type_traits>
#include <vector>

#include "bindings/js_bridge.h"
#include "core/error.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/mesh_layout.h"
#include "core/basis/cage_coordinates.h"
#include "core/basis/mean_value_coordinates.h"

namespace sd::bindings {

using emscripten::val;

// [{ severity: 'error'|'warning'|'note', code, message }]
inline val findings_to_js(const std::vector<Finding>& findings) {
  val out = val::array();
  for (const Finding& f : findings) {
    val item = val::object();
    item.set("severity", std::string(f.severity == Severity::Error     ? "error"
                                     : f.severity == Severity::Warning ? "warning"
                                                                       : "note"));
    item.set("code", f.code);
    item.set("message", f.message);
    out.call<void>("push", item);
  }
  return out;
}

// The message of a failed allocation, wherever the module runs: the wasm heap grows to 4 GB (CMakeLists.txt), but its
// allocator takes less than 2 GiB at a time (kMaxAllocationBytes), so one large matrix (W) can fail well before.
inline const char* out_of_memory_message() {
  return "out of memory: the model or its cage is too large for the solver's wasm heap (4 GB in all, one allocation "
         "under 2 GiB)";
}

// What a failed binding returns (JS never sees it: the pending error is thrown instead).
template <typename Result>
Result failed_result() {
  if constexpr (std::is_same_v<Result, val>) return val::undefined();
  else return Result{};
}

// Runs body(); a C++ exception becomes the JS error the call throws once it has returned (js_bridge.h says
// why not before): its code, message and (MeshError) findings. A JS callback's own error stays as it was
// thrown. On failure the binding returns a default value, which JS never sees.
template <typename Body>
auto guarded(Body&& body) -> decltype(body()) {
  using Result = decltype(body());
  try {
    return body();
  } catch (const JsCallbackThrew&) {
    // The callback's value is already the pending error.
  } catch (const MeshError& e) {
    set_pending_js_error(e.code(), e.what(), findings_to_js(e.findings()));
  } catch (const Error& e) {
    set_pending_js_error(e.code(), e.what());
  } catch (const std::bad_alloc&) {
    set_pending_js_error(ErrorCode::OutOfMemory, out_of_memory_message());
  } catch (const std::exception& e) {
    set_pending_js_error(ErrorCode::Internal, e.what());
  } catch (...) {
    set_pending_js_error(ErrorCode::Internal, "an unknown C++ exception");
  }
  if constexpr (!std::is_void_v<Result>) return failed_result<Result>();
}

// The setter of a value_object field that is computed for JS (an array, a method's value, a name): embind wants
// one for every field, and nothing comes back from JS this way.
template <class T, class Field>
void to_js_only(T&, Field) {}

inline bool present(const val& v) { return !v.isUndefined() && !v.isNull(); }
inline bool is_number(const val& v) { return v.typeOf().as<std::string>() == "number"; }

// A JS value as a message shows it: numbers as JS prints them (NaN, 1e+300), anything else as JSON.
inline std::string js_text(const val& v) {
  if (is_number(v) || v.isUndefined()) return val::global("String")(v).as<std::string>();
  return val::global("JSON").call<std::string>("stringify", v);
}

// `v` as an int in [min, max], refused (naming `what` and the limits) when it is not a number, not an
// integer or out of range: checked on the double, so nothing wraps around on the way to int.
inline int integer_in(const val& v, const std::string& what, int min, int max) {
  const double x = is_number(v) ? v.as<double>() : std::nan("");
  if (!(x == std::floor(x) && x >= min && x <= max))
    throw Error(what + " must be an integer from " + std::to_string(min) + " to " + std::to_string(max) + " (got " +
                js_text(v) + ")");
  return static_cast<int>(x);
}

// A memory budget in MB (positive, finite) as bytes, saturating at what size_t holds (wasm32: 4 GB).
inline std::size_t budget_bytes(const val& megabytes) {
  const double mb = is_number(megabytes) ? megabytes.as<double>() : std::nan("");
  if (!(mb > 0) || !std::isfinite(mb))
    throw Error("memoryBudgetMB must be a positive number (got " + js_text(megabytes) + ")");
  const double bytes = mb * 1e6;
  return bytes >= double(SIZE_MAX) ? SIZE_MAX : static_cast<std::size_t>(bytes);
}

// A progress callback for the core from an optional JS function: returning false cancels.
// A throw inside it unwinds the core's frames (freeing what they hold) and reaches JS as the callback's own error.
inline std::function<bool(double)> progress_from_js(const val& callback) {
  if (callback.typeOf().as<std::string>() != "function") return {};
  return [callback](double fraction) { return call_progress(callback, fraction); };
}

// How to bind W, from JS { float32?, memoryBudgetMB? } (may be null) and an optional progress callback.
inline MvcOptions mvc_options_from_js(const val& options, const val& progress) {
  MvcOptions mvc;
  if (present(options) && options.typeOf().as<std::string>() == "object") {
    if (present(options["float32"])) mvc.single_precision = options["float32"].as<bool>();
    if (present(options["memoryBudgetMB"])) mvc.memory_budget_bytes = budget_bytes(options["memoryBudgetMB"]);
  }
  mvc.progress = progress_from_js(progress);
  return mvc;
}

// { fileVertices, fileFaces, solverVertices, solverFaces, welded, unreferenced, collapsedFaces, splitVertices,
//   pairedEdges } (mesh_layout.h)
inline val layout_stats_to_js(const LayoutStats& l) {
  val out = val::object();
  out.set("fileVertices", l.file_vertices);
  out.set("fileFaces", l.file_faces);
  out.set("solverVertices", l.solver_vertices);
  out.set("solverFaces", l.solver_faces);
  out.set("welded", l.welded);
  out.set("unreferenced", l.unreferenced);
  out.set("collapsedFaces", l.collapsed_faces);
  out.set("splitVertices", l.split_vertices);
  out.set("pairedEdges", l.paired_edges);
  return out;
}

// How the mesh is welded, from JS { weldTolerance? } (relative to the bounding-box diagonal; mesh_layout.h).
inline LayoutOptions layout_options_from_js(const val& options) {
  LayoutOptions layout;
  if (present(options) && options.typeOf().as<std::string>() == "object" && present(options["weldTolerance"])) {
    const val t = options["weldTolerance"];
    if (!is_number(t)) throw Error("weldTolerance must be a number from 0 to 0.01 (got " + js_text(t) + ")");
    layout.weld_tolerance = t.as<double>();
  }
  return layout;
}

// Which cage coordinates to bind, from JS { coordinates?: 'mvc' | 'pmvc' | 'harmonic', pmvcResolution?,
// harmonicResolution? } (may be null; the resolutions are checked by the core, which names their limits).
inline CoordinatesOptions coordinates_from_js(const val& options) {
  CoordinatesOptions coordinates;
  if (!present(options) || options.typeOf().as<std::string>() != "object") return coordinates;
  const val type = options["coordinates"];
  if (present(type)) {
    if (!type.isString()) throw Error("coordinates must be 'mvc', 'pmvc' or 'harmonic' (got " + js_text(type) + ")");
    coordinates.type = coordinate_type_from_name(type.as<std::string>());
  }
  if (present(options["pmvcResolution"]))
    coordinates.positive.resolution =
        integer_in(options["pmvcResolution"], "pmvcResolution", PositiveMvcOptions::kMinResolution,
                   PositiveMvcOptions::kMaxResolution);
  if (present(options["harmonicResolution"]))
    coordinates.harmonic.resolution =
        integer_in(options["harmonicResolution"], "harmonicResolution", 0, HarmonicOptions::kMaxResolution);
  return coordinates;
}

// What binding found, for JS: { coordinates, minWeight, minWeightRow, minWeightCol, onVertex, onFace,
// bindMs } and, by type, pmvc: { rays, hiddenFaces, clamped } or harmonic: { resolution, grid: [nx, ny, nz],
// spacing, unknowns, factorNonzeros, gridBytes, boundaryCells, unresolved, factorMs, solveMs }.
inline val coordinates_report_to_js(const CoordinatesReport& r) {
  val out = val::object();
  out.set("coordinates", std::string(coordinate_type_name(r.type)));
  out.set("minWeight", r.binding.min_weight);
  out.set("minWeightRow", r.binding.min_weight_row);
  out.set("minWeightCol", r.binding.min_weight_col);
  out.set("onVertex", r.binding.on_vertex);
  out.set("onFace", r.binding.on_face);
  out.set("bindMs", r.binding.seconds * 1e3);
  if (r.type == CoordinateType::PositiveMeanValue) {
    out.set("rays", r.positive.rays);
    out.set("hiddenFaces", r.positive.hidden_faces);
    out.set("clamped", r.positive.clamped);
  }
  if (r.type == CoordinateType::Harmonic) {
    const HarmonicReport& h = r.harmonic;
    val grid = val::array();
    for (int count : h.grid) grid.call<void>("push", count);
    out.set("resolution", h.resolution);
    out.set("grid", grid);
    out.set("spacing", h.spacing);
    out.set("unknowns", h.unknowns);
    out.set("factorNonzeros", h.factor_nonzeros);
    out.set("gridBytes", h.bytes);
    out.set("boundaryCells", h.boundary_cells);
    out.set("unresolved", h.unresolved);
    out.set("factorMs", h.factor_seconds * 1e3);
    out.set("solveMs", h.solve_seconds * 1e3);
  }
  return out;
}

// An array-like of integers (Int32Array, Uint32Array or an array of numbers) as ints in [min, max], refused
// naming `what` and the position of the first bad entry.
inline std::vector<int> ints_from_js(const val& array, const std::string& what, int min, int max) {
  if (!present(array) || !present(array["length"])) throw Error(what + " must be an array of integers");
  const unsigned length = array["length"].as<unsigned>();
  std::vector<int> out(length);
  for (unsigned k = 0; k < length; ++k) out[k] = integer_in(array[k], what + "[" + std::to_string(k) + "]", min, max);
  return out;
}

// A new Int32Array / Float64Array holding a copy.
inline val to_js(const std::vector<int>& values) {
  return val(emscripten::typed_memory_view(values.size(), values.data())).call<val>("slice");
}
inline val to_js(const Eigen::VectorXd& values) {
  return val(emscripten::typed_memory_view(static_cast<size_t>(values.size()), values.data())).call<val>("slice");
}

// Copies a JS Float64Array (or any array-like of numbers) of length 3k into a k by 3 matrix.
inline Vertices vertices_from_js(const val& array, const char* what) {
  const unsigned length = array["length"].as<unsigned>();
  if (length % 3 != 0)
    throw Error(std::string(what) + ": length " + std::to_string(length) + " is not a multiple of 3");
  Vertices V(length / 3, 3);
  val view(emscripten::typed_memory_view(static_cast<size_t>(length), V.data()));
  view.call<void>("set", array);
  return V;
}

// Copies a JS Uint32Array / Int32Array of length 3k into a k by 3 face matrix (range not checked here).
inline Faces faces_from_js(const val& array, const char* what) {
  const unsigned length = array["length"].as<unsigned>();
  if (length % 3 != 0)
    throw Error(std::string(what) + ": length " + std::to_string(length) + " is not a multiple of 3");
  Faces F(length / 3, 3);
  val view(emscripten::typed_memory_view(static_cast<size_t>(length), F.data()));
  view.call<void>("set", array);
  return F;
}

inline Mesh mesh_from_js(const val& positions, const val& indices, const char* what) {
  return Mesh{vertices_from_js(positions, what), faces_from_js(indices, what)};
}

// A new Float64Array holding a copy (safe across later heap growth).
inline val float64_array(const double* data, size_t count) {
  return val(emscripten::typed_memory_view(count, data)).call<val>("slice");
}
inline val to_js(const Vertices& V) { return float64_array(V.data(), static_cast<size_t>(V.size())); }
inline val to_js(const Faces& F) {
  std::vector<uint32_t> copy(F.data(), F.data() + F.size());
  return val(emscripten::typed_memory_view(copy.size(), copy.data())).call<val>("slice");
}

// { positions: Float64Array, indices: Uint32Array }
inline val mesh_to_js(const Mesh& mesh) {
  val out = val::object();
  out.set("positions", to_js(mesh.V));
  out.set("indices", to_js(mesh.F));
  return out;
}

// Reads a JS string or Uint8Array into bytes.
inline std::string bytes_from_js(const val& data) {
  if (data.isString()) return data.as<std::string>();
  const unsigned length = data["length"].as<unsigned>();
  std::string bytes(length, '\0');
  val view(emscripten::typed_memory_view(static_cast<size_t>(length), reinterpret_cast<uint8_t*>(bytes.data())));
  view.call<void>("set", data);
  return bytes;
}

}  // namespace sd::bindings
