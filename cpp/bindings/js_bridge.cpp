// The JS side of js_bridge.h. sdPendingError lives in the module's scope (js_errors.post.js declares it and
// throws it when a binding call returns); these functions are compiled into the same module.
#include "bindings/js_bridge.h"

#include <emscripten/emscripten.h>

// clang-format off
EM_JS(void, sd_set_pending_error, (const char* code, const char* message, emscripten::EM_VAL findings), {
  const error = new Error(UTF8ToString(message));
  error.code = UTF8ToString(code);
  const list = Emval.toValue(findings);
  if (list !== undefined) error.findings = list;
  sdPendingError = { error: error };
});

// 0: go on, 1: the callback returned false (cancel), 2: it threw (its value is now the pending error).
EM_JS(int, sd_call_progress, (emscripten::EM_VAL callback, double fraction), {
  try {
    return Emval.toValue(callback)(fraction) === false ? 1 : 0;
  } catch (thrown) {
    sdPendingError = { error: thrown };
    return 2;
  }
});
// clang-format on

namespace sd::bindings {

void set_pending_js_error(ErrorCode code, const std::string& message, const emscripten::val& findings) {
  sd_set_pending_error(error_code_name(code), message.c_str(), findings.as_handle());
}

bool call_progress(const emscripten::val& callback, double fraction) {
  const int status = sd_call_progress(callback.as_handle(), fraction);
  if (status == 2) throw JsCallbackThrew();
  return status == 0;
}

}  // namespace sd::bindings
