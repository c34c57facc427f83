// What crosses between the bindings and JS beside plain values: failures and JS callbacks.
//
// Why failures are not thrown from C++ as JS exceptions: with Emscripten's JS-based exception handling a JS
// exception unwinds the wasm frames without running their destructors. Everything those frames owned would
// leak for good: the wasm heap a half-built session holds (3.6 MB per failed Deformer.create), the emval
// handles of the call's arguments (which keep the caller's arrays alive) and the strings embind copied in.
// So a binding never throws into JS: guarded() (convert.h) catches every C++ exception, leaves the JS error
// pending here and returns normally, so every frame unwinds and frees; the module's post-js
// (js_errors.post.js) wraps every binding and throws the pending error once the call has returned.
//
// A JS callback (a progress callback) is called through call_progress, which catches what it throws: the
// thrown value itself becomes the pending error and C++ unwinds with JsCallbackThrew, so the caller gets the
// callback's own error (its class and message), and the heap is freed on the way.
#pragma once

#include <emscripten/val.h>

#include <exception>
#include <string>

#include "core/error.h"

namespace sd::bindings {

// Makes a JS Error { message, code, findings? } the error the current binding call throws when it returns.
void set_pending_js_error(ErrorCode code, const std::string& message,
                          const emscripten::val& findings = emscripten::val::undefined());

// What C++ unwinds with after a JS callback threw (its own value is already the pending error).
class JsCallbackThrew : public std::exception {
 public:
  const char* what() const noexcept override { return "a JS callback threw"; }
};

// Calls a JS progress callback with the fraction done: false when it returned false (cancel), true otherwise.
// Throws JsCallbackThrew when the callback threw.
bool call_progress(const emscripten::val& callback, double fraction);

}  // namespace sd::bindings
