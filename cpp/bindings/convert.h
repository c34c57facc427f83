// Conversions and error handling shared by every embind file. Only this folder includes emscripten.
//   - Bulk data crosses as typed arrays: Float64Array (row-major xyz) and Uint32Array (indices), copied
//     in and out in the same call, so no JS view into wasm memory outlives a heap growth.
//   - Every C++ failure reaches JS as an Error with the C++ message (an uncaught C++ exception would
//     arrive as a bare number): wrap each binding body in `guarded`.
#pragma once

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/mesh/mesh.h"

namespace sd::bindings {

using emscripten::val;

[[noreturn]] inline void throw_js_error(const std::string& message) {
  val::global("Error").new_(message).throw_();
  __builtin_unreachable();
}

// Runs body(); any C++ exception becomes a JS Error carrying its message.
template <typename Body>
auto guarded(Body&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    throw_js_error("out of memory (the model or its cage is too large for the browser's wasm heap)");
  } catch (const std::exception& e) {
    throw_js_error(e.what());
  }
}

// Copies a JS Float64Array (or any array-like of numbers) of length 3k into a k by 3 matrix.
inline Vertices vertices_from_js(const val& array, const char* what) {
  const unsigned length = array["length"].as<unsigned>();
  if (length % 3 != 0) throw Error(std::string(what) + ": length " + std::to_string(length) + " is not a multiple of 3");
  Vertices V(length / 3, 3);
  val view(emscripten::typed_memory_view(static_cast<size_t>(length), V.data()));
  view.call<void>("set", array);
  return V;
}

// Copies a JS Uint32Array / Int32Array of length 3k into a k by 3 face matrix (range not checked here).
inline Faces faces_from_js(const val& array, const char* what) {
  const unsigned length = array["length"].as<unsigned>();
  if (length % 3 != 0) throw Error(std::string(what) + ": length " + std::to_string(length) + " is not a multiple of 3");
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
