// Appended to every wasm module's JS (CMakeLists.txt: --post-js). The bindings never throw into JS while
// C++ frames are live (cpp/bindings/js_bridge.h says why): a failing binding leaves its error here and
// returns normally; the wrappers below throw it once the call has returned. Every embind function, class
// constructor and method of the module is wrapped when the runtime is up, before any caller can use it.

/** The error the binding call in progress will throw: { error }, or null. Set by js_bridge.cpp. */
var sdPendingError = null;

function sdThrowPending() {
  if (sdPendingError === null) return;
  const error = sdPendingError.error;
  sdPendingError = null;
  throw error;
}

function sdRethrowing(call) {
  const wrapped = function (...args) {
    const result = call.apply(this, args);
    sdThrowPending();
    return result;
  };
  Object.defineProperty(wrapped, 'name', { value: call.name });
  return wrapped;
}

// An embind class: its constructor (which may also fail) and its own methods.
function sdRethrowingClass(Class) {
  const prototype = Class.prototype;
  for (const key of Object.getOwnPropertyNames(prototype)) {
    const member = Object.getOwnPropertyDescriptor(prototype, key);
    if (key !== 'constructor' && typeof member.value === 'function') prototype[key] = sdRethrowing(member.value);
  }
  const Wrapped = function (...args) {
    const object = Reflect.construct(Class, args, Class);
    sdThrowPending();
    return object;
  };
  Wrapped.prototype = prototype;
  Object.setPrototypeOf(Wrapped, Class);
  Object.defineProperty(Wrapped, 'name', { value: Class.name });
  return Wrapped;
}

// Embind's own markers: a function carries argCount, a class's instances the ClassHandle methods.
function sdIsEmbindClass(value) {
  const prototype = typeof value === 'function' ? value.prototype : undefined;
  return !!prototype && typeof prototype.isDeleted === 'function' && typeof prototype.delete === 'function';
}

addOnPostRun(() => {
  for (const name of Object.keys(Module)) {
    const value = Module[name];
    if (sdIsEmbindClass(value)) Module[name] = sdRethrowingClass(value);
    else if (typeof value === 'function' && value.argCount !== undefined) Module[name] = sdRethrowing(value);
  }
});
